#include "cortex_m.h"

#include "mmio.h"

namespace hal::mps2 {
namespace {

constexpr std::uintptr_t kNvicIser = 0xE000E100;  // set-enable, one bit per interrupt
constexpr std::uintptr_t kNvicIcer = 0xE000E180;  // clear-enable
constexpr std::uintptr_t kNvicIcpr = 0xE000E280;  // clear-pending
constexpr std::uintptr_t kScbAircr = 0xE000ED0C;
constexpr std::uint32_t kAircrVectKey = 0x05FAU << 16;
constexpr std::uint32_t kAircrPriorityGroup = 7U << 8;
constexpr std::uint32_t kAircrSysResetReq = 1U << 2;

std::uint32_t IrqBit(Irq irq) { return 1U << (static_cast<std::uint32_t>(irq) & 31U); }

}  // namespace

CriticalSection::CriticalSection() {
  std::uint32_t primask;
  __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask) : : "memory");
  saved_primask_ = primask;
}

CriticalSection::~CriticalSection() { __asm__ volatile("msr primask, %0" : : "r"(saved_primask_) : "memory"); }

void EnableIrq(Irq irq) { Write32(kNvicIser, IrqBit(irq)); }
void DisableIrq(Irq irq) {
  Write32(kNvicIcer, IrqBit(irq));
  __asm__ volatile("dsb\n\tisb" : : : "memory");
}
void ClearPendingIrq(Irq irq) { Write32(kNvicIcpr, IrqBit(irq)); }

void WaitForInterruptMasked() { __asm__ volatile("dsb\n\twfi" : : : "memory"); }
void MaskInterrupts() { __asm__ volatile("cpsid i" : : : "memory"); }
void UnmaskInterrupts() { __asm__ volatile("cpsie i\n\tisb" : : : "memory"); }

void SystemReset() {
  __asm__ volatile("dsb" : : : "memory");
  Write32(kScbAircr, kAircrVectKey | (Read32(kScbAircr) & kAircrPriorityGroup) | kAircrSysResetReq);
  __asm__ volatile("dsb" : : : "memory");
  for (;;) __asm__ volatile("wfi");
}

}  // namespace hal::mps2
