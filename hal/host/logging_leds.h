// hal::Leds on the host: remembers each LED's colour and a bounded history of changes, and logs every
// change as one text line, so that a test or a person can see the indicator patterns the firmware's LED
// state model produces (flash rates, power-up test sequence) without hardware.
#pragma once

#include <array>
#include <cstddef>
#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <string_view>

#include "hal/clock.h"
#include "hal/leds.h"

namespace hal::host {

struct LedChange {
  Micros at = 0;
  Led led = Led::kLinkLeft;
  LedColor color = LedColor::kOff;
  bool operator==(const LedChange&) const = default;
};

class LoggingLeds final : public Leds {
 public:
  // Receives one line per change, without a newline: "led MS green t=123456" (t in µs on the clock).
  using LineSink = std::function<void(std::string_view line)>;
  // Enough for several seconds of every LED flashing at the fastest rate the firmware uses.
  static constexpr std::size_t kHistoryCapacity = 1024;

  // All LEDs start off. Changes are logged to `sink`, or as lines to `log` (flushed at once, so a
  // `tail -f` follows live); without either (or with nullptr) nothing is logged.
  explicit LoggingLeds(const Clock& clock) : LoggingLeds(clock, LineSink()) {}
  LoggingLeds(const Clock& clock, std::FILE* log) : LoggingLeds(clock, FileSink(log)) {}
  LoggingLeds(const Clock& clock, LineSink sink);
  // A sink that writes each line plus '\n' to `file` and flushes it; an empty sink for nullptr.
  static LineSink FileSink(std::FILE* file);

  // hal::Leds. Setting the colour an LED already shows is not a change: it is neither logged nor kept.
  void Set(Led led, LedColor color) override;

  LedColor Current(Led led) const { return current_[LedIndex(led)]; }
  // The last kHistoryCapacity changes, oldest first.
  const std::deque<LedChange>& History() const { return history_; }
  // All LEDs on one line for the control socket: "LNK-L=green LNK-R=off MS=green NS=off".
  std::string Describe() const;

 private:
  const Clock& clock_;
  LineSink sink_;
  std::array<LedColor, kLedCount> current_{};
  std::deque<LedChange> history_;
};

}  // namespace hal::host
