#include "poll_waiter.h"

#include <cerrno>
#include <climits>

namespace hal::host {

std::size_t PollSet::Add(int fd, short events) {
  fds_.push_back(pollfd{fd, events, 0});
  return fds_.size() - 1;
}

short PollSet::Revents(std::size_t slot) const {
  return slot < fds_.size() ? fds_[slot].revents : 0;
}

void PollWaiter::WaitUntil(Micros deadline) {
  set_.Clear();
  for (PollSource* source : sources_) source->PrepareWait(set_, deadline);

  const Micros now = clock_.NowMicros();
  int timeout_ms = 0;
  if (deadline == kNever) {
    timeout_ms = -1;
  } else if (deadline > now) {
    // Round up: waking a little late is harmless, waking early just costs one more pass.
    const Micros ms = (deadline - now + kMicrosPerMilli - 1) / kMicrosPerMilli;
    timeout_ms = ms > static_cast<Micros>(INT_MAX) ? INT_MAX : static_cast<int>(ms);
  }
  ++wait_count_;
  // EINTR (a signal) just ends the wait early; the loop runs another pass.
  const int rc = poll(set_.data(), static_cast<nfds_t>(set_.size()), timeout_ms);
  if (rc < 0) {
    for (std::size_t i = 0; i < set_.size(); ++i) set_.data()[i].revents = 0;
  }
  for (PollSource* source : sources_) source->AfterWait(set_);
}

}  // namespace hal::host
