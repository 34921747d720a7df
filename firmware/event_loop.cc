#include "event_loop.h"

#include <algorithm>

#include "lwip/timeouts.h"

namespace firmware {

base::Status EventLoop::AddService(Service& service) {
  if (service_count_ == services_.size()) return base::ResourceExhausted();
  services_[service_count_++] = &service;
  return base::OkStatus();
}

hal::Micros EventLoop::NextDeadline(hal::Micros now) const {
  hal::Micros deadline = hal::kNever;
  const u32_t lwip_sleep_ms = sys_timeouts_sleeptime();
  if (lwip_sleep_ms != SYS_TIMEOUTS_SLEEPTIME_INFINITE) {
    // lwIP counts whole milliseconds of sys_now(); waking at now + n ms lands in the millisecond in
    // which its timer is due, never before it.
    deadline = now + static_cast<hal::Micros>(lwip_sleep_ms) * hal::kMicrosPerMilli;
  }
  for (std::size_t i = 0; i < service_count_; ++i) {
    deadline = std::min(deadline, services_[i]->NextDeadline());
  }
  return deadline;
}

void EventLoop::PollDue(hal::Micros now) {
  for (std::size_t i = 0; i < service_count_; ++i) {
    if (services_[i]->NextDeadline() <= now) services_[i]->Poll(now);
  }
}

void EventLoop::RunOnce() {
  ++stats_.passes;
  if (netif_.SyncLinkState()) ++stats_.link_changes;

  // Frames in batches; after each full batch the services whose deadline has passed run at once, so
  // an I/O production slot waits for at most one batch of requests, not for a whole pass.
  std::size_t frames = 0;
  while (frames < kMaxFramesPerPass) {
    const std::size_t batch = std::min(kFramesPerBatch, kMaxFramesPerPass - frames);
    const std::size_t taken = netif_.PumpReceive(batch);
    frames += taken;
    if (taken < batch || frames == kMaxFramesPerPass) break;
    PollDue(clock_.NowMicros());
  }
  stats_.frames_in += frames;

  sys_check_timeouts();

  const hal::Micros now = clock_.NowMicros();
  for (std::size_t i = 0; i < service_count_; ++i) services_[i]->Poll(now);

  if (frames == kMaxFramesPerPass) {
    ++stats_.bounded_passes;
    last_deadline_ = now;
  } else {
    last_deadline_ = NextDeadline(clock_.NowMicros());
  }
  waiter_.WaitUntil(last_deadline_);
}

}  // namespace firmware
