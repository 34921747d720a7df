// ARP over Ethernet for IPv4 (RFC 826), the frames Address Conflict Detection sends and reads
// (RFC 5227 §1.1 "ARP Probe" / "ARP Announcement"; docs/network.md "Address Conflict Detection").
//
// Frame layout, 42 bytes (the MAC pads it to 60 on the wire; padding and FCS are not ours to read):
//   0  destination MAC (6)   6  source MAC (6)   12  EtherType 0x0806 (2)
//   14 hardware type 1 (2)   16 protocol type 0x0800 (2)   18 hardware length 6   19 protocol length 4
//   20 operation 1 request / 2 reply (2)
//   22 sender MAC (6)   28 sender IPv4 (4)   32 target MAC (6)   38 target IPv4 (4)
// Bytes 14..41 are the ARP PDU that TCP/IP attribute 11 keeps verbatim.
// Not accepted: 802.1Q-tagged frames (EtherType 0x8100; the card is not VLAN-aware), ARP for other
// hardware or protocols, operations other than request and reply (RARP/InARP).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "base/status.h"

namespace net {

inline constexpr std::size_t kEthernetHeaderSize = 14;
inline constexpr std::size_t kArpPduSize = 28;
inline constexpr std::size_t kArpFrameSize = kEthernetHeaderSize + kArpPduSize;  // 42
inline constexpr std::uint16_t kEtherTypeArp = 0x0806;
inline constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
inline constexpr std::uint16_t kArpHardwareEthernet = 1;

enum class ArpOperation : std::uint16_t { kRequest = 1, kReply = 2 };

struct ArpPacket {
  base::MacAddress destination{};  // Ethernet header
  base::MacAddress source{};
  ArpOperation operation = ArpOperation::kRequest;
  base::MacAddress sender_mac{};
  base::Ipv4Address sender_ip;
  base::MacAddress target_mac{};
  base::Ipv4Address target_ip;

  bool operator==(const ArpPacket&) const = default;
};

using ArpFrame = std::array<std::uint8_t, kArpFrameSize>;

// RFC 5227 §2.1.1: broadcast request, sender IP 0.0.0.0, target MAC zero, target IP the one probed for.
ArpPacket ArpProbe(const base::MacAddress& own_mac, base::Ipv4Address probed);
// RFC 5227 §2.3: broadcast request with sender IP = target IP = the address claimed, target MAC zero.
ArpPacket ArpAnnouncement(const base::MacAddress& own_mac, base::Ipv4Address claimed);

void EncodeArpFrame(const ArpPacket& packet, std::span<std::uint8_t, kArpFrameSize> out);
ArpFrame EncodeArpFrame(const ArpPacket& packet);

// Parses the first 42 bytes of an Ethernet frame; reads nothing past `frame`'s end.
//   kOutOfRange        shorter than 42 bytes
//   kNotFound          not an ARP frame (another EtherType): nothing for ACD, pass it on
//   kInvalidArgument   ARP, but not Ethernet/IPv4 (hardware type, protocol type, lengths) or an
//                      operation other than request/reply
base::Result<ArpPacket> ParseArpFrame(std::span<const std::uint8_t> frame);

}  // namespace net
