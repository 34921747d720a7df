// Flash memory as a NOR part presents it: the facade under the card's non-volatile store
// (hal/src/flash_nv_store.h). A board backs it with its flash controller; tests with a fake that
// enforces the same rules and can cut power at any byte.
//
// Contract (the rules of real NOR flash, which the store above must respect):
// - The area is SectorCount() sectors of SectorSize() bytes, offsets 0 .. Size() - 1.
// - Erase(sector) sets every byte of that sector to 0xFF. It may take milliseconds and blocks.
// - Program(offset, data) can only clear bits (1 -> 0): the result is old AND new. Offset and length
//   are multiples of ProgramUnit(). Programming a unit twice without an erase in between is not
//   allowed (kFailedPrecondition; some parts corrupt ECC or refuse it).
// - Read(offset, out) copies bytes; reading never wears the part.
// - A power cut during Program leaves the unit being programmed with any mix of old and new bits;
//   during Erase, the sector with any mix of its old bits and 1s. Units and sectors not being
//   written are never disturbed.
// - kOutOfRange for an access past the end, kInvalidArgument for a misaligned one, kDataLoss when the
//   part reports a failed operation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"

namespace hal {

class Flash {
 public:
  virtual ~Flash() = default;
  virtual std::size_t SectorSize() const = 0;
  virtual std::size_t SectorCount() const = 0;
  virtual std::size_t ProgramUnit() const = 0;
  std::size_t Size() const { return SectorSize() * SectorCount(); }

  virtual base::Status Read(std::size_t offset, std::span<std::uint8_t> out) = 0;
  virtual base::Status Erase(std::size_t sector) = 0;
  virtual base::Status Program(std::size_t offset, std::span<const std::uint8_t> data) = 0;
};

}  // namespace hal
