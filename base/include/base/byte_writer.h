// ByteWriter: the one way every layer writes wire bytes (the counterpart of ByteReader, after Pigweed's
// ByteBuilder). It appends to a caller's span and never writes outside it; every multi-byte write
// names its byte order.
//
// Failure is sticky: a write that does not fit writes nothing, marks the writer failed, and every later
// write is dropped. size() stays at the last write that fitted, so a caller can still see how far it
// got; a failed writer's bytes are never sent (callers check ok(), or Finish(), once at the end).
//
// A field whose value is known only later (a length, a count) is reserved with Reserve(n), which writes
// n zero bytes and returns their offset, and filled with the Patch* calls. A patch outside what was
// written marks the writer failed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"

namespace base {

class ByteWriter {
 public:
  constexpr explicit ByteWriter(std::span<std::uint8_t> buffer) : buffer_(buffer) {}
  // Copying would make two writers over one buffer; a nested encoder gets Tail() and Advance().
  ByteWriter(const ByteWriter&) = delete;
  ByteWriter& operator=(const ByteWriter&) = delete;

  constexpr bool ok() const { return ok_; }
  constexpr std::size_t size() const { return size_; }
  constexpr std::size_t capacity() const { return buffer_.size(); }
  constexpr std::size_t room() const { return buffer_.size() - size_; }
  constexpr std::span<const std::uint8_t> written() const { return buffer_.first(size_); }
  // The number of bytes written, or kResourceExhausted when any write did not fit.
  constexpr Result<std::size_t> Finish() const {
    if (!ok_) return ResourceExhausted();
    return size_;
  }

  constexpr void U8(std::uint8_t value) {
    if (Require(1)) buffer_[size_++] = value;
  }
  constexpr void U16Le(std::uint16_t value) { Little(value, 2); }
  constexpr void U16Be(std::uint16_t value) { Big(value, 2); }
  constexpr void U32Le(std::uint32_t value) { Little(value, 4); }
  constexpr void U32Be(std::uint32_t value) { Big(value, 4); }
  constexpr void U64Le(std::uint64_t value) { Little(value, 8); }
  constexpr void U64Be(std::uint64_t value) { Big(value, 8); }
  constexpr void Bytes(std::span<const std::uint8_t> bytes) {
    if (!Require(bytes.size())) return;
    for (std::uint8_t byte : bytes) buffer_[size_++] = byte;
  }
  constexpr void Zeros(std::size_t count) {
    if (!Require(count)) return;
    for (std::size_t i = 0; i < count; ++i) buffer_[size_++] = 0;
  }

  // Writes `count` zero bytes to be patched later; returns their offset.
  constexpr std::size_t Reserve(std::size_t count) {
    const std::size_t offset = size_;
    Zeros(count);
    return offset;
  }
  constexpr void PatchU8(std::size_t offset, std::uint8_t value) { Patch(offset, value, 1, false); }
  constexpr void PatchU16Le(std::size_t offset, std::uint16_t value) { Patch(offset, value, 2, false); }
  constexpr void PatchU16Be(std::size_t offset, std::uint16_t value) { Patch(offset, value, 2, true); }
  constexpr void PatchU32Le(std::size_t offset, std::uint32_t value) { Patch(offset, value, 4, false); }
  constexpr void PatchU32Be(std::size_t offset, std::uint32_t value) { Patch(offset, value, 4, true); }

  // Drops everything from `size` on and clears a failure: used to replace a partly written reply by an
  // error reply. A size beyond what was written is ignored.
  constexpr void Truncate(std::size_t size) {
    if (size <= size_) size_ = size;
    ok_ = true;
  }
  // The unwritten rest of the buffer, for a nested encoder whose output is then committed with
  // Advance(). The tail is only valid until this writer is written again.
  constexpr std::span<std::uint8_t> Tail() { return buffer_.subspan(size_); }
  constexpr void Advance(std::size_t count) {
    if (Require(count)) size_ += count;
  }

 private:
  constexpr bool Require(std::size_t count) {
    if (ok_ && count <= room()) return true;
    ok_ = false;
    return false;
  }
  constexpr void Little(std::uint64_t value, std::size_t width) {
    if (!Require(width)) return;
    for (std::size_t i = 0; i < width; ++i) buffer_[size_++] = static_cast<std::uint8_t>(value >> (8 * i));
  }
  constexpr void Big(std::uint64_t value, std::size_t width) {
    if (!Require(width)) return;
    for (std::size_t i = width; i > 0; --i) buffer_[size_++] = static_cast<std::uint8_t>(value >> (8 * (i - 1)));
  }
  constexpr void Patch(std::size_t offset, std::uint64_t value, std::size_t width, bool big_endian) {
    if (!ok_ || offset > size_ || size_ - offset < width) {
      ok_ = false;
      return;
    }
    for (std::size_t i = 0; i < width; ++i) {
      const std::size_t shift = 8 * (big_endian ? width - 1 - i : i);
      buffer_[offset + i] = static_cast<std::uint8_t>(value >> shift);
    }
  }

  std::span<std::uint8_t> buffer_;
  std::size_t size_ = 0;
  bool ok_ = true;
};

}  // namespace base
