#include "event_loop.h"

#include <algorithm>

#include "lwip/timeouts.h"

namespace firmware {

base::Status EventLoop::AddService(Service& service, PollWhen when) {
  if (service_count_ == services_.size()) return base::ResourceExhausted();
  when_[service_count_] = when;
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
    if (services_[i]->NextDeadline() <= now) {
      ++stats_.polls;
      services_[i]->Poll(now);
    }
  }
}

void EventLoop::PollServices(hal::Micros now, bool event) {
  if (probe_ != nullptr && probe_->TakeEvent()) event = true;
  if (event) ++stats_.event_passes;
  for (std::size_t i = 0; i < service_count_; ++i) {
    Service& service = *services_[i];
    const PollWhen when = when_[i];
    const bool due = when == PollWhen::kEveryPass || service.NextDeadline() <= now;
    if (!due && !(event && when == PollWhen::kDueOrEvent)) continue;
    ++stats_.polls;
    service.Poll(now);
    if (when == PollWhen::kEveryPass) {
      if (probe_ != nullptr && probe_->TakeEvent()) {
        if (!event) ++stats_.event_passes;
        event = true;
      }
    } else if (when == PollWhen::kDueOrEvent && !event) {
      // Polled at its deadline: whatever it changed, the services after it look at in this pass.
      ++stats_.event_passes;
      event = true;
    }
  }
}

void EventLoop::RunOnce() {
  ++stats_.passes;
  bool event = false;
  if (netif_.SyncLinkState()) {
    ++stats_.link_changes;
    event = true;
  }

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
  if (frames > 0) event = true;

  // lwIP's timers call into the services' callbacks (a retransmission given up, a TCP poll, an ARP
  // answer that releases queued output): a pass that runs one is an event like a frame.
  if (sys_timeouts_sleeptime() == 0) {
    sys_check_timeouts();
    event = true;
  }

  const hal::Micros now = clock_.NowMicros();
  PollServices(now, event);

  if (frames == kMaxFramesPerPass) {
    ++stats_.bounded_passes;
    last_deadline_ = now;
  } else {
    last_deadline_ = NextDeadline(clock_.NowMicros());
  }
  waiter_.WaitUntil(last_deadline_);
}

}  // namespace firmware
