// Vocabulary of the network cores (docs/network.md): MAC and IPv4 addresses, and big-endian field
// access on fixed-extent spans, so that a reader can only be called where the caller has already proved
// the bytes are there (the span's extent is part of the type; a too-short view does not compile).
//
// IPv4 addresses are host-order integers (192.168.0.10 = 0xC0A8000A), as in cip::InterfaceConfiguration,
// so the wiring passes them across unchanged.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace net {

using MacAddress = std::array<std::uint8_t, 6>;
using Ipv4Address = std::uint32_t;

inline constexpr MacAddress kBroadcastMac = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
inline constexpr MacAddress kZeroMac = {0, 0, 0, 0, 0, 0};

constexpr std::uint16_t LoadBe16(std::span<const std::uint8_t, 2> bytes) {
  return static_cast<std::uint16_t>(bytes[0] << 8 | bytes[1]);
}

constexpr std::uint32_t LoadBe32(std::span<const std::uint8_t, 4> bytes) {
  return static_cast<std::uint32_t>(bytes[0]) << 24 | static_cast<std::uint32_t>(bytes[1]) << 16 |
         static_cast<std::uint32_t>(bytes[2]) << 8 | static_cast<std::uint32_t>(bytes[3]);
}

constexpr void StoreBe16(std::uint16_t value, std::span<std::uint8_t, 2> out) {
  out[0] = static_cast<std::uint8_t>(value >> 8);
  out[1] = static_cast<std::uint8_t>(value);
}

constexpr void StoreBe32(std::uint32_t value, std::span<std::uint8_t, 4> out) {
  out[0] = static_cast<std::uint8_t>(value >> 24);
  out[1] = static_cast<std::uint8_t>(value >> 16);
  out[2] = static_cast<std::uint8_t>(value >> 8);
  out[3] = static_cast<std::uint8_t>(value);
}

// Copies the 6 bytes at `bytes` (already bounds-proved by the fixed extent).
constexpr MacAddress LoadMac(std::span<const std::uint8_t, 6> bytes) {
  MacAddress mac{};
  for (std::size_t i = 0; i < mac.size(); ++i) mac[i] = bytes[i];
  return mac;
}

constexpr void StoreMac(const MacAddress& mac, std::span<std::uint8_t, 6> out) {
  for (std::size_t i = 0; i < mac.size(); ++i) out[i] = mac[i];
}

}  // namespace net
