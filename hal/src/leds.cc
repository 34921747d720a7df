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

}  // namespace hal
