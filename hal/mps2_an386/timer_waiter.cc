#include "timer_waiter.h"

#include <algorithm>

#include "cmsdk_timer_registers.h"
#include "cortex_m.h"
#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

constexpr std::uintptr_t kTimer = address::kTimer1;

void StopDeadlineTimer() {
  Write32(kTimer + timer_reg::kCtrl, 0);
  Write32(kTimer + timer_reg::kIntStatus, 1);
  ClearPendingIrq(Irq::kTimer1);
}

}  // namespace

void TimerWaiter::Start() {
  StopDeadlineTimer();
  BindInterrupt(Irq::kTimer1, *this);
}

void TimerWaiter::WaitUntil(Micros deadline) {
  const Micros now = clock_.NowMicros();
  if (deadline <= now) return;
  // A wait of at least one tick; at most longest_sleep_ (well below 2^32 ticks).
  const Micros sleep = std::min(deadline - now, longest_sleep_);
  const auto ticks = static_cast<std::uint32_t>(std::max<Micros>(sleep * kTicksPerMicro, 1));

  MaskInterrupts();
  if (TakeLoopWake()) {
    UnmaskInterrupts();
    ++counters_.woken_early;
    return;
  }
  Write32(kTimer + timer_reg::kCtrl, 0);
  Write32(kTimer + timer_reg::kIntStatus, 1);
  Write32(kTimer + timer_reg::kReload, ticks);
  Write32(kTimer + timer_reg::kCtrl, timer_reg::kCtrlEnable | timer_reg::kCtrlInterruptEnable);
  ++counters_.sleeps;
  WaitForInterruptMasked();
  // Whatever woke the core, the deadline timer has done its job (or is no longer needed).
  StopDeadlineTimer();
  UnmaskInterrupts();  // the handlers of whatever is pending run here
  // The pass that follows does their work; a handler that runs during that pass sets the flag again.
  TakeLoopWake();
}

bool TimerWaiter::OnInterrupt() {
  // Only reached when the deadline passes while the loop is not waiting; the next wait is due anyway.
  StopDeadlineTimer();
  return true;
}

}  // namespace hal::mps2
