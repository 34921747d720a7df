// Common Packet Format (CIP Vol. 2 ch. 2): the item list inside SendRRData and SendUnitData (and, on UDP
// 2222, class 0/1 I/O). Decoding is strict: the item count must match the items present, every item
// must fit, and nothing may follow the last item. The item layout each command expects is checked by
// ParseUnconnectedMessage / ParseConnectedMessage; a packet failing any check is answered with
// encapsulation status 0x0003 (incorrect data) by the server.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/status.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/wire_types.h"

namespace cip {

enum class CpfItemType : std::uint16_t {
  kNullAddress = 0x0000,       // address item of unconnected messages, length 0
  kListIdentity = 0x000C,      // ListIdentity reply
  kConnectedAddress = 0x00A1,  // connection ID, length 4
  kConnectedData = 0x00B1,     // class 3: sequence count + message; class 0/1: I/O data
  kUnconnectedData = 0x00B2,   // UCMM message router request/reply
  kListServices = 0x0100,      // ListServices reply
  kSockaddrOtoT = 0x8000,      // socket address info originator -> target, length 16
  kSockaddrTtoO = 0x8001,      // socket address info target -> originator, length 16
  kSequencedAddress = 0x8002,  // connection ID + sequence number (UDP I/O), length 8
};

// More items than this is not a valid packet for any command the card accepts (SendRRData carries at
// most null address + unconnected data + two socket address items).
inline constexpr std::size_t kMaxCpfItems = 4;

struct CpfItem {
  std::uint16_t type = 0;
  std::span<const std::uint8_t> data;
};

struct CpfPacket {
  std::array<CpfItem, kMaxCpfItems> items{};
  std::size_t count = 0;
};

// Splits `bytes` (starting at the item count) into items. kOutOfRange: an item header or body runs
// past the end, or the count field is missing. kInvalidArgument: more than kMaxCpfItems items, or
// bytes left after the last item.
base::Result<CpfPacket> DecodeCpf(std::span<const std::uint8_t> bytes);

// The command-specific data of SendRRData and SendUnitData: interface handle (0 for CIP), timeout
// (ignored by a target) and the packet. Errors as DecodeCpf; kOutOfRange when shorter than 8 bytes.
struct SendDataCommand {
  std::uint32_t interface_handle = 0;
  std::uint16_t timeout = 0;
  CpfPacket packet;
};
base::Result<SendDataCommand> DecodeSendDataCommand(std::span<const std::uint8_t> bytes);

// SendRRData: null address item, unconnected data item, then at most one socket address item of each
// direction (Forward_Open). kInvalidArgument for any other layout.
struct UnconnectedMessage {
  std::span<const std::uint8_t> request;  // the message router request
  std::optional<SocketAddress> o_to_t;
  std::optional<SocketAddress> t_to_o;
};
base::Result<UnconnectedMessage> ParseUnconnectedMessage(const CpfPacket& packet);

// SendUnitData: connected address item (connection ID) and connected data item (2-byte sequence
// count, then the message router request). kInvalidArgument for any other layout.
struct ConnectedMessage {
  std::uint32_t connection_id = 0;
  std::uint16_t sequence_count = 0;
  std::span<const std::uint8_t> request;
};
base::Result<ConnectedMessage> ParseConnectedMessage(const CpfPacket& packet);

// Item writing: BeginCpfItem writes the type and a zero length and returns where the length is;
// FinishCpfItem patches it with the bytes written since.
std::size_t BeginCpfItem(base::ByteWriter& out, CpfItemType type);
void FinishCpfItem(base::ByteWriter& out, std::size_t length_at);
void EncodeSockaddrItem(base::ByteWriter& out, CpfItemType type, const SocketAddress& address);

}  // namespace cip
