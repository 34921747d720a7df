#include "event_loop.h"

#include <algorithm>

#include "lwip/timeouts.h"

namespace firmware {

base::Status EventLoop::AddService(Service& service, PollWhen when) {
  if (service_count_ == services_.size()) return base::ResourceExhausted();
  when_[service_count_] = when;
  deadlines_[service_count_] = 0;
  polled_once_[service_count_] = false;
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
  for (std::size_t i = 0; i < service_count_; ++i) deadline = std::min(deadline, deadlines_[i]);
  return deadline;
}

void EventLoop::PollDue(hal::Micros now) {
  for (std::size_t i = 0; i < service_count_; ++i) {
    // Frames came in: any service's deadline may have moved (a connection opened).
    deadlines_[i] = services_[i]->NextDeadline();
    if (deadlines_[i] <= now) {
      ++stats_.polls;
      services_[i]->Poll(now);
      deadlines_[i] = services_[i]->NextDeadline();
    }
  }
}

void EventLoop::PollServices(hal::Micros now, bool event) {
  // The probe is asked after the kEveryPass services only: what the others change in the drive link
  // (an access refused at once) reaches them when the drive link has run.
  // The services before the one whose poll raised the event did not see it: their deadlines are read
  // again at the end of the pass.
  std::size_t unseen = event ? 0 : service_count_;
  for (std::size_t i = 0; i < service_count_; ++i) {
    Service& service = *services_[i];
    const PollWhen when = when_[i];
    const bool woken = event && when == PollWhen::kDueOrEvent;
    // An event may have moved the deadline of a service it does not wake (an I/O slot scheduled by a
    // Forward_Open); one it wakes reports its deadline after the poll.
    if (event && when == PollWhen::kDueOnly) deadlines_[i] = service.NextDeadline();
    const bool due = when == PollWhen::kEveryPass || deadlines_[i] <= now || !polled_once_[i];
    polled_once_[i] = true;
    if (!due && !woken) continue;
    ++stats_.polls;
    service.Poll(now);
    deadlines_[i] = service.NextDeadline();
    if (event) continue;
    // A drive-link event, or a service polled at its deadline: what it changed, the services after
    // it look at in this pass.
    if ((when == PollWhen::kEveryPass && probe_ != nullptr && probe_->TakeEvent()) ||
        when == PollWhen::kDueOrEvent) {
      event = true;
      unseen = i;
    }
  }
  if (!event) return;
  ++stats_.event_passes;
  for (std::size_t i = 0; i < unseen; ++i) deadlines_[i] = services_[i]->NextDeadline();
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
