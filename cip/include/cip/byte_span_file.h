// A FileContent over bytes that stay where they are (a constant in flash): the card's served file until
// the EDS generator provides its own content (docs/file-object.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/file_content.h"

namespace cip {

// The File object's checksum of `bytes`: the two's complement of the 16-bit sum of every byte (CIP Vol. 1
// §5A-42, attribute 7), so that the sum of the bytes and the checksum is 0 modulo 2^16.
constexpr std::uint16_t FileChecksum(std::span<const std::uint8_t> bytes) {
  std::uint16_t sum = 0;
  for (std::uint8_t byte : bytes) sum = static_cast<std::uint16_t>(sum + byte);
  return static_cast<std::uint16_t>(0x10000U - sum);
}

class ByteSpanFile final : public FileContent {
 public:
  // `bytes` must outlive the file (at most 4 GiB - 1: the size is a UDINT).
  constexpr explicit ByteSpanFile(std::span<const std::uint8_t> bytes)
      : bytes_(bytes), checksum_(FileChecksum(bytes)) {}

  std::uint32_t Size() const override { return static_cast<std::uint32_t>(bytes_.size()); }
  std::uint16_t Checksum() const override { return checksum_; }
  // Copies min(out.size(), Size() - offset) bytes; 0 at or past the end.
  std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override;

 private:
  std::span<const std::uint8_t> bytes_;
  std::uint16_t checksum_;
};

}  // namespace cip
