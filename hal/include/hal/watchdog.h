// Watchdog: resets the card when the firmware stops feeding it (a hung event loop, a runaway handler).
//
// Contract: Feed() restarts the countdown and costs a few register writes. The event loop feeds it
// once per pass; a backend whose timeout is shorter than the loop's longest sleep must bound that
// sleep itself (its Waiter returns early), so an idle card is never reset. What happens when it
// expires is the backend's: a board resets the MCU; the host has no watchdog (a hung process is the
// supervisor's business).
#pragma once

namespace hal {

class Watchdog {
 public:
  virtual ~Watchdog() = default;
  virtual void Feed() = 0;
};

}  // namespace hal
