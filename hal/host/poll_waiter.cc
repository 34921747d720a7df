#include "poll_waiter.h"

#include <cerrno>
#include <climits>
#include <ctime>

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
  // ppoll with a timespec: microsecond resolution, so an I/O production slot 1 ms away is not rounded
  // to a whole millisecond (poll's unit). The process's timer slack (set in main) bounds the lateness.
  timespec timeout{};
  const timespec* timeout_ptr = &timeout;
  if (deadline == kNever) {
    timeout_ptr = nullptr;
  } else if (deadline > now) {
    const Micros wait = deadline - now;
    constexpr Micros kMaxWait = static_cast<Micros>(INT_MAX) * kMicrosPerSecond;
    const Micros bounded = wait > kMaxWait ? kMaxWait : wait;
    timeout.tv_sec = static_cast<time_t>(bounded / kMicrosPerSecond);
    timeout.tv_nsec = static_cast<long>((bounded % kMicrosPerSecond) * 1000);
  }
  ++wait_count_;
  // EINTR (a signal) just ends the wait early; the loop runs another pass.
  const int rc = ppoll(set_.data(), static_cast<nfds_t>(set_.size()), timeout_ptr, nullptr);
  if (rc < 0) {
    for (std::size_t i = 0; i < set_.size(); ++i) set_.data()[i].revents = 0;
  }
  for (PollSource* source : sources_) source->AfterWait(set_);
}

}  // namespace hal::host
