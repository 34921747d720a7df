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

// The EDS of the inverter the card is plugged into (DeviceInfoProvider::Model(): VF-MB1 until FB05 says
// VF-S15), asked at every call. An upload that spans a change of model (the first configuration load)
// gets bytes of both files; its checksum then fails at the originator, which uploads again.
class DetectedModelEds final : public FileContent {
 public:
  explicit DetectedModelEds(const DeviceInfoProvider& device) : device_(device) {}

  std::uint32_t Size() const override { return Current().Size(); }
  std::uint16_t Checksum() const override { return Current().Checksum(); }
  std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override {
    return Current().ReadAt(offset, out);
  }

 private:
  const EdsFile& Current() const { return device_.Model() == DriveModel::kVfS15 ? vf_s15_ : vf_mb1_; }

  const DeviceInfoProvider& device_;
  EdsFile vf_mb1_{DriveModel::kVfMb1};
  EdsFile vf_s15_{DriveModel::kVfS15};
};

// The CIP File object's checksum of some bytes: the two's complement of their 16-bit sum.
std::uint16_t FileChecksum(std::uint16_t sum_of_bytes);

}  // namespace cip::eds
