#include "cip/eds/eds_file.h"

#include <algorithm>
#include <string_view>

#include "cip/eds/eds_writer.h"

namespace cip::eds {
namespace {

// Counts the bytes and adds them up (16 bits, wrapping).
class CountingSink final : public EdsSink {
 public:
  bool Append(std::string_view text) override {
    size += static_cast<std::uint32_t>(text.size());
    for (const char c : text) sum = static_cast<std::uint16_t>(sum + static_cast<std::uint8_t>(c));
    return true;
  }
  std::uint32_t size = 0;
  std::uint16_t sum = 0;
};

// Keeps bytes [offset, offset + out.size()) of the text and stops the writer once it has them.
class WindowSink final : public EdsSink {
 public:
  WindowSink(std::uint32_t offset, std::span<std::uint8_t> out) : skip_(offset), out_(out) {}
  bool Append(std::string_view text) override {
    if (skip_ >= text.size()) {
      skip_ -= static_cast<std::uint32_t>(text.size());
      return true;
    }
    text.remove_prefix(skip_);
    skip_ = 0;
    const std::size_t count = std::min(text.size(), out_.size() - copied_);
    std::copy_n(text.begin(), count, out_.begin() + static_cast<std::ptrdiff_t>(copied_));
    copied_ += count;
    return copied_ < out_.size();
  }
  std::size_t copied() const { return copied_; }

 private:
  std::uint32_t skip_;
  std::span<std::uint8_t> out_;
  std::size_t copied_ = 0;
};

}  // namespace

std::uint16_t FileChecksum(std::uint16_t sum_of_bytes) { return static_cast<std::uint16_t>(0x10000U - sum_of_bytes); }

EdsFile::EdsFile(DriveModel model) : model_(model) {
  CountingSink counter;
  WriteEds(model_, counter);
  size_ = counter.size;
  checksum_ = FileChecksum(counter.sum);
}

std::size_t EdsFile::ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const {
  if (offset >= size_ || out.empty()) return 0;
  WindowSink window(offset, out);
  WriteEds(model_, window);
  return window.copied();
}

}  // namespace cip::eds
