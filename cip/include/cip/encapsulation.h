// EtherNet/IP encapsulation, wire format only (CIP Vol. 2 ch. 2): the 24-byte header, the command and
// status codes, and the bodies of the three discovery replies (ListIdentity, ListServices,
// ListInterfaces). What the card does with each command (sessions, replies, delays) is
// encapsulation_server.h's business.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/wire_types.h"

namespace cip {

inline constexpr std::uint16_t kEncapsulationPort = 44818;  // TCP and UDP
inline constexpr std::size_t kEncapsulationHeaderSize = 24;
inline constexpr std::uint16_t kEncapsulationProtocolVersion = 1;

enum class EncapCommand : std::uint16_t {
  kNop = 0x0000,                // TCP only; never answered
  kListServices = 0x0004,       // TCP or UDP
  kListIdentity = 0x0063,       // TCP or UDP (UDP broadcast answered after a random delay)
  kListInterfaces = 0x0064,     // TCP or UDP
  kRegisterSession = 0x0065,    // TCP only
  kUnRegisterSession = 0x0066,  // TCP only; never answered when the handle is valid
  kSendRRData = 0x006F,         // TCP only: unconnected (UCMM) request/reply
  kSendUnitData = 0x0070,       // TCP only: connected (class 3) data
};

// Status field of a reply header.
enum class EncapStatus : std::uint32_t {
  kSuccess = 0x0000,
  kInvalidCommand = 0x0001,        // unknown command, or not allowed (2nd RegisterSession on a connection)
  kInsufficientMemory = 0x0002,    // session table full; message longer than the receive buffer
  kIncorrectData = 0x0003,         // malformed command-specific data (Common Packet Format)
  kInvalidSessionHandle = 0x0064,  // no such session on this TCP connection
  kInvalidLength = 0x0065,         // length field wrong for the command
  kUnsupportedProtocol = 0x0069,   // RegisterSession with a version other than 1 or options other than 0
};

struct EncapsulationHeader {
  std::uint16_t command = 0;
  std::uint16_t length = 0;  // bytes of command-specific data after the header
  std::uint32_t session_handle = 0;
  std::uint32_t status = 0;
  std::array<std::uint8_t, 8> sender_context{};
  std::uint32_t options = 0;

  constexpr bool operator==(const EncapsulationHeader&) const = default;
};

// Decodes the first 24 bytes of `bytes` (anything after them is the caller's); kOutOfRange when fewer
// than 24 bytes are given.
base::Result<EncapsulationHeader> DecodeEncapsulationHeader(std::span<const std::uint8_t> bytes);
void EncodeEncapsulationHeader(const EncapsulationHeader& header, base::ByteWriter& out);

// The reply header for a request: command, session handle and sender context echoed, options 0.
// `length` is patched by whoever writes the reply data.
EncapsulationHeader ReplyHeaderFor(const EncapsulationHeader& request, EncapStatus status);

// Common Packet Format item types of the discovery replies.
inline constexpr std::uint16_t kItemListIdentity = 0x000C;
inline constexpr std::uint16_t kItemListServices = 0x0100;

// What a ListIdentity reply says about the device (the CIP fields are the Identity
// object's attributes 1-7, `state` its attribute 8).
struct IdentityItem {
  SocketAddress socket_address;  // the card's own IP and TCP port 44818
  std::uint16_t vendor_id = 0;
  std::uint16_t device_type = 0;
  std::uint16_t product_code = 0;
  std::uint8_t major_revision = 0;
  std::uint8_t minor_revision = 0;
  std::uint16_t status = 0;
  std::uint32_t serial_number = 0;
  FixedString<32> product_name;
  std::uint8_t state = 0;
};

// The command-specific data of each discovery reply: an item count and the items.
void EncodeListIdentityData(const IdentityItem& identity, base::ByteWriter& out);
void EncodeListServicesData(base::ByteWriter& out);
void EncodeListInterfacesData(base::ByteWriter& out);

// ListServices "Communications" capability flags.
inline constexpr std::uint16_t kCapabilityCipOverTcp = 0x0020;
inline constexpr std::uint16_t kCapabilityCipClass0And1OverUdp = 0x0100;

}  // namespace cip
