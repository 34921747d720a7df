#include "cmsdk_watchdog.h"

#include <cstdint>

#include "mmio.h"
#include "mps2_an386.h"
#include "panic.h"

namespace hal::mps2 {
namespace {

constexpr std::uintptr_t kWatchdog = address::kWatchdog;
constexpr std::uintptr_t kLoad = kWatchdog + 0x000;
constexpr std::uintptr_t kControl = kWatchdog + 0x008;
constexpr std::uintptr_t kIntClear = kWatchdog + 0x00C;
constexpr std::uintptr_t kLock = kWatchdog + 0xC00;
constexpr std::uint32_t kControlInterruptEnable = 1U << 0;
constexpr std::uint32_t kControlResetEnable = 1U << 1;
constexpr std::uint32_t kUnlockKey = 0x1ACCE551;

}  // namespace

void CmsdkWatchdog::Start() {
  BindNmi(*this);
  Write32(kLock, kUnlockKey);
  Write32(kLoad, static_cast<std::uint32_t>(timeout_ * kTicksPerMicro));
  Write32(kIntClear, 1);
  Write32(kControl, kControlInterruptEnable | kControlResetEnable);
  Write32(kLock, 0);
}

void CmsdkWatchdog::Feed() {
  Write32(kLock, kUnlockKey);
  Write32(kIntClear, 1);
  Write32(kLock, 0);
}

bool CmsdkWatchdog::OnInterrupt() {
  TextLine line;
  line.Text("watchdog: the loop has not fed the watchdog for ").Unsigned(timeout_ / kMicrosPerMilli);
  line.Text(" ms; reset in ").Unsigned(timeout_ / kMicrosPerMilli).Text(" ms unless it does\r\n");
  WriteConsolePolled(line.view());
  return false;
}

}  // namespace hal::mps2
