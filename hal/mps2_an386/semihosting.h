// ARM semihosting (the "Semihosting for AArch32 and AArch64" specification): BKPT 0xAB with an
// operation number in r0 and a parameter block in r1, served by QEMU (-semihosting-config
// enable=on,target=native) or a debug probe. Without either, the BKPT faults; the HardFault handler
// turns that into a return value of -1 (startup.h SemihostingTrapped()), so every call here fails
// cleanly instead of stopping the card.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/status.h"

namespace hal::mps2::semihosting {

// SYS_OPEN modes (the fopen() strings they stand for).
enum class OpenMode : std::uint32_t {
  kReadBinary = 1,         // "rb"
  kReadWriteBinary = 3,    // "r+b": an existing file
  kCreateReadWriteBinary = 7,  // "w+b": created or truncated
};

// A handle, or kUnavailable (no semihosting) / kNotFound (the host could not open it). `path` must be
// NUL-terminated within its view.
base::Result<int> Open(std::string_view path, OpenMode mode);
void Close(int handle);
// Whole transfers only: kDataLoss when the host moved fewer bytes.
base::Status Seek(int handle, std::size_t offset);
base::Status Read(int handle, std::span<std::uint8_t> out);
base::Status Write(int handle, std::span<const std::uint8_t> data);
base::Result<std::size_t> FileLength(int handle);
// Ends the emulation (SYS_EXIT): QEMU exits with status 0 for success, 1 otherwise. Without an
// emulator (no semihosting) it returns.
void Exit(bool success);
// The command line QEMU passes (-semihosting-config arg=..., or the kernel's name followed by -append),
// NUL-terminated in `out`; its length.
base::Result<std::size_t> CommandLine(std::span<char> out);

}  // namespace hal::mps2::semihosting
