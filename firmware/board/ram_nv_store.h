// A stand-in hal::NvStore in RAM, so the board boots before the flash-backed store exists.
//
// TODO(FlashNvStore): replace with hal::FlashNvStore (hal/include/hal/flash_nv_store.h) on the
// SemihostingFlash the board main already opens; nothing here survives a reset, so until then the card
// makes a new MAC and a new random seed at every start and forgets its settings.
//
// Contract as hal/nv_store.h, with one limit of its own: at most kRecords records of at most
// kRecordBytes bytes (kResourceExhausted beyond). A write is atomic (RAM: nothing can cut it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "hal/nv_store.h"

namespace firmware::board {

class RamNvStore final : public hal::NvStore {
 public:
  static constexpr std::size_t kRecords = 6;
  static constexpr std::size_t kRecordBytes = 128;

  base::Result<std::size_t> Read(hal::NvRecordId id, std::span<std::uint8_t> out) override;
  base::Status Write(hal::NvRecordId id, std::span<const std::uint8_t> data) override;
  base::Status Erase(hal::NvRecordId id) override;

 private:
  struct Record {
    bool used = false;
    hal::NvRecordId id = 0;
    std::size_t length = 0;
    std::array<std::uint8_t, kRecordBytes> bytes{};
  };
  Record* Find(hal::NvRecordId id);

  std::array<Record, kRecords> records_{};
};

}  // namespace firmware::board
