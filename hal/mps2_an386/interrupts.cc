#include "interrupts.h"

#include <array>
#include <atomic>
#include <cstdint>

#include "cortex_m.h"
#include "panic.h"

namespace hal::mps2 {
namespace {

std::array<InterruptHandler*, kIrqCount> g_handlers{};
std::atomic<bool> g_loop_wake{false};
std::atomic<unsigned> g_unbound{0};
InterruptHandler* g_nmi_handler = nullptr;

}  // namespace

void BindInterrupt(Irq irq, InterruptHandler& handler) {
  g_handlers[static_cast<std::size_t>(irq)] = &handler;
  EnableIrq(irq);
}

void BindNmi(InterruptHandler& handler) { g_nmi_handler = &handler; }

void DispatchNmi() {
  if (g_nmi_handler == nullptr) Panic("fault: NMI with no handler");
  g_nmi_handler->OnInterrupt();
}

bool TakeLoopWake() { return g_loop_wake.exchange(false, std::memory_order_acq_rel); }

unsigned UnboundInterrupts() { return g_unbound.load(std::memory_order_relaxed); }

}  // namespace hal::mps2

extern "C" void ipe_mps2_irq_dispatch() {
  std::uint32_t exception;
  __asm__ volatile("mrs %0, ipsr" : "=r"(exception));
  const std::uint32_t line = (exception & 0x1FFU) - 16U;
  if (line >= hal::mps2::kIrqCount) return;
  hal::mps2::InterruptHandler* handler = hal::mps2::g_handlers[line];
  if (handler == nullptr) {
    hal::mps2::DisableIrq(static_cast<hal::mps2::Irq>(line));
    hal::mps2::g_unbound.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (handler->OnInterrupt()) hal::mps2::g_loop_wake.store(true, std::memory_order_release);
}
