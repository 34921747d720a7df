#include "link_leds.h"

namespace firmware {

void LinkLeds::Poll(hal::Micros /*now*/) {
  static constexpr hal::Led kLedOfPort[hal::kMaxPorts] = {hal::Led::kLinkLeft, hal::Led::kLinkRight};
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    hal::LedColor color = hal::LedColor::kOff;
    if (i < port_.PortCount()) {
      const hal::LinkState link = port_.Link(static_cast<hal::PortId>(i));
      if (link.up) color = link.speed == hal::LinkSpeed::k10Mbps ? hal::LedColor::kYellow : hal::LedColor::kGreen;
    }
    leds_.Set(kLedOfPort[i], color);
  }
}

}  // namespace firmware
