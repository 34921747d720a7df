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

TextLine& TextLine::Ipv4(const base::Ipv4Address& address) {
  bool first = true;
  for (std::uint8_t octet : address.octets()) {
    if (!first) Text(".");
    Unsigned(octet);
    first = false;
  }
  return *this;
}

TextLine& TextLine::Mac(const base::MacAddress& mac) {
  bool first = true;
  for (std::uint8_t octet : mac.octets()) {
    if (!first) Text(":");
    Hex(octet);
    first = false;
  }
  return *this;
}

}  // namespace hal
