// Reset and exception entry of the mps2-an386 image: the vector table (at 0x0, where the code SSRAM
// standing for flash starts), the reset handler (paint the stack, copy .data, zero .bss, turn the FPU
// on, run the static constructors, call main) and the fault handlers (report on the console, reset).
#include <cstddef>
#include <cstdint>

#include "cortex_m.h"
#include "interrupts.h"
#include "mmio.h"
#include "panic.h"
#include "startup.h"

// Symbols of the linker script (mps2_an386.ld.in).
extern "C" {
extern std::uint32_t __data_load_start[];
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern std::uint32_t __stack_start[];
extern std::uint32_t __stack_end[];
extern void (*__preinit_array_start[])();
extern void (*__preinit_array_end[])();
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();

int main();
[[noreturn]] void Reset_Handler();
void NMI_Handler();
void HardFault_Handler();
void ipe_mps2_hard_fault(std::uint32_t* frame);
void Unexpected_Handler();
}

namespace {

constexpr std::uintptr_t kScbCpacr = 0xE000ED88;
constexpr std::uintptr_t kScbVtor = 0xE000ED08;
constexpr std::uintptr_t kScbCfsr = 0xE000ED28;
constexpr std::uintptr_t kScbHfsr = 0xE000ED2C;
constexpr std::uintptr_t kScbMmfar = 0xE000ED34;
constexpr std::uintptr_t kScbBfar = 0xE000ED38;
constexpr std::uint32_t kHfsrDebugEvent = 1U << 31;  // a BKPT without a debugger (the architecture)
constexpr std::uint32_t kHfsrForced = 1U << 30;      // ... as QEMU reports it (DebugMonitor escalated)
constexpr std::uint16_t kSemihostingBreakpoint = 0xBEAB;  // BKPT 0xAB

bool g_semihosting_trapped = false;

union Vector {
  void (*handler)();
  const void* stack_top;
};

}  // namespace

// 16 system exceptions, then the 32 external interrupts of the AN386 image, all to one dispatcher.
__attribute__((section(".isr_vector"), used)) const Vector g_vectors[16 + hal::mps2::kIrqCount] = {
    {.stack_top = __stack_end},
    {.handler = Reset_Handler},
    {.handler = NMI_Handler},
    {.handler = HardFault_Handler},
    {.handler = Unexpected_Handler},  // MemManage (not enabled: escalates to HardFault)
    {.handler = Unexpected_Handler},  // BusFault
    {.handler = Unexpected_Handler},  // UsageFault
    {.handler = nullptr},
    {.handler = nullptr},
    {.handler = nullptr},
    {.handler = nullptr},
    {.handler = Unexpected_Handler},  // SVCall
    {.handler = Unexpected_Handler},  // DebugMonitor
    {.handler = nullptr},
    {.handler = Unexpected_Handler},  // PendSV
    {.handler = Unexpected_Handler},  // SysTick
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
    {.handler = ipe_mps2_irq_dispatch}, {.handler = ipe_mps2_irq_dispatch},
};

extern "C" void Reset_Handler() {
  // Paint the main stack below the few words this function uses, so MainStackUsage() can tell later
  // how deep it has ever been.
  std::uintptr_t sp;
  __asm__ volatile("mov %0, sp" : "=r"(sp));
  for (std::uint32_t* word = __stack_start; reinterpret_cast<std::uintptr_t>(word) < sp - 64; ++word) {
    *word = hal::mps2::kStackPaint;
  }
  for (std::uint32_t *from = __data_load_start, *to = __data_start; to < __data_end;) *to++ = *from++;
  for (std::uint32_t* word = __bss_start; word < __bss_end;) *word++ = 0;
  // CP10 and CP11 (the FPU) full access: the image is built for the hard-float ABI.
  hal::mps2::Write32(kScbCpacr, hal::mps2::Read32(kScbCpacr) | (0xFU << 20));
  hal::mps2::Write32(kScbVtor, reinterpret_cast<std::uintptr_t>(g_vectors));
  __asm__ volatile("dsb\n\tisb" : : : "memory");
  for (auto** init = __preinit_array_start; init < __preinit_array_end; ++init) (*init)();
  for (auto** init = __init_array_start; init < __init_array_end; ++init) (*init)();
  // This is the C run-time's job, which ISO C++ does not let a program do.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
  main();
#pragma GCC diagnostic pop
  // main never returns on a card; should it, start again.
  hal::mps2::SystemReset();
}

extern "C" void NMI_Handler() {
  // The only NMI source of the board is the watchdog's first expiry (cmsdk_watchdog.h).
  hal::mps2::DispatchNmi();
}

// Passes the stacked exception frame (r0-r3, r12, lr, pc, xPSR) of whichever stack was in use.
extern "C" __attribute__((naked)) void HardFault_Handler() {
  __asm__ volatile(
      "tst lr, #4\n\t"
      "ite eq\n\t"
      "mrseq r0, msp\n\t"
      "mrsne r0, psp\n\t"
      "b ipe_mps2_hard_fault\n\t");
}

extern "C" void ipe_mps2_hard_fault(std::uint32_t* frame) {
  const std::uint32_t pc = frame[6];
  const std::uint32_t hfsr = hal::mps2::Read32(kScbHfsr);
  // A semihosting call without an emulator or debugger to serve it: return -1 from it and go on.
  if ((hfsr & (kHfsrDebugEvent | kHfsrForced)) != 0 &&
      *reinterpret_cast<const std::uint16_t*>(pc) == kSemihostingBreakpoint) {
    g_semihosting_trapped = true;
    frame[0] = 0xFFFFFFFFU;
    frame[6] = pc + 2;
    hal::mps2::Write32(kScbHfsr, hfsr & (kHfsrDebugEvent | kHfsrForced));
    return;
  }
  hal::TextLine line;
  line.Text("fault: HardFault pc=");
  hal::mps2::AppendHex32(line, pc);
  line.Text(" lr=");
  hal::mps2::AppendHex32(line, frame[5]);
  line.Text(" cfsr=");
  hal::mps2::AppendHex32(line, hal::mps2::Read32(kScbCfsr));
  line.Text(" hfsr=");
  hal::mps2::AppendHex32(line, hfsr);
  line.Text(" bfar=");
  hal::mps2::AppendHex32(line, hal::mps2::Read32(kScbBfar));
  line.Text(" mmfar=");
  hal::mps2::AppendHex32(line, hal::mps2::Read32(kScbMmfar));
  hal::mps2::Panic(line.view());
}

extern "C" void Unexpected_Handler() {
  std::uint32_t exception;
  __asm__ volatile("mrs %0, ipsr" : "=r"(exception));
  hal::TextLine line;
  line.Text("fault: unexpected exception ").Unsigned(exception & 0x1FFU);
  hal::mps2::Panic(line.view());
}

namespace hal::mps2 {

StackUsage MainStackUsage() {
  const auto bottom = reinterpret_cast<std::uintptr_t>(__stack_start);
  const auto top = reinterpret_cast<std::uintptr_t>(__stack_end);
  const std::uint32_t* word = __stack_start;
  while (reinterpret_cast<std::uintptr_t>(word) < top && *word == kStackPaint) ++word;
  return StackUsage{.size = top - bottom, .high_water = top - reinterpret_cast<std::uintptr_t>(word)};
}

bool SemihostingTrapped() { return g_semihosting_trapped; }

}  // namespace hal::mps2
