// hal::Watchdog on the CMSDK APB watchdog (ARM DDI0479C; QEMU hw/watchdog/cmsdk-apb-watchdog.c).
//
// The counter runs down from LOAD at 25 MHz. Its first expiry raises the watchdog interrupt, which
// the AN386 image wires to the NMI: this backend then writes one warning line to the console (polled)
// and lets it run on. Its second expiry, one more `timeout` later with the interrupt still pending,
// resets the MCU (RESEN). Feed() clears the interrupt and reloads the counter. The registers are locked
// (WDOGLOCK) between accesses, so a stray write cannot stop it.
//
// So a loop that stops feeding is reset 2 x timeout after its last feed, and the Waiter must wake the
// loop within `timeout` (TimerWaiter's longest_sleep) so that an idle card is never reset.
#pragma once

#include "hal/clock.h"
#include "hal/watchdog.h"
#include "interrupts.h"

namespace hal::mps2 {

class CmsdkWatchdog final : public Watchdog, private InterruptHandler {
 public:
  explicit CmsdkWatchdog(Micros timeout) : timeout_(timeout) {}
  CmsdkWatchdog(const CmsdkWatchdog&) = delete;
  CmsdkWatchdog& operator=(const CmsdkWatchdog&) = delete;

  // Starts counting (once started, only a reset stops it).
  void Start();
  void Feed() override;
  Micros timeout() const { return timeout_; }

 private:
  bool OnInterrupt() override;

  const Micros timeout_;
};

}  // namespace hal::mps2
