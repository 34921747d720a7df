// Bounded byte reader and writer: the only way the EtherNet/IP core touches wire bytes.
//
// CIP and the encapsulation layer are little-endian; the socket-address items of the Common Packet
// Format and of ListIdentity are big-endian ("network order"), hence the Be variants.
//
// Both classes fail sticky, the way p-net's pf_get_info_t and Pigweed's ByteBuilder do, so that a flat
// layout can be read field by field and checked once with ok():
// - ByteReader: a read past the end marks the reader failed, moves the cursor to the end and returns 0
//   (or an empty span / a failed child reader). Every later read fails too. Nothing is ever read
//   outside the span the reader was made from.
// - ByteWriter: a write that does not fit writes nothing, marks the writer failed, and every later
//   write is dropped. size() stays at the last write that fitted, so a caller can still see how far it
//   got; a failed writer's bytes are never sent (callers check ok() once at the end).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace cip {

class ByteReader {
 public:
  constexpr ByteReader() = default;
  constexpr explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  constexpr bool ok() const { return ok_; }
  constexpr std::size_t remaining() const { return bytes_.size() - position_; }
  constexpr std::size_t position() const { return position_; }
  constexpr bool empty() const { return remaining() == 0; }

  constexpr std::uint8_t U8() {
    if (!Require(1)) return 0;
    return bytes_[position_++];
  }
  constexpr std::uint16_t U16() {
    if (!Require(2)) return 0;
    const std::uint16_t value = static_cast<std::uint16_t>(bytes_[position_] | bytes_[position_ + 1] << 8);
    position_ += 2;
    return value;
  }
  constexpr std::uint32_t U32() {
    if (!Require(4)) return 0;
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(bytes_[position_ + i]) << (8 * i);
    position_ += 4;
    return value;
  }
  constexpr std::uint16_t U16Be() {
    if (!Require(2)) return 0;
    const std::uint16_t value = static_cast<std::uint16_t>(bytes_[position_] << 8 | bytes_[position_ + 1]);
    position_ += 2;
    return value;
  }
  constexpr std::uint32_t U32Be() {
    if (!Require(4)) return 0;
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i) value = value << 8 | bytes_[position_ + i];
    position_ += 4;
    return value;
  }
  // The next `count` bytes, or an empty span (and a failed reader) when fewer remain.
  constexpr std::span<const std::uint8_t> Bytes(std::size_t count) {
    if (!Require(count)) return {};
    const std::span<const std::uint8_t> bytes = bytes_.subspan(position_, count);
    position_ += count;
    return bytes;
  }
  constexpr void Skip(std::size_t count) { (void)Bytes(count); }
  // A reader over the next `count` bytes (a length-delimited field); this reader moves past them. When
  // fewer remain, both this reader and the returned one are failed.
  constexpr ByteReader Take(std::size_t count) {
    if (!Require(count)) return Failed();
    return ByteReader(Bytes(count));
  }
  // Everything not read yet; the reader is then at its end.
  constexpr std::span<const std::uint8_t> Rest() { return Bytes(remaining()); }

 private:
  static constexpr ByteReader Failed() {
    ByteReader reader;
    reader.ok_ = false;
    return reader;
  }
  constexpr bool Require(std::size_t count) {
    if (ok_ && count <= remaining()) return true;
    ok_ = false;
    position_ = bytes_.size();
    return false;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

class ByteWriter {
 public:
  constexpr explicit ByteWriter(std::span<std::uint8_t> buffer) : buffer_(buffer) {}
  // Copying would make two writers over one buffer; a sub-writer is made explicitly with Tail().
  ByteWriter(const ByteWriter&) = delete;
  ByteWriter& operator=(const ByteWriter&) = delete;

  constexpr bool ok() const { return ok_; }
  constexpr std::size_t size() const { return size_; }
  constexpr std::size_t capacity() const { return buffer_.size(); }
  constexpr std::size_t room() const { return buffer_.size() - size_; }
  constexpr std::span<const std::uint8_t> written() const { return buffer_.first(size_); }

  constexpr void U8(std::uint8_t value) {
    if (Require(1)) buffer_[size_++] = value;
  }
  constexpr void U16(std::uint16_t value) {
    if (!Require(2)) return;
    buffer_[size_++] = static_cast<std::uint8_t>(value);
    buffer_[size_++] = static_cast<std::uint8_t>(value >> 8);
  }
  constexpr void U32(std::uint32_t value) {
    if (!Require(4)) return;
    for (std::size_t i = 0; i < 4; ++i) buffer_[size_++] = static_cast<std::uint8_t>(value >> (8 * i));
  }
  constexpr void U16Be(std::uint16_t value) {
    if (!Require(2)) return;
    buffer_[size_++] = static_cast<std::uint8_t>(value >> 8);
    buffer_[size_++] = static_cast<std::uint8_t>(value);
  }
  constexpr void U32Be(std::uint32_t value) {
    if (!Require(4)) return;
    for (std::size_t i = 0; i < 4; ++i) buffer_[size_++] = static_cast<std::uint8_t>(value >> (24 - 8 * i));
  }
  constexpr void Bytes(std::span<const std::uint8_t> bytes) {
    if (!Require(bytes.size())) return;
    for (std::uint8_t byte : bytes) buffer_[size_++] = byte;
  }
  constexpr void Zeros(std::size_t count) {
    if (!Require(count)) return;
    for (std::size_t i = 0; i < count; ++i) buffer_[size_++] = 0;
  }

  // Patches a 16-bit little-endian field written earlier (a length or count known only afterwards).
  // An offset outside what was written marks the writer failed.
  constexpr void PatchU16(std::size_t offset, std::uint16_t value) {
    if (!ok_ || offset > size_ || size_ - offset < 2) {
      ok_ = false;
      return;
    }
    buffer_[offset] = static_cast<std::uint8_t>(value);
    buffer_[offset + 1] = static_cast<std::uint8_t>(value >> 8);
  }
  constexpr void PatchU32(std::size_t offset, std::uint32_t value) {
    PatchU16(offset, static_cast<std::uint16_t>(value));
    PatchU16(offset + 2, static_cast<std::uint16_t>(value >> 16));
  }
  constexpr void PatchU8(std::size_t offset, std::uint8_t value) {
    if (!ok_ || offset >= size_) {
      ok_ = false;
      return;
    }
    buffer_[offset] = value;
  }
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

  std::span<std::uint8_t> buffer_;
  std::size_t size_ = 0;
  bool ok_ = true;
};

}  // namespace cip
