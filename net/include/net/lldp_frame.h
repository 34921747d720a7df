// LLDP frames (IEEE 802.1AB; docs/network.md "LLDP"): the card's own LLDPDU and the parser of its
// neighbours'. Pure functions on spans; no clock, no state.
//
// Frame: destination 01-80-C2-00-00-0E (nearest bridge), source = the card's MAC, EtherType 0x88CC,
// then TLVs, each a 2-byte header (type: high 7 bits, length: low 9 bits) and `length` bytes:
//   1 Chassis ID (subtype + id)   2 Port ID (subtype + id)   3 Time To Live (2 bytes, seconds)
//   optional: 4 Port Description   5 System Name   6 System Description   7 System Capabilities
//             8 Management Address   127 organisationally specific ... then 0 End (length 0).
// The first three are mandatory and come first, in this order.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/addresses.h"
#include "base/status.h"

namespace net {

inline constexpr base::MacAddress kLldpNearestBridge{0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E};
inline constexpr std::uint16_t kEtherTypeLldp = 0x88CC;

// Chassis ID and Port ID subtypes (802.1AB §8.5.2.2, §8.5.3.2) the card uses or renders specially.
inline constexpr std::uint8_t kLldpChassisMac = 4;
inline constexpr std::uint8_t kLldpChassisNetworkAddress = 5;
inline constexpr std::uint8_t kLldpPortMac = 3;
inline constexpr std::uint8_t kLldpPortNetworkAddress = 4;
inline constexpr std::uint8_t kLldpPortLocal = 7;
// System capabilities bit: bridge (802.1AB §8.5.8.1). The card's two ports are an embedded switch.
inline constexpr std::uint16_t kLldpCapabilityBridge = 0x0004;

// What the card advertises on one port. The strings are cut to 255 bytes (the TLV limit).
struct LldpAdvert {
  base::MacAddress mac{};           // Chassis ID (subtype 4) and the frame's source
  std::string_view port_id{};       // Port ID, subtype 7 (locally assigned)
  std::uint16_t ttl_seconds = 0;
  std::string_view port_description{};
  std::string_view system_name{};
  std::string_view system_description{};
  base::Ipv4Address management{};   // 0.0.0.0: no Management Address TLV
  std::uint32_t interface_number = 0;  // of the Management Address TLV (ifIndex numbering)
};

// Writes the advert's LLDPDU into `out`; its size, or kResourceExhausted when it does not fit.
base::Result<std::size_t> BuildLldpFrame(const LldpAdvert& advert, std::span<std::uint8_t> out);

// An ID or a text as received, cut to a fixed size (the table has no room for 255-byte strings).
template <std::size_t N>
struct LldpBytes {
  std::array<std::uint8_t, N> bytes{};
  std::uint8_t size = 0;

  std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
  void Assign(std::span<const std::uint8_t> from) {
    size = static_cast<std::uint8_t>(from.size() < N ? from.size() : N);
    for (std::size_t i = 0; i < size; ++i) bytes[i] = from[i];
  }
  bool operator==(const LldpBytes&) const = default;
};

inline constexpr std::size_t kLldpIdMax = 32;    // chassis and port IDs: longer ones keep their start
inline constexpr std::size_t kLldpTextMax = 32;  // system name, port description

struct LldpId {
  std::uint8_t subtype = 0;
  LldpBytes<kLldpIdMax> id;
  bool operator==(const LldpId&) const = default;
};

// What the card keeps of a neighbour's LLDPDU.
struct LldpNeighbourInfo {
  LldpId chassis;
  LldpId port;
  std::uint16_t ttl_seconds = 0;
  LldpBytes<kLldpTextMax> system_name;
  LldpBytes<kLldpTextMax> port_description;
  base::Ipv4Address management;  // the first IPv4 Management Address TLV; 0.0.0.0: none
};

// Reads an Ethernet frame. kNotFound: not an LLDP frame for the nearest-bridge address (another
// EtherType or destination). kDataLoss: an LLDPDU the card refuses: the mandatory TLVs missing or out
// of order or of a wrong length, a TLV running past the frame, a second Chassis ID/Port ID/TTL, an End
// TLV with a length, a Management Address TLV whose inner lengths do not add up. A frame that ends
// without an End TLV is accepted (the frame's end ends the list). Only the first instance of an optional
// TLV counts; unknown TLVs are skipped by their length.
base::Result<LldpNeighbourInfo> ParseLldpFrame(std::span<const std::uint8_t> frame);
// Whether `frame` is LLDP to the nearest-bridge address (ParseLldpFrame answers kNotFound for exactly
// the other frames): the cheap test for every frame the card receives.
bool IsLldpFrame(std::span<const std::uint8_t> frame);

}  // namespace net
