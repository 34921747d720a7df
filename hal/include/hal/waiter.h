// Idle wait of the event loop.
//
// Contract: WaitUntil(deadline) returns when `deadline` (on hal::Clock) has passed or when any device
// of the HAL may have work (a frame, a serial byte, a control command), whichever comes first. It may
// return early without cause; the loop simply runs another pass. It returns at once when the deadline
// is already past. This is where a host process sleeps in poll() and a microcontroller in WFI.
#pragma once

#include "hal/clock.h"

namespace hal {

class Waiter {
 public:
  virtual ~Waiter() = default;
  virtual void WaitUntil(Micros deadline) = 0;
};

}  // namespace hal
