// The card's indicators (§2.4 of the IPE002Z manual): LNK per port, MS (module status), NS (network
// status). This interface sets one colour at a time; flashing patterns are made by the firmware's LED
// state model calling Set() at the right instants, so the HAL stays trivial and the timing testable.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hal/clock.h"
#include "hal/text_line.h"

namespace hal {

enum class Led : std::uint8_t { kLinkLeft = 0, kLinkRight, kModuleStatus, kNetworkStatus };
inline constexpr std::size_t kLedCount = 4;

enum class LedColor : std::uint8_t { kOff = 0, kGreen, kRed, kYellow };

constexpr std::size_t LedIndex(Led led) { return static_cast<std::size_t>(led); }
const char* LedName(Led led);
const char* LedColorName(LedColor color);

// The text every backend gives an LED change (host: its log; a board: its console), so that a test or a
// person reads the same line from both: "led MS green t=123456" (t: µs on the card's clock).
void DescribeLedChange(Led led, LedColor color, Micros at, TextLine& line);
// Every LED on one line: "LNK-L=green LNK-R=off MS=green NS=off".
void DescribeLeds(const std::array<LedColor, kLedCount>& colors, TextLine& line);

class Leds {
 public:
  virtual ~Leds() = default;
  virtual void Set(Led led, LedColor color) = 0;
};

}  // namespace hal
