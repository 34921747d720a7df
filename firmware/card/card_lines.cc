#include "card_lines.h"

#include <array>

#include "net/acd.h"

namespace firmware {
namespace {

const char* ModeName(config::IpMode mode) {
  switch (mode) {
    case config::IpMode::kManual:
      return "manual";
    case config::IpMode::kBootp:
      return "bootp";
    case config::IpMode::kDhcp:
      return "dhcp";
  }
  return "?";
}

unsigned PrefixLength(base::Ipv4Address netmask) {
  std::uint32_t mask = netmask.HostOrder();
  unsigned bits = 0;
  while ((mask & 0x80000000U) != 0) {
    ++bits;
    mask <<= 1;
  }
  return bits;
}

}  // namespace

void DescribeAddress(const CardAddressing& addressing, TextLine& line) {
  const Ipv4Config active = addressing.active();
  std::array<std::uint8_t, net::kLastConflictDetectedSize> attribute{};
  net::EncodeLastConflictDetected(addressing.last_conflict(), attribute);
  line.Text("mode=").Text(ModeName(addressing.mode())).Text(" phase=").Text(AddressPhaseName(addressing.phase()));
  line.Text(" ip=").Ipv4(active.address).Text("/").Unsigned(PrefixLength(active.netmask));
  line.Text(" gw=").Ipv4(active.gateway).Text(" duplicate=").Text(addressing.duplicate_detected() ? "1" : "0");
  line.Text(" conflict=");
  for (const std::uint8_t byte : attribute) line.Hex(byte);
}

void DescribeIdentity(const Card& card, TextLine& line) {
  line.Text("ip=").Ipv4(card.addressing().active().address).Text(" mac=").Mac(card.mac());
}

void DescribeEndpoints(base::Ipv4Address address, TextLine& line) {
  static constexpr struct {
    const char* name;
    unsigned port;
  } kEndpoints[] = {{"modbus", 502}, {"enip", 44818}, {"enip-udp", 44818}, {"io", 2222}, {"http", 80}};
  bool first = true;
  for (const auto& endpoint : kEndpoints) {
    if (!first) line.Text(" ");
    first = false;
    line.Text(endpoint.name).Text("=").Ipv4(address).Text(":").Unsigned(endpoint.port);
  }
}

}  // namespace firmware
