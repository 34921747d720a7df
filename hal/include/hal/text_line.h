// A line of text built in a fixed buffer: no allocation, so a board formats its console lines (the
// ready line, LED changes, diagnostics) without a heap. What does not fit is cut off and marked.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "hal/frame_port.h"

namespace hal {

// A line of at most kCapacity characters; what does not fit is cut off (and marked `truncated`).
class TextLine {
 public:
  static constexpr std::size_t kCapacity = 240;

  TextLine& Text(std::string_view text);
  TextLine& Unsigned(std::uint64_t value);
  TextLine& Hex(std::uint8_t byte);  // two lowercase digits
  TextLine& Ipv4(const base::Ipv4Address& address);
  TextLine& Mac(const base::MacAddress& mac);

  std::string_view view() const { return {text_.data(), length_}; }
  bool truncated() const { return truncated_; }
  void Clear() {
    length_ = 0;
    truncated_ = false;
  }

 private:
  // The octets as decimal or two-digit hex numbers between separators (an address).
  TextLine& Octets(std::span<const std::uint8_t> octets, std::string_view separator, bool hex);
  std::array<char, kCapacity> text_{};
  std::size_t length_ = 0;
  bool truncated_ = false;
};

}  // namespace hal
