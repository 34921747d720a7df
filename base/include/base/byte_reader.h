// ByteReader: the one way every layer reads wire bytes (issue 20; open62541's decode context is the
// model). It is a span plus a cursor and it never reads outside that span: there is no unchecked
// accessor. Every multi-byte read names its byte order (U16Le/U16Be, ...): CIP and the encapsulation
// layer are little-endian, Modbus, the Toshiba binary protocol, ARP/IP/UDP/BOOTP are big-endian.
//
// Failure is sticky, the way p-net's pf_get_info_t and Pigweed's ByteBuilder are, so that a flat
// layout can be read field by field and checked once with ok(): a read that needs more bytes than
// remain marks the reader failed, moves the cursor to the end and yields 0 (or an empty span, or a
// failed child reader). Every later read fails the same way, even one that would have fitted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace base {

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
  constexpr std::uint16_t U16Le() { return static_cast<std::uint16_t>(Little(2)); }
  constexpr std::uint16_t U16Be() { return static_cast<std::uint16_t>(Big(2)); }
  constexpr std::uint32_t U32Le() { return static_cast<std::uint32_t>(Little(4)); }
  constexpr std::uint32_t U32Be() { return static_cast<std::uint32_t>(Big(4)); }
  constexpr std::uint64_t U64Le() { return Little(8); }
  constexpr std::uint64_t U64Be() { return Big(8); }

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
  constexpr std::uint64_t Little(std::size_t size) {
    if (!Require(size)) return 0;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < size; ++i) value |= static_cast<std::uint64_t>(bytes_[position_ + i]) << (8 * i);
    position_ += size;
    return value;
  }
  constexpr std::uint64_t Big(std::size_t size) {
    if (!Require(size)) return 0;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < size; ++i) value = value << 8 | bytes_[position_ + i];
    position_ += size;
    return value;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

}  // namespace base
