#include "semihosting.h"

#include <array>

namespace hal::mps2::semihosting {
namespace {

enum class Operation : std::uint32_t {
  kOpen = 0x01,
  kClose = 0x02,
  kWrite = 0x05,
  kRead = 0x06,
  kSeek = 0x0A,
  kFileLength = 0x0C,
  kCommandLine = 0x15,
  kExit = 0x18,
};

// SYS_EXIT reasons: "application exit" (status 0) and "run-time error, unknown" (status 1).
constexpr std::uint32_t kApplicationExit = 0x20026;
constexpr std::uint32_t kRunTimeError = 0x20023;

std::uint32_t Call(Operation operation, const void* parameters) {
  std::uint32_t result;
  __asm__ volatile(
      "mov r0, %1\n\t"
      "mov r1, %2\n\t"
      "bkpt 0xAB\n\t"
      "mov %0, r0"
      : "=r"(result)
      : "r"(static_cast<std::uint32_t>(operation)), "r"(parameters)
      : "r0", "r1", "memory");
  return result;
}

constexpr std::uint32_t kFailed = 0xFFFFFFFFU;

std::uint32_t Word(const void* pointer) { return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(pointer)); }

}  // namespace

base::Result<int> Open(std::string_view path, OpenMode mode) {
  if (path.empty() || path.back() != '\0') return base::InvalidArgument();
  const std::array<std::uint32_t, 3> block{Word(path.data()), static_cast<std::uint32_t>(mode),
                                           static_cast<std::uint32_t>(path.size() - 1)};
  const std::uint32_t handle = Call(Operation::kOpen, block.data());
  if (handle == kFailed) return base::NotFound();
  return static_cast<int>(handle);
}

void Close(int handle) {
  const std::array<std::uint32_t, 1> block{static_cast<std::uint32_t>(handle)};
  Call(Operation::kClose, block.data());
}

base::Status Seek(int handle, std::size_t offset) {
  const std::array<std::uint32_t, 2> block{static_cast<std::uint32_t>(handle), static_cast<std::uint32_t>(offset)};
  return Call(Operation::kSeek, block.data()) == 0 ? base::OkStatus() : base::DataLoss();
}

base::Status Read(int handle, std::span<std::uint8_t> out) {
  const std::array<std::uint32_t, 3> block{static_cast<std::uint32_t>(handle), Word(out.data()),
                                           static_cast<std::uint32_t>(out.size())};
  // The result is the number of bytes NOT read.
  return Call(Operation::kRead, block.data()) == 0 ? base::OkStatus() : base::DataLoss();
}

base::Status Write(int handle, std::span<const std::uint8_t> data) {
  const std::array<std::uint32_t, 3> block{static_cast<std::uint32_t>(handle), Word(data.data()),
                                           static_cast<std::uint32_t>(data.size())};
  // The result is the number of bytes NOT written.
  return Call(Operation::kWrite, block.data()) == 0 ? base::OkStatus() : base::DataLoss();
}

base::Result<std::size_t> FileLength(int handle) {
  const std::array<std::uint32_t, 1> block{static_cast<std::uint32_t>(handle)};
  const std::uint32_t length = Call(Operation::kFileLength, block.data());
  if (length == kFailed) return base::DataLoss();
  return static_cast<std::size_t>(length);
}

void Exit(bool success) {
  // On 32-bit ARM the parameter is the reason itself, not a block.
  Call(Operation::kExit, reinterpret_cast<const void*>(static_cast<std::uintptr_t>(success ? kApplicationExit : kRunTimeError)));
}

base::Result<std::size_t> CommandLine(std::span<char> out) {
  if (out.empty()) return base::InvalidArgument();
  std::array<std::uint32_t, 2> block{Word(out.data()), static_cast<std::uint32_t>(out.size())};
  if (Call(Operation::kCommandLine, block.data()) != 0) return base::Unavailable();
  // The host writes the length it used back into the block.
  if (block[1] >= out.size()) return base::OutOfRange();
  out[block[1]] = '\0';
  return static_cast<std::size_t>(block[1]);
}

}  // namespace hal::mps2::semihosting
