// hal::Leds on the MPS2: the FPGA I/O block's two user LEDs (LED0 bit 0: MS lit, bit 1: NS lit, in
// any colour; the board has no coloured or link LEDs), and one console line per change, in the host's
// format ("led MS green t=123456", hal::DescribeLedChange), which carries the colours and LNK.
#pragma once

#include <array>

#include "hal/clock.h"
#include "hal/console.h"
#include "hal/leds.h"

namespace hal::mps2 {

class FpgaioLeds final : public Leds {
 public:
  FpgaioLeds(const Clock& clock, ConsoleOutput& console) : clock_(clock), console_(console) {}

  // Setting the colour an LED already shows is not a change: neither written nor logged.
  void Set(Led led, LedColor color) override;
  const std::array<LedColor, kLedCount>& colors() const { return colors_; }

 private:
  const Clock& clock_;
  ConsoleOutput& console_;
  std::array<LedColor, kLedCount> colors_{};
};

}  // namespace hal::mps2
