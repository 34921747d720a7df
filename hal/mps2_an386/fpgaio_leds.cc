#include "fpgaio_leds.h"

#include <cstdint>

#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

constexpr std::uintptr_t kLed0 = address::kFpgaIo + 0x00;

}  // namespace

void FpgaioLeds::Set(Led led, LedColor color) {
  if (LedIndex(led) >= kLedCount || colors_[LedIndex(led)] == color) return;
  colors_[LedIndex(led)] = color;
  const bool ms = colors_[LedIndex(Led::kModuleStatus)] != LedColor::kOff;
  const bool ns = colors_[LedIndex(Led::kNetworkStatus)] != LedColor::kOff;
  Write32(kLed0, (ms ? 1U : 0U) | (ns ? 2U : 0U));
  TextLine line;
  DescribeLedChange(led, color, clock_.NowMicros(), line);
  line.Text("\n");
  console_.Write(line.view());
}

}  // namespace hal::mps2
