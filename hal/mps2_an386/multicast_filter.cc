#include "multicast_filter.h"

namespace hal::mps2 {

std::uint8_t Lan9118HashIndex(const base::MacAddress& mac) {
  std::uint32_t crc = 0xFFFFFFFFU;
  for (const std::uint8_t byte : mac.octets()) {
    for (int bit = 0; bit < 8; ++bit) {
      const bool carry = ((crc >> 31) ^ (static_cast<std::uint32_t>(byte) >> bit)) & 1U;
      crc <<= 1;
      if (carry) crc ^= 0x04C11DB7U;
    }
  }
  return static_cast<std::uint8_t>(crc >> 26);
}

void MulticastFilter::Join(const base::MacAddress& group) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].mac == group) {
      ++entries_[i].joins;
      return;
    }
  }
  if (count_ == entries_.size()) {
    ++overflow_joins_;
    return;
  }
  entries_[count_++] = Entry{group, 1};
}

base::Status MulticastFilter::Leave(const base::MacAddress& group) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].mac != group) continue;
    if (--entries_[i].joins == 0) entries_[i] = entries_[--count_];
    return base::OkStatus();
  }
  // Not in the table: one of the joins that found it full (they are not told apart).
  if (overflow_joins_ == 0) return base::NotFound();
  --overflow_joins_;
  return base::OkStatus();
}

std::uint64_t MulticastFilter::HashTable() const {
  std::uint64_t table = 0;
  for (std::size_t i = 0; i < count_; ++i) table |= std::uint64_t{1} << Lan9118HashIndex(entries_[i].mac);
  return table;
}

}  // namespace hal::mps2
