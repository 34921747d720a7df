#include "semihosting_flash.h"

#include <algorithm>
#include <array>

#include "semihosting.h"
#include "startup.h"

namespace hal::mps2 {
namespace {

constexpr std::uint8_t kErased = 0xFF;
constexpr std::size_t kChunk = 256;  // bytes per semihosting transfer (on the stack)

}  // namespace

base::Status SemihostingFlash::Open(std::string_view path) {
  base::Result<int> handle = semihosting::Open(path, semihosting::OpenMode::kReadWriteBinary);
  if (!handle.ok()) {
    // No such file yet ("r+b" does not create): make it. A missing semihosting fails here again.
    handle = semihosting::Open(path, semihosting::OpenMode::kCreateReadWriteBinary);
    if (!handle.ok()) return SemihostingTrapped() ? base::Unavailable() : handle.status();
  }
  const base::Result<std::size_t> length = semihosting::FileLength(handle.value());
  if (!length.ok()) {
    semihosting::Close(handle.value());
    return base::DataLoss();
  }
  handle_ = handle.value();
  if (length.value() < Size()) {
    if (base::Status filled = Fill(length.value(), Size() - length.value()); !filled.ok()) {
      semihosting::Close(handle_);
      handle_ = -1;
      return filled;
    }
  }
  return base::OkStatus();
}

base::Status SemihostingFlash::Fill(std::size_t offset, std::size_t length) {
  std::array<std::uint8_t, kChunk> erased;
  erased.fill(kErased);
  if (base::Status sought = semihosting::Seek(handle_, offset); !sought.ok()) return sought;
  while (length > 0) {
    const std::size_t take = std::min(length, erased.size());
    if (base::Status written = semihosting::Write(handle_, std::span(erased).first(take)); !written.ok()) {
      return written;
    }
    length -= take;
  }
  return base::OkStatus();
}

base::Status SemihostingFlash::Read(std::size_t offset, std::span<std::uint8_t> out) {
  if (!open()) return base::FailedPrecondition();
  if (offset > Size() || out.size() > Size() - offset) return base::OutOfRange();
  if (out.empty()) return base::OkStatus();
  if (base::Status sought = semihosting::Seek(handle_, offset); !sought.ok()) return sought;
  return semihosting::Read(handle_, out);
}

base::Status SemihostingFlash::Erase(std::size_t sector) {
  if (!open()) return base::FailedPrecondition();
  if (sector >= SectorCount()) return base::OutOfRange();
  return Fill(sector * SectorSize(), SectorSize());
}

base::Status SemihostingFlash::Program(std::size_t offset, std::span<const std::uint8_t> data) {
  if (!open()) return base::FailedPrecondition();
  if (offset > Size() || data.size() > Size() - offset) return base::OutOfRange();
  if (offset % ProgramUnit() != 0 || data.size() % ProgramUnit() != 0) return base::InvalidArgument();
  // Every unit must still be erased: read them all before writing any.
  std::array<std::uint8_t, kChunk> current;
  for (std::size_t done = 0; done < data.size(); done += current.size()) {
    const std::size_t take = std::min(current.size(), data.size() - done);
    if (base::Status read = Read(offset + done, std::span(current).first(take)); !read.ok()) return read;
    if (std::any_of(current.begin(), current.begin() + static_cast<std::ptrdiff_t>(take),
                    [](std::uint8_t byte) { return byte != kErased; })) {
      return base::FailedPrecondition();
    }
  }
  if (data.empty()) return base::OkStatus();
  if (base::Status sought = semihosting::Seek(handle_, offset); !sought.ok()) return sought;
  return semihosting::Write(handle_, data);
}

base::Result<std::string_view> SemihostingArgument(std::string_view name, std::span<char> out) {
  std::array<char, 256> line;
  const base::Result<std::size_t> length = semihosting::CommandLine(line);
  if (!length.ok()) return length.status() == base::OutOfRange() ? base::OutOfRange() : base::Unavailable();
  std::string_view rest(line.data(), length.value());
  while (!rest.empty()) {
    const std::size_t space = rest.find(' ');
    const std::string_view word = rest.substr(0, space);
    rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
    if (word.size() <= name.size() || word.substr(0, name.size()) != name || word[name.size()] != '=') continue;
    const std::string_view value = word.substr(name.size() + 1);
    if (value.size() + 1 > out.size()) return base::OutOfRange();
    std::copy(value.begin(), value.end(), out.begin());
    out[value.size()] = '\0';
    return std::string_view(out.data(), value.size());
  }
  return base::NotFound();
}

}  // namespace hal::mps2
