// The multicast groups a LAN9118 lets in, as its 64-bit hash table (MAC_HASHH:MAC_HASHL) sees them.
//
// The chip hashes a multicast destination to 6 bits: the top 6 bits of the Ethernet CRC-32 of the six
// address bytes (register preset to all ones, bits fed least significant first, no final inversion).
// Bit 5 of the hash picks HASHH (1) or HASHL (0), bits 4..0 the bit in it. A frame passes when its bit
// is set, so a table with few groups also lets in the other groups that share their bits; the stack
// above filters by address anyway. A group joined twice stays until left twice. Beyond kCapacity
// distinct groups the table cannot follow: PassAll() says the MAC must pass every multicast frame
// (MAC_CR.MCPAS) until enough groups have left.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "hal/frame_port.h"

namespace hal::mps2 {

std::uint8_t Lan9118HashIndex(const base::MacAddress& mac);

class MulticastFilter {
 public:
  static constexpr std::size_t kCapacity = 16;

  void Join(const base::MacAddress& group);
  // kNotFound: the group was not joined.
  base::Status Leave(const base::MacAddress& group);

  // Bit i set: hash index i passes (bits 63..32 go to MAC_HASHH, 31..0 to MAC_HASHL).
  std::uint64_t HashTable() const;
  bool PassAll() const { return overflow_joins_ > 0; }
  std::size_t groups() const { return count_; }

 private:
  struct Entry {
    base::MacAddress mac{};
    std::uint32_t joins = 0;
  };
  std::array<Entry, kCapacity> entries_{};
  std::size_t count_ = 0;
  std::uint32_t overflow_joins_ = 0;  // joins that found the table full
};

}  // namespace hal::mps2
