// Bounded big-endian readers and writers for Modbus frames (style-examples.md, "what to absorb" 1-4).
//
// Both keep a sticky error: once a read runs past the end (or a write past the capacity) every later
// call does nothing and ok() stays false, so a caller checks once, after a flat sequence of fields. A
// failed read yields 0; a failed write leaves the bytes already written and writes nothing more.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace modbus {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::uint8_t U8() {
    if (!Has(1)) return 0;
    return bytes_[position_++];
  }
  std::uint16_t U16() {
    if (!Has(2)) return 0;
    const auto value = static_cast<std::uint16_t>((bytes_[position_] << 8) | bytes_[position_ + 1]);
    position_ += 2;
    return value;
  }

  bool ok() const { return ok_; }
  std::size_t remaining() const { return bytes_.size() - position_; }
  std::size_t position() const { return position_; }

 private:
  bool Has(std::size_t n) {
    if (!ok_ || remaining() < n) {
      ok_ = false;
      return false;
    }
    return true;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::uint8_t> buffer) : buffer_(buffer) {}
  ByteWriter(const ByteWriter&) = delete;
  ByteWriter& operator=(const ByteWriter&) = delete;

  void U8(std::uint8_t value) {
    if (!Has(1)) return;
    buffer_[length_++] = value;
  }
  void U16(std::uint16_t value) {
    if (!Has(2)) return;
    buffer_[length_++] = static_cast<std::uint8_t>(value >> 8);
    buffer_[length_++] = static_cast<std::uint8_t>(value & 0xFF);
  }
  void Bytes(std::span<const std::uint8_t> bytes) {
    if (!Has(bytes.size())) return;
    for (std::uint8_t b : bytes) buffer_[length_++] = b;
  }

  bool ok() const { return ok_; }
  std::size_t length() const { return length_; }
  std::span<const std::uint8_t> written() const { return buffer_.first(length_); }

 private:
  bool Has(std::size_t n) {
    if (!ok_ || buffer_.size() - length_ < n) {
      ok_ = false;
      return false;
    }
    return true;
  }

  std::span<std::uint8_t> buffer_;
  std::size_t length_ = 0;
  bool ok_ = true;
};

}  // namespace modbus
