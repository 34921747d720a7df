// The board's interrupt handlers: each driver binds itself to its NVIC line. The vector table points
// every external interrupt to one dispatcher, which calls the bound driver and, when the driver says
// the event loop has work (a frame, a byte, a deadline), sets the loop's wake flag for the Waiter.
//
// This table is the board's one piece of file-scope mutable state besides the lwIP binding: a vector
// has no context pointer, so the dispatcher must find the driver from the interrupt number alone.
#pragma once

#include "mps2_an386.h"

namespace hal::mps2 {

class InterruptHandler {
 public:
  virtual ~InterruptHandler() = default;
  // Runs in handler mode with the interrupt's line active. True: the event loop has work to do.
  virtual bool OnInterrupt() = 0;
};

// Binds `handler` (which must outlive the program) to `irq` and enables the line in the NVIC.
void BindInterrupt(Irq irq, InterruptHandler& handler);

// The NMI: the board's only source is the watchdog's first expiry. Without a handler bound, an NMI
// is a fault (Panic).
void BindNmi(InterruptHandler& handler);
void DispatchNmi();

// True when an interrupt gave the loop work since the last call. The Waiter calls it with interrupts
// masked, just before it sleeps.
bool TakeLoopWake();

// Interrupts that arrived on a line nobody bound (the line is then disabled).
unsigned UnboundInterrupts();

}  // namespace hal::mps2

extern "C" void ipe_mps2_irq_dispatch();
