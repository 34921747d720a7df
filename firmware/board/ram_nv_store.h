// hal::NvStore in RAM, for a run of the board without flash (QEMU without semihosting or without
// flash=PATH; a flash store that does not mount): the card works, but nothing survives a reset, so it
// makes a new MAC and a new random seed at every start and forgets its settings. The board main says
// so on the console. With flash, the records are in hal::FlashNvStore.
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
