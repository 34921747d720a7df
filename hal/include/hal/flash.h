// Flash memory as a NOR part presents it: the facade under the card's non-volatile store
// (hal/flash_nv_store.h). A board backs it with its flash controller; tests with a fake
// (hal/test/fake_flash.h) that enforces the same rules and can cut power at any byte.
//
// Contract (the rules of real NOR flash, which the store above must respect):
// - The area is SectorCount() sectors of SectorSize() bytes, offsets 0 .. Size() - 1.
// - Erase(sector) sets every byte of that sector to 0xFF. It may take milliseconds and blocks.
// - Program(offset, data) can only clear bits (1 -> 0): the result is old AND new. Offset and length
//   are multiples of ProgramUnit(). Programming a unit twice without an erase in between is not
//   allowed (kFailedPrecondition; some parts corrupt ECC or refuse it).
// - Read(offset, out) copies bytes, from any offset and of any length; reading never wears the part.
// - A power cut during Program leaves the unit being programmed with any mix of old and new bits;
//   during Erase, the sector with any mix of its old bits and 1s. Units and sectors not being
//   written are never disturbed. A Program of several units writes them in address order, so the
//   units before the one being programmed are complete and those after it untouched.
// - A unit whose Program was cut counts as programmed until its sector is erased, even when it reads
//   0xFF (a part with ECC has already written part of its check bits), and a sector whose Erase was
//   cut counts as not erased: neither may be programmed before a complete Erase. Reading such a unit
//   gives one of the mixes above (the same at every read) or kDataLoss (an ECC error).
// - A sector is also the unit of wear: parts guarantee some 10^4..10^5 erases per sector. A backend
//   may present several physical pages as one sector (erasing them together) to reach a size its user
//   needs.
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
