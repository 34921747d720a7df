// The Modbus TCP frame (ADU): the 7-byte MBAP header, then the PDU (seed 000 §8.1).
//
//   0-1 transaction id   2-3 protocol id (always 0)   4-5 length = unit byte + PDU   6 unit id   7.. PDU
//
// A TCP stream is cut into ADUs by the length field alone, so a header whose fields cannot be true
// leaves no way to find the next frame: FindFrame reports it and the connection is closed
// (docs/modbus.md "Framing").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace modbus {

inline constexpr std::size_t kMbapHeaderBytes = 7;
// The Modbus PDU is at most 253 bytes (Modbus Application Protocol 1.1b3 §4.1), so an ADU is at most
// 260 and the length field (unit + PDU) at most 254. The seed (§8.1) only says "less than 256".
inline constexpr std::size_t kMaxPduBytes = 253;
inline constexpr std::size_t kMaxAduBytes = kMbapHeaderBytes + kMaxPduBytes;
// The length field counts the unit id and at least the function code.
inline constexpr std::uint16_t kMinLengthField = 2;
inline constexpr std::uint16_t kMaxLengthField = 1 + kMaxPduBytes;

struct MbapHeader {
  std::uint16_t transaction_id = 0;
  std::uint16_t protocol_id = 0;
  std::uint16_t length = 0;  // unit id + PDU
  std::uint8_t unit_id = 0;
};

enum class FrameCheck : std::uint8_t {
  kNeedMore,   // the stream does not hold a whole ADU yet
  kComplete,   // the front of the stream is one whole ADU of `adu_length` bytes
  kBadHeader,  // the header cannot be framed (see `fault`); nothing after it can be trusted
};

enum class HeaderFault : std::uint8_t {
  kNone,
  kProtocolId,      // protocol id not 0
  kLengthTooShort,  // length 0 or 1: no room for unit id and function code
  kLengthTooLong,   // length > 254: the PDU would exceed 253 bytes
};

struct FrameResult {
  FrameCheck check = FrameCheck::kNeedMore;
  HeaderFault fault = HeaderFault::kNone;
  std::size_t adu_length = 0;  // kComplete only
  MbapHeader header;           // kComplete only
};

// Looks at the front of a received stream. A bad header is reported as soon as its first 6 bytes are
// there (protocol id and length), without waiting for the rest.
FrameResult FindFrame(std::span<const std::uint8_t> stream);

// The PDU of a whole ADU (FindFrame said kComplete for exactly these bytes).
inline std::span<const std::uint8_t> PduOf(std::span<const std::uint8_t> adu) {
  return adu.size() > kMbapHeaderBytes ? adu.subspan(kMbapHeaderBytes) : adu.last(0);
}

// Writes the answer's header: the request's transaction id, protocol id 0 and unit id, the length of
// the answer's PDU + 1.
void WriteMbapHeader(base::ByteWriter& writer, const MbapHeader& request, std::size_t answer_pdu_length);

}  // namespace modbus
