#include "system_clock.h"

#include "cmsdk_timer_registers.h"
#include "cortex_m.h"
#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

constexpr std::uintptr_t kTimer = address::kTimer0;

}  // namespace

void SystemClock::Start() {
  Write32(kTimer + timer_reg::kCtrl, 0);
  Write32(kTimer + timer_reg::kIntStatus, 1);
  Write32(kTimer + timer_reg::kReload, 0xFFFFFFFFU);
  {
    CriticalSection masked;
    ticks_ = DownCounterTicks(Read32(kTimer + timer_reg::kValue));
  }
  Write32(kTimer + timer_reg::kCtrl, timer_reg::kCtrlEnable | timer_reg::kCtrlInterruptEnable);
  BindInterrupt(Irq::kTimer0, *this);
  started_ = true;
}

std::uint64_t SystemClock::NowTicks() const {
  if (!started_) return 0;
  CriticalSection masked;
  return ticks_.Update(Read32(kTimer + timer_reg::kValue));
}

Micros SystemClock::NowMicros() const { return NowTicks() / kTicksPerMicro; }

bool SystemClock::OnInterrupt() {
  Write32(kTimer + timer_reg::kIntStatus, 1);
  ticks_.Update(Read32(kTimer + timer_reg::kValue));
  return false;
}

}  // namespace hal::mps2
