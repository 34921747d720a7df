// hal::Flash for QEMU: the card's NV flash area kept in a file on the host through semihosting, so it
// survives a restart of the emulator like flash survives a power cycle. The file is the area's image
// (Size() bytes, erased = 0xFF), created on first use; `flash=PATH` on the semihosting command line
// names it (docs/board.md "Flash under QEMU").
//
// The NOR rules of hal/flash.h are enforced: a program unit that is not erased (not all 0xFF) cannot be
// programmed again (kFailedPrecondition), as the flash controllers with ECC of the parts this card
// would use refuse it; programming all-0xFF data is therefore indistinguishable from not programming.
// A failed semihosting transfer is kDataLoss ("the part reports a failed operation").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/status.h"
#include "hal/flash.h"

namespace hal::mps2 {

// The geometry of the area: 8 sectors of 4 KiB, programmed 8 bytes at a time (a double word, as on
// many Cortex-M4 parts). 32 KiB of the 256 KiB flash budget.
inline constexpr std::size_t kFlashSectorSize = 4096;
inline constexpr std::size_t kFlashSectorCount = 8;
inline constexpr std::size_t kFlashProgramUnit = 8;

class SemihostingFlash final : public Flash {
 public:
  SemihostingFlash() = default;
  SemihostingFlash(const SemihostingFlash&) = delete;
  SemihostingFlash& operator=(const SemihostingFlash&) = delete;

  // Opens (or creates, erased) the image file at `path` (NUL-terminated in its view) and extends a
  // shorter one with erased bytes. kUnavailable: no semihosting; kNotFound: the host cannot open or
  // create the file; kDataLoss: it cannot be read or extended.
  base::Status Open(std::string_view path);
  bool open() const { return handle_ >= 0; }

  std::size_t SectorSize() const override { return kFlashSectorSize; }
  std::size_t SectorCount() const override { return kFlashSectorCount; }
  std::size_t ProgramUnit() const override { return kFlashProgramUnit; }

  // Before a successful Open(): kFailedPrecondition.
  base::Status Read(std::size_t offset, std::span<std::uint8_t> out) override;
  base::Status Erase(std::size_t sector) override;
  base::Status Program(std::size_t offset, std::span<const std::uint8_t> data) override;

 private:
  base::Status Fill(std::size_t offset, std::size_t length);  // writes erased bytes

  int handle_ = -1;
};

// The value of `name=` on the semihosting command line, NUL-terminated in `out` (view without the NUL).
// kNotFound: no such argument; kUnavailable: no semihosting; kOutOfRange: it does not fit.
base::Result<std::string_view> SemihostingArgument(std::string_view name, std::span<char> out);

}  // namespace hal::mps2
