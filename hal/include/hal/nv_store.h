// Non-volatile store: the card's own small records (passwords, web settings, counters).
// The drive's configuration lives in the inverter (c-parameters), not here.
//
// Contract:
// - Records are keyed by a 16-bit id and hold 0..kMaxRecordBytes bytes.
// - Write() is atomic with respect to power loss: after a cut at any instant, the next Read() returns
//   either the complete old contents or the complete new contents, never a mix and never garbage.
// - Read() copies the record into `out` and returns its length. kNotFound: never written (or erased).
//   kOutOfRange: `out` is smaller than the record. kDataLoss: the stored copy fails its integrity check.
// - Calls block only for the duration of the storage write itself (a flash page, an fsync), which the
//   firmware does only on configuration changes, never per packet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"

namespace hal {

inline constexpr std::size_t kMaxRecordBytes = 1024;

using NvRecordId = std::uint16_t;

class NvStore {
 public:
  virtual ~NvStore() = default;
  virtual base::Result<std::size_t> Read(NvRecordId id, std::span<std::uint8_t> out) = 0;
  virtual base::Status Write(NvRecordId id, std::span<const std::uint8_t> data) = 0;
  virtual base::Status Erase(NvRecordId id) = 0;
};

}  // namespace hal
