// hal::Leds that remembers the colour each LED shows and passes every change on: the web page reports
// the LEDs as a person in front of the card would see them, whatever backend drives them.
#pragma once

#include <array>

#include "hal/leds.h"

namespace firmware {

class LedMirror final : public hal::Leds {
 public:
  explicit LedMirror(hal::Leds& leds) : leds_(leds) {}
  void Set(hal::Led led, hal::LedColor color) override {
    current_[hal::LedIndex(led)] = color;
    leds_.Set(led, color);
  }
  hal::LedColor Current(hal::Led led) const { return current_[hal::LedIndex(led)]; }

 private:
  hal::Leds& leds_;
  std::array<hal::LedColor, hal::kLedCount> current_{};
};

}  // namespace firmware
