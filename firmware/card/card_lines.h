// The lines a card prints about itself, the same on the host's stdout and a board's console: the
// "ready" line (the card-side part) and the "address" line. Built in a fixed buffer (no allocation),
// so a board prints them without a heap; docs/architecture.md "The ready line" defines the fields.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "card.h"
#include "hal/frame_port.h"

namespace firmware {

// A line of at most kCapacity characters; what does not fit is cut off (and marked `truncated`).
class TextLine {
 public:
  static constexpr std::size_t kCapacity = 240;

  TextLine& Text(std::string_view text);
  TextLine& Unsigned(std::uint64_t value);
  TextLine& Hex(std::uint8_t byte);  // two lowercase digits
  TextLine& Ipv4(std::uint32_t host_order);
  TextLine& Mac(const hal::MacAddress& mac);

  std::string_view view() const { return {text_.data(), length_}; }
  bool truncated() const { return truncated_; }

 private:
  std::array<char, kCapacity> text_{};
  std::size_t length_ = 0;
  bool truncated_ = false;
};

// "mode=dhcp phase=in-use ip=A.B.C.D/N gw=G duplicate=0 conflict=<attribute 11 in hex>".
void DescribeAddress(const CardAddressing& addressing, TextLine& line);
// "ip=A.B.C.D mac=aa:bb:cc:dd:ee:ff": the start of the ready line.
void DescribeIdentity(const Card& card, TextLine& line);
// "modbus=A:502 enip=A:44818 enip-udp=A:44818 io=A:2222 http=A:80" for the address in use.
void DescribeEndpoints(std::uint32_t address, TextLine& line);

}  // namespace firmware
