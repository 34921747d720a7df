#include "hal/leds.h"

namespace hal {

const char* LedName(Led led) {
  switch (led) {
    case Led::kLinkLeft: return "LNK-L";
    case Led::kLinkRight: return "LNK-R";
    case Led::kModuleStatus: return "MS";
    case Led::kNetworkStatus: return "NS";
  }
  return "?";
}

const char* LedColorName(LedColor color) {
  switch (color) {
    case LedColor::kOff: return "off";
    case LedColor::kGreen: return "green";
    case LedColor::kRed: return "red";
    case LedColor::kYellow: return "yellow";
  }
  return "?";
}

void DescribeLedChange(Led led, LedColor color, Micros at, TextLine& line) {
  line.Text("led ").Text(LedName(led)).Text(" ").Text(LedColorName(color)).Text(" t=").Unsigned(at);
}

void DescribeLeds(const std::array<LedColor, kLedCount>& colors, TextLine& line) {
  for (std::size_t i = 0; i < kLedCount; ++i) {
    if (i != 0) line.Text(" ");
    line.Text(LedName(static_cast<Led>(i))).Text("=").Text(LedColorName(colors[i]));
  }
}

}  // namespace hal
