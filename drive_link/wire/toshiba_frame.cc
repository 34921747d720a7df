// Mode-independent parts of the Toshiba inverter protocol codec: checksums, addressing, the error-reply
// rules, and the dispatch on the start code that picks the ASCII or binary codec.
#include "drive_link/wire/toshiba_frame.h"

#include <array>

#include "toshiba_internal.h"

namespace drive_link::wire {
namespace {

struct FaultRow {
  FrameFault fault;
  const char* name;
  // The inverter's answer in each mode (4.3); nullopt = silence.
  std::optional<ErrorCode> ascii_reply;
  std::optional<ErrorCode> binary_reply;
};

constexpr std::optional<ErrorCode> kSilent = std::nullopt;

// One row per fault, in enum order (checked below), so the names and the answers cannot drift apart.
constexpr std::array<FaultRow, 16> kFaults = {{
    {FrameFault::kNone, "none", kSilent, kSilent},
    {FrameFault::kTruncated, "truncated", kSilent, kSilent},
    {FrameFault::kTrailingBytes, "trailing bytes", kSilent, kSilent},
    {FrameFault::kTooLong, "too long", kSilent, kSilent},
    {FrameFault::kBadStartCode, "bad start code", kSilent, kSilent},
    {FrameFault::kBadInverterNumber, "bad inverter number", kSilent, kSilent},
    {FrameFault::kBadStopCode, "bad stop code", kSilent, kSilent},
    // "Command error: 0003 (ASCII mode), no code returned (binary mode)" (p.21).
    {FrameFault::kUnknownCommand, "unknown command", ErrorCode::kCommandError, kSilent},
    {FrameFault::kBadChecksum, "bad checksum", ErrorCode::kChecksumError, ErrorCode::kChecksumError},
    // "(R0))))CR: 0))) is recognized as a communication number" -> 0002 (p.21).
    {FrameFault::kBadCommunicationNumber, "bad communication number", ErrorCode::kCommunicationNumberError,
     kSilent},
    // "Data error: ... it is composed of too many digits" (p.10).
    {FrameFault::kBadData, "bad data", ErrorCode::kDataError, kSilent},
    {FrameFault::kBadErrorCode, "bad error code", kSilent, kSilent},
    // "If specified outside of the range, data will be treated as a format error" (p.14).
    {FrameFault::kBadBlockWriteCount, "bad block write count", kSilent, kSilent},
    {FrameFault::kBadBlockReadCount, "bad block read count", kSilent, kSilent},
    // "When the maintenance command (M) is issued, an impossible-to-execute error occurs" (p.21).
    {FrameFault::kMaintenanceCommand, "maintenance command", ErrorCode::kImpossibleToExecute, kSilent},
    // S is never answered (p.20); we do not implement inter-drive communication at all.
    {FrameFault::kInterDriveCommand, "inter-drive command (unsupported)", kSilent, kSilent},
}};

constexpr bool FaultTableInEnumOrder() {
  for (std::size_t i = 0; i < kFaults.size(); ++i) {
    if (static_cast<std::size_t>(kFaults[i].fault) != i) return false;
  }
  return true;
}
static_assert(FaultTableInEnumOrder(), "kFaults must list every FrameFault in declaration order");

const FaultRow* FindFault(FrameFault fault) {
  const auto index = static_cast<std::size_t>(fault);
  return index < kFaults.size() ? &kFaults[index] : nullptr;
}

std::uint8_t SumLowByte(std::span<const std::uint8_t> bytes) {
  unsigned sum = 0;
  for (std::uint8_t byte : bytes) sum += byte;
  return static_cast<std::uint8_t>(sum & 0xFFU);
}

// Membership of a digit-group broadcast ("*n": ones digit n, "n*": tens digit n); the representative has
// 0 in the '*' position (p.22).
Addressing ResolveDigitGroup(std::uint8_t group_digit, std::uint8_t own_digit, std::uint8_t star_digit) {
  if (own_digit != group_digit) return Addressing::kIgnore;
  return star_digit == 0 ? Addressing::kExecuteAndReply : Addressing::kExecuteSilently;
}

}  // namespace

const char* FrameFaultName(FrameFault fault) {
  const FaultRow* row = FindFault(fault);
  return row != nullptr ? row->name : "unknown fault";
}

std::optional<ErrorCode> ErrorReplyFor(Mode mode, FrameFault fault) {
  const FaultRow* row = FindFault(fault);
  if (row == nullptr) return std::nullopt;
  return mode == Mode::kAscii ? row->ascii_reply : row->binary_reply;
}

std::optional<ErrorCode> ErrorReplyFor(const DecodedRequest& decoded) {
  const Mode mode = decoded.kind == RequestKind::kBlock ? Mode::kBinary : decoded.request.envelope.mode;
  return ErrorReplyFor(mode, decoded.fault);
}

std::uint8_t BinaryChecksum(std::span<const std::uint8_t> bytes) { return SumLowByte(bytes); }

std::array<std::uint8_t, 2> AsciiChecksum(std::span<const std::uint8_t> bytes) {
  const std::uint8_t sum = SumLowByte(bytes);
  return {internal::HexCharacter(sum >> 4), internal::HexCharacter(sum & 0x0FU)};
}

Addressing ResolveAddress(Mode mode, InverterAddress address, std::uint8_t own_number) {
  const std::uint8_t highest = mode == Mode::kAscii ? kMaxAsciiInverterNumber : kMaxBinaryInverterNumber;
  const bool member = own_number <= highest;
  const auto ones = static_cast<std::uint8_t>(own_number % 10);
  const auto tens = static_cast<std::uint8_t>(own_number / 10);
  switch (address.kind) {
    case InverterAddress::Kind::kOmitted:
      return Addressing::kExecuteAndReply;  // one-to-one link: every frame is ours
    case InverterAddress::Kind::kNumber:
      return address.value == own_number && member ? Addressing::kExecuteAndReply : Addressing::kIgnore;
    case InverterAddress::Kind::kBroadcast:
      if (!member) return Addressing::kIgnore;
      return own_number == 0 ? Addressing::kExecuteAndReply : Addressing::kExecuteSilently;
    case InverterAddress::Kind::kOnesDigitGroup:
      if (!member || mode != Mode::kAscii) return Addressing::kIgnore;
      return ResolveDigitGroup(address.value, ones, tens);
    case InverterAddress::Kind::kTensDigitGroup:
      if (!member || mode != Mode::kAscii) return Addressing::kIgnore;
      return ResolveDigitGroup(address.value, tens, ones);
  }
  return Addressing::kIgnore;
}

InverterAddress ReplyAddress(InverterAddress request, std::uint8_t own_number) {
  if (request.kind == InverterAddress::Kind::kOmitted) return InverterAddress::Omitted();
  return InverterAddress::Number(own_number);
}

Envelope ReplyEnvelope(const Envelope& request, std::uint8_t own_number) {
  Envelope reply = request;
  reply.address = ReplyAddress(request.address, own_number);
  return reply;
}

std::uint8_t ReadGroupsToReturn(const BlockRequest& request) {
  return request.read_count <= kMaxBlockReads ? request.read_count : 0;
}

DecodedRequest DecodeRequest(std::span<const std::uint8_t> frame, BlockWriteLimit block_limit) {
  if (!frame.empty() && frame[0] == kAsciiStartCode) return internal::DecodeAsciiRequest(frame);
  if (!frame.empty() && frame[0] == kBinaryStartCode) return internal::DecodeBinaryRequest(frame, block_limit);
  DecodedRequest decoded;
  decoded.fault = frame.empty() ? FrameFault::kTruncated : FrameFault::kBadStartCode;
  return decoded;
}

DecodedReply DecodeReply(std::span<const std::uint8_t> frame) {
  if (!frame.empty() && frame[0] == kAsciiStartCode) return internal::DecodeAsciiReply(frame);
  if (!frame.empty() && frame[0] == kBinaryStartCode) return internal::DecodeBinaryReply(frame);
  DecodedReply decoded;
  decoded.fault = frame.empty() ? FrameFault::kTruncated : FrameFault::kBadStartCode;
  return decoded;
}

base::Result<std::size_t> EncodeRequest(const Request& request, std::span<std::uint8_t> out) {
  return request.envelope.mode == Mode::kAscii ? internal::EncodeAsciiRequest(request, out)
                                               : internal::EncodeBinaryRequest(request, out);
}

base::Result<std::size_t> EncodeReply(const Reply& reply, std::span<std::uint8_t> out) {
  return reply.envelope.mode == Mode::kAscii ? internal::EncodeAsciiReply(reply, out)
                                             : internal::EncodeBinaryReply(reply, out);
}

base::Result<std::size_t> EncodeErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out) {
  return reply.envelope.mode == Mode::kAscii ? internal::EncodeAsciiErrorReply(reply, out)
                                             : internal::EncodeBinaryErrorReply(reply, out);
}

namespace internal {

void PutHex(base::ByteWriter& writer, std::uint16_t value, std::size_t digits) {
  for (std::size_t i = digits; i > 0; --i) writer.U8(HexCharacter((value >> (4 * (i - 1))) & 0x0FU));
}

std::optional<std::uint16_t> ParseHex(std::span<const std::uint8_t> digits) {
  if (digits.size() > 4) return std::nullopt;
  unsigned value = 0;
  for (std::uint8_t c : digits) {
    if (!IsHexDigit(c)) return std::nullopt;
    const unsigned nibble = IsDecimalDigit(c) ? c - '0' : (c | 0x20U) - 'a' + 10U;
    value = (value << 4) | nibble;
  }
  return static_cast<std::uint16_t>(value);
}

std::uint8_t HexCharacter(unsigned nibble) {
  static constexpr std::array<std::uint8_t, 16> kDigits = {'0', '1', '2', '3', '4', '5', '6', '7',
                                                           '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};
  return kDigits[nibble & 0x0FU];
}

}  // namespace internal
}  // namespace drive_link::wire
