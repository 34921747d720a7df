#include "card_indicators.h"

#include <array>

namespace firmware {

CardIndicators::CardIndicators(const IndicatorSources& sources, hal::Leds& leds, hal::Micros now)
    : sources_(sources), leds_(leds) {
  model_.StartPowerUpTest(now);
}

base::Status CardIndicators::Configure(const config::CardConfig& config) {
  protocol_ = config.protocol == config::Protocol::kEtherNetIp ? net::Protocol::kEtherNetIp
                                                                   : net::Protocol::kModbusTcp;
  next_change_ = 0;  // re-evaluate at once
  return base::OkStatus();
}

net::LedInputs CardIndicators::Gather() const {
  net::LedInputs in;
  in.protocol = protocol_;
  const drive_link::LinkState link = sources_.proxy.link().state();
  in.configured = sources_.proxy.config_loaded() && link != drive_link::LinkState::kFault;
  in.fault = link == drive_link::LinkState::kFault      ? net::ModuleFault::kMajor
             : link == drive_link::LinkState::kDegraded ? net::ModuleFault::kMinor
                                                        : net::ModuleFault::kNone;
  const CardAddressing& addressing = sources_.addressing;
  in.has_address = addressing.has_address();
  in.acquiring_address = addressing.acquiring();
  in.duplicate_address = addressing.duplicate_detected();
  for (std::size_t i = 0; i < sources_.port.PortCount(); ++i) {
    in.any_link_up = in.any_link_up || sources_.port.Link(static_cast<hal::PortId>(i)).up;
  }
  if (protocol_ == net::Protocol::kEtherNetIp && sources_.connections != nullptr) {
    if (sources_.connections->IoStatus() == cip::ExtendedDeviceStatus::kFaultedIoConnection) {
      in.connections = net::ConnectionState::kTimedOut;
    } else if (sources_.connections->AnyOpen()) {
      in.connections = net::ConnectionState::kEstablished;
    }
  } else if (protocol_ == net::Protocol::kModbusTcp && sources_.proxy.loss_action_active()) {
    in.connections = net::ConnectionState::kTimedOut;
  }
  return in;
}

void CardIndicators::Poll(hal::Micros now) {
  // Polled after every event of the loop; the LEDs change only with their inputs or their pattern's
  // next step, so an unchanged picture costs the comparison and nothing more.
  const net::LedInputs inputs = Gather();
  const std::uint8_t links = PortLinks();
  if (now < next_change_ && inputs == model_.Inputs() && links == port_links_) return;
  port_links_ = links;
  model_.Update(inputs, now);
  model_.Drive(leds_, now);
  DriveLinkLeds(now);
  next_change_ = model_.NextChange(now);
}

std::uint8_t CardIndicators::PortLinks() const {
  std::uint8_t links = 0;
  for (std::size_t i = 0; i < sources_.port.PortCount() && i < hal::kMaxPorts; ++i) {
    const hal::LinkState link = sources_.port.Link(static_cast<hal::PortId>(i));
    if (link.up) links = static_cast<std::uint8_t>(links | (1U << (2 * i)));
    if (link.speed == hal::LinkSpeed::k10Mbps) links = static_cast<std::uint8_t>(links | (2U << (2 * i)));
  }
  return links;
}

void CardIndicators::DriveLinkLeds(hal::Micros now) {
  static constexpr hal::Led kLedOfPort[hal::kMaxPorts] = {hal::Led::kLinkLeft, hal::Led::kLinkRight};
  const std::optional<hal::LedColor> test = model_.LinkTestColor(now);
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    hal::LedColor color = hal::LedColor::kOff;
    if (test.has_value()) {
      color = *test;
    } else if (i < sources_.port.PortCount()) {
      const hal::LinkState link = sources_.port.Link(static_cast<hal::PortId>(i));
      if (link.up) color = link.speed == hal::LinkSpeed::k10Mbps ? hal::LedColor::kYellow : hal::LedColor::kGreen;
    }
    leds_.Set(kLedOfPort[i], color);
  }
}

}  // namespace firmware
