// The card's EDS as a cip::FileContent (docs/eds.md "Serving"): what the CIP File object 0x37 and the
// HTTP download read. Nothing is stored: the constructor runs the writer once to count the bytes and
// their checksum; ReadAt runs it again through a window (skip to the offset, copy, stop when full).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/file_content.h"
#include "cip/providers.h"

namespace cip::eds {

class EdsFile final : public FileContent {
 public:
  explicit EdsFile(DriveModel model);

  std::uint32_t Size() const override { return size_; }
  std::uint16_t Checksum() const override { return checksum_; }
  std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override;

  DriveModel model() const { return model_; }

 private:
  DriveModel model_;
  std::uint32_t size_ = 0;
  std::uint16_t checksum_ = 0;
};

// The CIP File object's checksum of some bytes: the two's complement of their 16-bit sum.
std::uint16_t FileChecksum(std::uint16_t sum_of_bytes);

}  // namespace cip::eds
