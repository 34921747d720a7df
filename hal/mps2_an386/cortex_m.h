// The parts of the Cortex-M4 core the board uses: interrupt masking, the NVIC, sleeping and reset.
#pragma once

#include <cstdint>

#include "mps2_an386.h"

namespace hal::mps2 {

// Masks every interrupt (PRIMASK) for its lifetime; nests (restores what it found).
class CriticalSection {
 public:
  CriticalSection();
  ~CriticalSection();
  CriticalSection(const CriticalSection&) = delete;
  CriticalSection& operator=(const CriticalSection&) = delete;

 private:
  std::uint32_t saved_primask_;
};

void EnableIrq(Irq irq);
void DisableIrq(Irq irq);
void ClearPendingIrq(Irq irq);

// Sleeps until an interrupt is pending. Called with interrupts masked, so that an interrupt that
// arrives between the caller's last check and the sleep still ends it (WFI wakes on a pending
// interrupt even when PRIMASK masks it); the caller unmasks afterwards and the handler runs then.
void WaitForInterruptMasked();
void MaskInterrupts();
void UnmaskInterrupts();

// SYSRESETREQ: the whole MCU and its peripherals start again from the reset vector.
[[noreturn]] void SystemReset();

}  // namespace hal::mps2
