// IPv4 and MAC addresses as value types, the one spelling every layer uses (issue 20).
//
// Both keep their octets in wire order (the order they are written in, 192.168.0.10 and
// 00:00:A0:12:34:56). An IPv4 address also converts to and from a host-order integer
// (192.168.0.10 = 0xC0A8000A), which is how masks are applied and how CIP's TCP/IP Interface object
// carries it (a UDINT); that conversion is always spelled out, never implicit. On the wire an address
// is read and written through ByteReader/ByteWriter in network order (Read/Write below).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace base {

class Ipv4Address {
 public:
  static constexpr std::size_t kSize = 4;
  using Octets = std::array<std::uint8_t, kSize>;

  constexpr Ipv4Address() = default;  // 0.0.0.0
  constexpr Ipv4Address(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d) : octets_{a, b, c, d} {}
  constexpr explicit Ipv4Address(const Octets& octets) : octets_(octets) {}
  // From a host-order integer: Ipv4Address(0xC0A8000A) is 192.168.0.10.
  constexpr explicit Ipv4Address(std::uint32_t host_order)
      : octets_{static_cast<std::uint8_t>(host_order >> 24), static_cast<std::uint8_t>(host_order >> 16),
                static_cast<std::uint8_t>(host_order >> 8), static_cast<std::uint8_t>(host_order)} {}

  constexpr const Octets& octets() const { return octets_; }
  constexpr std::uint32_t HostOrder() const {
    return static_cast<std::uint32_t>(octets_[0]) << 24 | static_cast<std::uint32_t>(octets_[1]) << 16 |
           static_cast<std::uint32_t>(octets_[2]) << 8 | static_cast<std::uint32_t>(octets_[3]);
  }
  // 0.0.0.0: "none" or "any", as each user documents.
  constexpr bool IsUnspecified() const { return HostOrder() == 0; }

  // Four bytes in network order; a short reader yields 0.0.0.0 and fails (ByteReader's sticky rule).
  static constexpr Ipv4Address Read(ByteReader& in) { return Ipv4Address(in.U32Be()); }
  constexpr void Write(ByteWriter& out) const { out.Bytes(octets_); }

  constexpr bool operator==(const Ipv4Address&) const = default;

 private:
  Octets octets_{};
};

class MacAddress {
 public:
  static constexpr std::size_t kSize = 6;
  using Octets = std::array<std::uint8_t, kSize>;

  constexpr MacAddress() = default;  // 00:00:00:00:00:00
  constexpr MacAddress(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d, std::uint8_t e,
                       std::uint8_t f)
      : octets_{a, b, c, d, e, f} {}
  constexpr explicit MacAddress(const Octets& octets) : octets_(octets) {}

  constexpr const Octets& octets() const { return octets_; }
  // The octets in wire order, for copying them out (a MAC is often handled as 6 raw bytes).
  constexpr Octets::const_iterator begin() const { return octets_.begin(); }
  constexpr Octets::const_iterator end() const { return octets_.end(); }
  // Group bit: the least significant bit of the first octet (broadcast included).
  constexpr bool IsMulticast() const { return (octets_[0] & 0x01U) != 0; }

  // Six bytes in wire order; a short reader yields 00:00:00:00:00:00 and fails.
  static constexpr MacAddress Read(ByteReader& in) {
    const auto bytes = in.Bytes(kSize);
    Octets octets{};
    for (std::size_t i = 0; i < bytes.size(); ++i) octets[i] = bytes[i];
    return MacAddress(octets);
  }
  constexpr void Write(ByteWriter& out) const { out.Bytes(octets_); }

  constexpr bool operator==(const MacAddress&) const = default;

 private:
  Octets octets_{};
};

inline constexpr MacAddress kBroadcastMac{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
inline constexpr MacAddress kZeroMac{};

}  // namespace base
