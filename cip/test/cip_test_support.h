// Helpers shared by the EtherNet/IP core's tests: hex byte strings and scripted fakes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hal/random.h"

namespace cip::test {

using Bytes = std::vector<std::uint8_t>;

// "65 00 04 00" -> bytes; spaces and '|' are separators.
inline Bytes Hex(std::string_view text) {
  Bytes bytes;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ' || text[i] == '|' || text[i] == '\n') {
      ++i;
      continue;
    }
    bytes.push_back(static_cast<std::uint8_t>(std::stoi(std::string(text.substr(i, 2)), nullptr, 16)));
    i += 2;
  }
  return bytes;
}

inline Bytes Of(std::span<const std::uint8_t> span) { return Bytes(span.begin(), span.end()); }

inline Bytes Concat(const Bytes& a, const Bytes& b) {
  Bytes out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

// Hands out the pushed 32-bit values first (little-endian, as NextU32 reads them); when none are
// queued, a fixed sequence 0x11223344, 0x12233445, ... so that unscripted draws are predictable too.
class ScriptedRandom final : public hal::RandomSource {
 public:
  void Push(std::uint32_t value) { values_.push_back(value); }
  void Fill(std::span<std::uint8_t> out) override {
    std::uint32_t value = next_default_;
    if (!values_.empty()) {
      value = values_.front();
      values_.pop_front();
    } else {
      next_default_ += 0x01010101;
    }
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * (i % 4)));
  }

 private:
  std::deque<std::uint32_t> values_;
  std::uint32_t next_default_ = 0x11223344;
};

}  // namespace cip::test
