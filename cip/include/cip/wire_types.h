// Small value types shared by the encapsulation layer and the CIP objects: fixed-capacity strings, the
// IPv4 socket address of the Common Packet Format and of ListIdentity.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/addresses.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace cip {

// A string of at most N bytes stored inline (CIP SHORT_STRING and STRING values, host names).
// Assign refuses a longer text instead of cutting it, so a caller cannot silently lose characters.
template <std::size_t N>
class FixedString {
 public:
  static constexpr std::size_t kCapacity = N;

  constexpr FixedString() = default;

  [[nodiscard]] constexpr bool Assign(std::span<const std::uint8_t> bytes) {
    if (bytes.size() > N) return false;
    for (std::size_t i = 0; i < bytes.size(); ++i) chars_[i] = bytes[i];
    size_ = bytes.size();
    return true;
  }
  [[nodiscard]] constexpr bool Assign(std::string_view text) {
    if (text.size() > N) return false;
    for (std::size_t i = 0; i < text.size(); ++i) chars_[i] = static_cast<std::uint8_t>(text[i]);
    size_ = text.size();
    return true;
  }
  constexpr std::size_t size() const { return size_; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr std::span<const std::uint8_t> bytes() const { return std::span<const std::uint8_t>(chars_).first(size_); }
  constexpr bool operator==(const FixedString& other) const {
    if (size_ != other.size_) return false;
    for (std::size_t i = 0; i < size_; ++i) {
      if (chars_[i] != other.chars_[i]) return false;
    }
    return true;
  }

 private:
  std::array<std::uint8_t, N> chars_{};
  std::size_t size_ = 0;
};

// struct sockaddr_in as EtherNet/IP carries it: 16 bytes, every field big-endian,
// 8 zero bytes at the end. Addresses are host-order integers here (10.0.2.15 = 0x0A00020F).
struct SocketAddress {
  static constexpr std::size_t kWireSize = 16;
  static constexpr std::uint16_t kAfInet = 2;

  std::uint16_t family = kAfInet;
  std::uint16_t port = 0;
  std::uint32_t address = 0;

  constexpr bool operator==(const SocketAddress&) const = default;
};

inline void EncodeSocketAddress(const SocketAddress& address, base::ByteWriter& out) {
  out.U16Be(address.family);
  out.U16Be(address.port);
  out.U32Be(address.address);
  out.Zeros(8);
}

// Reads the 16 bytes; the zero padding is not checked (receivers ignore it).
inline SocketAddress DecodeSocketAddress(base::ByteReader& in) {
  SocketAddress address;
  address.family = in.U16Be();
  address.port = in.U16Be();
  address.address = in.U32Be();
  in.Skip(8);
  return address;
}

}  // namespace cip
