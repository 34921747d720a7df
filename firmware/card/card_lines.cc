#include "card_lines.h"

#include "net/acd.h"

namespace firmware {
namespace {

const char* ModeName(drive_link::IpMode mode) {
  switch (mode) {
    case drive_link::IpMode::kManual:
      return "manual";
    case drive_link::IpMode::kBootp:
      return "bootp";
    case drive_link::IpMode::kDhcp:
      return "dhcp";
  }
  return "?";
}

unsigned PrefixLength(std::uint32_t mask) {
  unsigned bits = 0;
  while ((mask & 0x80000000U) != 0) {
    ++bits;
    mask <<= 1;
  }
  return bits;
}

}  // namespace

TextLine& TextLine::Text(std::string_view text) {
  for (const char c : text) {
    if (length_ == text_.size()) {
      truncated_ = true;
      break;
    }
    text_[length_++] = c;
  }
  return *this;
}

TextLine& TextLine::Unsigned(std::uint64_t value) {
  char digits[20];
  std::size_t count = 0;
  do {
    digits[count++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (count > 0) Text(std::string_view(&digits[--count], 1));
  return *this;
}

TextLine& TextLine::Hex(std::uint8_t byte) {
  static constexpr char kDigits[] = "0123456789abcdef";
  const char pair[2] = {kDigits[byte >> 4], kDigits[byte & 0x0F]};
  return Text(std::string_view(pair, 2));
}

TextLine& TextLine::Ipv4(std::uint32_t host_order) {
  for (int shift = 24; shift >= 0; shift -= 8) {
    Unsigned((host_order >> shift) & 0xFF);
    if (shift != 0) Text(".");
  }
  return *this;
}

TextLine& TextLine::Mac(const hal::MacAddress& mac) {
  for (std::size_t i = 0; i < mac.size(); ++i) {
    if (i != 0) Text(":");
    Hex(mac[i]);
  }
  return *this;
}

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

void DescribeEndpoints(std::uint32_t address, TextLine& line) {
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
