#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace cip {

// A read-only file the card serves (the EDS): its size, its CIP checksum and its bytes by offset.
class FileContent {
 public:
  virtual std::uint32_t Size() const = 0;
  virtual std::uint16_t Checksum() const = 0;   // two's complement of the 16-bit sum of every byte
  virtual std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const = 0;  // bytes copied
 protected:
  ~FileContent() = default;
};

}  // namespace cip
