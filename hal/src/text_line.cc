#include "hal/text_line.h"

namespace hal {

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

TextLine& TextLine::Octets(std::span<const std::uint8_t> octets, std::string_view separator, bool hex) {
  for (std::size_t i = 0; i < octets.size(); ++i) {
    if (i != 0) Text(separator);
    if (hex) {
      Hex(octets[i]);
    } else {
      Unsigned(octets[i]);
    }
  }
  return *this;
}

TextLine& TextLine::Ipv4(const base::Ipv4Address& address) { return Octets(address.octets(), ".", false); }

TextLine& TextLine::Mac(const base::MacAddress& mac) { return Octets(mac.octets(), ":", true); }

}  // namespace hal
