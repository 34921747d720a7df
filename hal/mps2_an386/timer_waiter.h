// hal::Waiter on CMSDK timer 1: sleeps in WFI until the deadline (timer 1 counts the time down and
// interrupts) or until any interrupt, whichever comes first. The sleep is never longer than
// `longest_sleep`, so a card whose watchdog runs out sooner than its loop's next deadline still comes
// round to feed it (hal/watchdog.h). An interrupt that gave the loop work while it was busy (a frame, a
// byte: InterruptHandler::OnInterrupt() returned true) makes the next wait return at once, so no work
// waits for the next deadline.
#pragma once

#include <cstdint>

#include "hal/waiter.h"
#include "interrupts.h"
#include "system_clock.h"

namespace hal::mps2 {

struct WaiterCounters {
  std::uint64_t sleeps = 0;          // WFI entered
  std::uint64_t woken_early = 0;     // returned at once: work arrived while the loop was busy
};

class TimerWaiter final : public Waiter, private InterruptHandler {
 public:
  TimerWaiter(const SystemClock& clock, Micros longest_sleep) : clock_(clock), longest_sleep_(longest_sleep) {}
  TimerWaiter(const TimerWaiter&) = delete;
  TimerWaiter& operator=(const TimerWaiter&) = delete;

  void Start();
  void WaitUntil(Micros deadline) override;
  const WaiterCounters& counters() const { return counters_; }

 private:
  bool OnInterrupt() override;

  const SystemClock& clock_;
  const Micros longest_sleep_;
  WaiterCounters counters_;
};

}  // namespace hal::mps2
