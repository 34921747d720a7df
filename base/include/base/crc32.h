// CRC-32 as in IEEE 802.3 and zlib (reflected polynomial 0x04C11DB7, initial value and final XOR
// 0xFFFFFFFF; check value of "123456789": 0xCBF43926). Used where stored data must prove it is whole:
// the card's NV records and the simulated inverter's EEPROM image.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace base {

namespace crc32_detail {
constexpr std::array<std::uint32_t, 256> MakeTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1U) != 0 ? (crc >> 1) ^ 0xEDB88320U : crc >> 1;
    table[i] = crc;
  }
  return table;
}
inline constexpr std::array<std::uint32_t, 256> kTable = MakeTable();
}  // namespace crc32_detail

// The CRC of data that arrives in pieces (read from flash a chunk at a time): Add each piece in order;
// value() is then Crc32 of their concatenation.
class Crc32Builder {
 public:
  constexpr void Add(std::span<const std::uint8_t> bytes) {
    for (std::uint8_t byte : bytes) crc_ = (crc_ >> 8) ^ crc32_detail::kTable[(crc_ ^ byte) & 0xFFU];
  }
  constexpr std::uint32_t value() const { return crc_ ^ 0xFFFFFFFFU; }

 private:
  std::uint32_t crc_ = 0xFFFFFFFFU;
};

constexpr std::uint32_t Crc32(std::span<const std::uint8_t> bytes) {
  Crc32Builder crc;
  crc.Add(bytes);
  return crc.value();
}

}  // namespace base
