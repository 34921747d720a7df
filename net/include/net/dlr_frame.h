// Device Level Ring frames (EtherType 0x80E1, CIP Vol 2 ch 9; docs/network.md "Ring (DLR)"): the codec
// a ring node needs. Field layouts and multicast addresses as Wireshark's DLR dissector (packet-enip.c)
// and published DLR node implementations give them; every parser is a function on a span.
//
// A DLR PDU follows the Ethernet header (with or without one 802.1Q tag) and starts with a common
// header of 12 bytes, big-endian:
//   0 ring subtype 0x02 | 1 protocol version 1 | 2 frame type | 3 source port (0 either, 1, 2)
//   4 source IP (4)     | 8 sequence id (4)
// then the fields of the frame type (offsets from the subtype):
//   Beacon 1          12 ring state (1 normal, 2 fault), 13 supervisor precedence, 14 beacon interval
//                     (µs, UDINT), 18 beacon timeout (µs, UDINT), 22..41 reserved
//   Neighbor_Check    request: 12..41 reserved; response 3: 12 request source port, 13..41 reserved
//   Link_Status 4     12 status byte (bit 0 port 1 active, bit 1 port 2 active, bit 7 set =
//                     Neighbor_Status, clear = Link_Status), 13..41 reserved
//   Locate_Fault 5    12..41 reserved
//   Announce 6        12 ring state, 13..41 reserved
//   Sign_On 7         12 number of nodes (UINT), 14.. that many (MAC 6, IP 4); padded to 42
//   Advertise 8       12 gateway state, 13 gateway precedence, 14 advertise interval, 18 advertise
//                     timeout, 22 learning update enable, 23..41 reserved
//   Flush_Tables 9    12 learning update enable (0/1), 13..41 reserved
//   Learning_Update 10 12..45 reserved (46 bytes: the frame is sent untagged, so 14 + 46 = 60)
// Every fixed-size PDU is 42 bytes: with the 18-byte tagged Ethernet header that is exactly the 60-byte
// minimum frame, which is the length the dissector reads. The parser requires the defined fields only,
// not the reserved tail (a TAP port delivers frames unpadded).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "base/status.h"

namespace net {

inline constexpr std::uint16_t kDlrEtherType = 0x80E1;
inline constexpr std::uint16_t kVlanTagType = 0x8100;
inline constexpr std::uint8_t kDlrRingSubtype = 0x02;
inline constexpr std::uint8_t kDlrProtocolVersion = 1;

// Frames the node builds carry an 802.1Q tag with VLAN id 0 (priority-tagged) and priority 7, the
// highest, as DLR frames do on the wire (docs/network.md); Learning_Update alone is untagged.
inline constexpr std::uint16_t kDlrTagControl = 0xE000;  // PCP 7, DEI 0, VID 0

inline constexpr std::size_t kDlrCommonHeaderSize = 12;
inline constexpr std::size_t kDlrPduSize = 42;             // every fixed-size frame type
inline constexpr std::size_t kDlrLearningUpdatePduSize = 46;
inline constexpr std::size_t kEthernetMinFrameSize = 60;   // without FCS
inline constexpr std::size_t kDlrMaxPayload = 1500;        // the Ethernet MTU bounds a Sign_On list
inline constexpr std::size_t kDlrSignOnEntrySize = 10;     // MAC 6 + IP 4

// Destination group addresses.
inline constexpr base::MacAddress kDlrBeaconMac{0x01, 0x21, 0x6C, 0x00, 0x00, 0x01};
inline constexpr base::MacAddress kDlrNeighborCheckMac{0x01, 0x21, 0x6C, 0x00, 0x00, 0x02};  // and Sign_On
inline constexpr base::MacAddress kDlrAnnounceMac{0x01, 0x21, 0x6C, 0x00, 0x00, 0x03};  // also Locate_Fault
inline constexpr base::MacAddress kDlrAdvertiseMac{0x01, 0x21, 0x6C, 0x00, 0x00, 0x04};
inline constexpr base::MacAddress kDlrLearningUpdateMac{0x01, 0x21, 0x6C, 0x00, 0x00, 0x05};

enum class DlrFrameType : std::uint8_t {
  kBeacon = 1,
  kNeighborCheckRequest = 2,
  kNeighborCheckResponse = 3,
  kLinkStatus = 4,  // Link_Status and Neighbor_Status (bit 7 of the status byte)
  kLocateFault = 5,
  kAnnounce = 6,
  kSignOn = 7,
  kAdvertise = 8,
  kFlushTables = 9,
  kLearningUpdate = 10,
};

enum class DlrRingState : std::uint8_t { kNormal = 1, kFault = 2 };

// The status byte of Link_Status / Neighbor_Status.
struct DlrLinkStatus {
  bool port1_active = false;
  bool port2_active = false;
  bool neighbor_status = false;  // true: Neighbor_Status (a neighbour check failed); false: Link_Status

  std::uint8_t Encode() const;
  static DlrLinkStatus Decode(std::uint8_t byte);
  bool operator==(const DlrLinkStatus&) const = default;
};

// A parsed DLR frame. Fields that a frame type does not have stay at their defaults.
struct DlrFrame {
  base::MacAddress destination;
  base::MacAddress source;
  bool tagged = false;
  std::uint16_t tag_control = 0;  // the 802.1Q TCI when tagged
  std::size_t pdu_offset = 0;     // where the ring subtype is in the frame (14 or 18)

  DlrFrameType type = DlrFrameType::kBeacon;
  std::uint8_t source_port = 0;
  base::Ipv4Address source_ip;
  std::uint32_t sequence_id = 0;

  DlrRingState ring_state = DlrRingState::kNormal;  // Beacon, Announce
  std::uint8_t precedence = 0;                      // Beacon (supervisor), Advertise (gateway)
  std::uint32_t interval_us = 0;                    // Beacon interval, Advertise interval
  std::uint32_t timeout_us = 0;                     // Beacon timeout, Advertise timeout
  std::uint8_t gateway_state = 0;                   // Advertise
  bool learning_update_enable = false;              // Flush_Tables, Advertise
  std::uint8_t request_source_port = 0;             // Neighbor_Check_Response
  DlrLinkStatus link_status;                        // Link_Status / Neighbor_Status
  std::uint16_t sign_on_nodes = 0;                  // Sign_On: entries in the list
};

// Parses an Ethernet frame. kNotFound: not a DLR frame (another EtherType, or shorter than an Ethernet
// header). kOutOfRange: shorter than its frame type's fields (a Sign_On whose node count does not fit).
// kInvalidArgument: wrong subtype or version, unknown frame type, a ring state other than 1/2.
base::Result<DlrFrame> ParseDlrFrame(std::span<const std::uint8_t> frame);
// Whether `frame` carries EtherType 0x80E1, after the addresses or after one 802.1Q tag: the cheap test
// of the card's receive path (ParseDlrFrame answers kNotFound for exactly the other frames).
bool IsDlrFrame(std::span<const std::uint8_t> frame);

// The MAC/IP entry `index` (< sign_on_nodes) of a Sign_On that ParseDlrFrame accepted.
struct DlrNode {
  base::MacAddress mac;
  base::Ipv4Address ip;
};
DlrNode SignOnNode(std::span<const std::uint8_t> frame, const DlrFrame& parsed, std::size_t index);

// ---- Builders: what a ring node sends. Each writes a whole frame, padded to 60 bytes, into `out` and
// returns its length (kResourceExhausted when `out` is too small). -----------------------------------

// The addressing and common-header fields of a frame the node originates.
struct DlrOrigin {
  base::MacAddress destination;
  base::MacAddress source;       // the node's MAC
  std::uint8_t source_port = 0;  // 1 or 2: the ring port the frame leaves on
  base::Ipv4Address source_ip;   // the node's IP (0.0.0.0 before it has one)
  std::uint32_t sequence_id = 0;
};

base::Result<std::size_t> BuildNeighborCheckRequest(const DlrOrigin& origin, std::span<std::uint8_t> out);
// `origin.sequence_id` is the request's; `request_source_port` the request's source port.
base::Result<std::size_t> BuildNeighborCheckResponse(const DlrOrigin& origin, std::uint8_t request_source_port,
                                                     std::span<std::uint8_t> out);
// Link_Status or Neighbor_Status (status.neighbor_status), unicast to the active supervisor.
base::Result<std::size_t> BuildLinkStatus(const DlrOrigin& origin, DlrLinkStatus status,
                                          std::span<std::uint8_t> out);
// Untagged, 60 bytes (the 46-byte PDU).
base::Result<std::size_t> BuildLearningUpdate(const DlrOrigin& origin, std::span<std::uint8_t> out);

// The Sign_On a node passes on: the received frame (`parsed` from ParseDlrFrame) with the node's MAC as
// Ethernet source, `destination` as Ethernet destination (the received group address, or the
// supervisor's MAC), and, when `append` is set, the node's MAC/IP appended and the count raised; padded
// to 60. kResourceExhausted when `out` is too small or the list would pass kDlrMaxPayload.
base::Result<std::size_t> BuildSignOn(std::span<const std::uint8_t> received, const DlrFrame& parsed,
                                      const base::MacAddress& destination, const DlrNode& self, bool append,
                                      std::span<std::uint8_t> out);
// Whether one more entry fits in a Sign_On of `nodes` entries within kDlrMaxPayload.
constexpr bool SignOnHasRoom(std::uint16_t nodes) {
  return kDlrCommonHeaderSize + 2 + (static_cast<std::size_t>(nodes) + 1) * kDlrSignOnEntrySize <= kDlrMaxPayload;
}

}  // namespace net
