// Random numbers for things an attacker must not guess: session handles, TCP initial sequence numbers
// and ephemeral ports, connection serials. The host backend uses the kernel's CSPRNG; a board uses its
// TRNG peripheral.
#pragma once

#include <cstdint>
#include <span>

namespace hal {

class RandomSource {
 public:
  virtual ~RandomSource() = default;
  virtual void Fill(std::span<std::uint8_t> out) = 0;

  std::uint32_t NextU32() {
    std::uint8_t bytes[4];
    Fill(bytes);
    return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
           static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
  }
};

}  // namespace hal
