#include "card_lldp.h"

namespace firmware {
namespace {

constexpr std::uint8_t kAddressFamilyIpv4 = 1;

}  // namespace

CardLldp::CardLldp(CardNetif& netif, const CardAddressing& addressing, const hal::Clock& clock,
                   std::string_view system_description)
    : netif_(netif),
      addressing_(addressing),
      clock_(clock),
      agent_({.mac = netif.port().Mac(), .product = "IPE002Z", .system_description = system_description}, *this) {}

base::Status CardLldp::Configure(const config::CardConfig& config) {
  agent_.SetSystemName(std::string_view(config.device_name.data()));
  return base::OkStatus();
}

void CardLldp::Poll(hal::Micros now) {
  const hal::FramePort& port = netif_.port();
  for (std::size_t i = 0; i < net::kLldpPorts; ++i) {
    const bool up = i < port.PortCount() && port.Link(static_cast<hal::PortId>(i)).up;
    if (up == up_[i]) continue;
    up_[i] = up;
    if (up) {
      agent_.LinkUp(i, now);
    } else {
      agent_.LinkDown(i);
    }
  }
  agent_.SetManagementAddress(addressing_.active().address);
  agent_.Poll(now);
}

bool CardLldp::TakeFrame(hal::PortId port, std::span<const std::uint8_t> frame) {
  // Every frame for the card passes here (each O->T datagram, each Modbus request): the two-field test
  // first, not the clock and a parse into a 150-byte neighbour record.
  if (!net::IsLldpFrame(frame)) return false;
  return agent_.OnFrame(hal::PortIndex(port), frame, clock_.NowMicros());
}

void CardLldp::SendLldp(std::size_t port, std::span<const std::uint8_t> frame) {
  // A port that refused the frame sends the next one at the interval, like any lost frame.
  netif_.SendFrameOn(static_cast<hal::PortId>(port), frame);
}

void DescribeLldpText(std::span<const std::uint8_t> text, hal::TextLine& line) {
  for (const std::uint8_t byte : text) {
    const char c = byte > 0x20 && byte < 0x7F ? static_cast<char>(byte) : '_';
    line.Text(std::string_view(&c, 1));
  }
}

void DescribeLldpId(const net::LldpId& id, bool chassis, hal::TextLine& line) {
  const std::span<const std::uint8_t> bytes = id.id.view();
  const std::uint8_t mac = chassis ? net::kLldpChassisMac : net::kLldpPortMac;
  const std::uint8_t address = chassis ? net::kLldpChassisNetworkAddress : net::kLldpPortNetworkAddress;
  if (id.subtype == mac && bytes.size() == base::MacAddress::kSize) {
    line.Mac(base::MacAddress(bytes[0], bytes[1], bytes[2], bytes[3], bytes[4], bytes[5]));
  } else if (id.subtype == address && bytes.size() == 5 && bytes[0] == kAddressFamilyIpv4) {
    line.Ipv4(base::Ipv4Address(bytes[1], bytes[2], bytes[3], bytes[4]));
  } else {
    DescribeLldpText(bytes, line);
  }
}

}  // namespace firmware
