// LNK LEDs (§2.4): green = link at 100 Mbit/s, yellow = link at 10 Mbit/s, off = no link.
// Activity blinking and the power-up test belong to the LED state model of the indicator work.
#pragma once

#include "event_loop.h"
#include "hal/frame_port.h"
#include "hal/leds.h"

namespace firmware {

class LinkLeds final : public Service {
 public:
  LinkLeds(const hal::FramePort& port, hal::Leds& leds) : port_(port), leds_(leds) {}
  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return hal::kNever; }

 private:
  const hal::FramePort& port_;
  hal::Leds& leds_;
};

}  // namespace firmware
