// ASCII mode of the Toshiba inverter protocol (4.1.1, p.8-10):
//
//   "(" [INV-NO 2] LETTER FIELD 4 [DATA 0-4 hex] ["&" SUM 2] [")"] CR
//
// FIELD is the communication number, or an error reply's code. The frame is cut by position, as the
// inverter does: whatever 4 characters follow the letter are the field ("(R0))))" asks for number
// "0)))"), and only then may the frame end.
#include <array>

#include "drive_link/wire/toshiba_frame.h"
#include "toshiba_internal.h"

namespace drive_link::wire::internal {
namespace {

constexpr std::size_t kFieldLength = 4;
constexpr std::size_t kMaxDataDigits = 4;

struct AsciiParts {
  InverterAddress address;
  std::uint8_t letter = 0;
  std::span<const std::uint8_t> field;
  std::span<const std::uint8_t> digits;         // hex digits after the field
  bool has_checksum = false;
  std::span<const std::uint8_t> checksum_area;  // "(" through "&"
  std::span<const std::uint8_t> sum;            // the 2 characters after "&"
  bool has_stop_code = false;
};

bool IsAddressCharacter(std::uint8_t c) { return IsDecimalDigit(c) || c == '*'; }

InverterAddress AddressFromPair(std::uint8_t first, std::uint8_t second) {
  const auto digit = [](std::uint8_t c) { return static_cast<std::uint8_t>(c - '0'); };
  if (first == '*' && second == '*') return InverterAddress::Broadcast();
  if (first == '*') return InverterAddress::OnesDigitGroup(digit(second));
  if (second == '*') return InverterAddress::TensDigitGroup(digit(first));
  return InverterAddress::Number(static_cast<std::uint8_t>(digit(first) * 10 + digit(second)));
}

// The optional inverter number: present when the character after "(" is a digit or '*' (letters start
// the command). A one-digit number is a format error (p.8); replies carry plain numbers only.
FrameFault ReadAddress(Cursor& cursor, bool wildcards_allowed, InverterAddress& address) {
  const std::optional<std::uint8_t> next = cursor.Peek();
  if (!next.has_value() || !IsAddressCharacter(*next)) return FrameFault::kNone;
  std::span<const std::uint8_t> pair;
  if (!cursor.TakeSpan(2, pair)) return FrameFault::kTruncated;
  if (!IsAddressCharacter(pair[1])) return FrameFault::kBadInverterNumber;
  const bool wildcard = pair[0] == '*' || pair[1] == '*';
  if (wildcard && !wildcards_allowed) return FrameFault::kBadInverterNumber;
  address = AddressFromPair(pair[0], pair[1]);
  return FrameFault::kNone;
}

// Cuts a frame into its parts. Every fault found here is a format error: the inverter stays silent.
FrameFault SplitAsciiFrame(std::span<const std::uint8_t> frame, bool wildcards_allowed, AsciiParts& parts) {
  if (frame.size() > kMaxFrameLength) return FrameFault::kTooLong;
  Cursor cursor(frame);
  std::uint8_t byte = 0;
  if (!cursor.Take(byte)) return FrameFault::kTruncated;
  if (byte != kAsciiStartCode) return FrameFault::kBadStartCode;
  if (const FrameFault fault = ReadAddress(cursor, wildcards_allowed, parts.address);
      fault != FrameFault::kNone) {
    return fault;
  }
  if (!cursor.Take(parts.letter) || !cursor.TakeSpan(kFieldLength, parts.field)) return FrameFault::kTruncated;
  parts.digits = cursor.TakeWhile(IsHexDigit);
  parts.has_checksum = cursor.TakeIf(kAsciiChecksumMark);
  if (parts.has_checksum) {
    parts.checksum_area = cursor.consumed();
    if (!cursor.TakeSpan(2, parts.sum)) return FrameFault::kTruncated;
  }
  parts.has_stop_code = cursor.TakeIf(kAsciiStopCode);
  if (!cursor.Take(byte)) return FrameFault::kTruncated;
  if (byte != kCarriageReturn) return FrameFault::kBadStopCode;
  if (cursor.remaining() != 0) return FrameFault::kTrailingBytes;
  return FrameFault::kNone;
}

// The SUM characters are compared case-blind; a non-hex SUM is simply a mismatch (0004).
bool ChecksumMatches(const AsciiParts& parts) {
  if (!parts.has_checksum) return true;
  const std::array<std::uint8_t, 2> expected = AsciiChecksum(parts.checksum_area);
  const auto upper = [](std::uint8_t c) { return c >= 'a' && c <= 'z' ? static_cast<std::uint8_t>(c - 0x20) : c; };
  return upper(parts.sum[0]) == expected[0] && upper(parts.sum[1]) == expected[1];
}

Envelope EnvelopeOf(const AsciiParts& parts) {
  return {.mode = Mode::kAscii,
          .address = parts.address,
          .ascii_checksum = parts.has_checksum,
          .ascii_stop_code = parts.has_stop_code};
}

// Checks in the order the inverter's answers imply: the checksum vouches for everything else, then the
// command, then the communication number, then the data (4.3).
FrameFault ReadRequestFields(const AsciiParts& parts, Request& request) {
  if (!ChecksumMatches(parts)) return FrameFault::kBadChecksum;
  if (parts.letter == kMaintenanceLetter) return FrameFault::kMaintenanceCommand;
  // Only R, W and P exist in ASCII; G, S, X and lowercase letters are command errors (p.10).
  if (parts.letter != 'R' && parts.letter != 'W' && parts.letter != 'P') return FrameFault::kUnknownCommand;
  request.command = static_cast<Command>(parts.letter);
  const std::optional<std::uint16_t> number = ParseHex(parts.field);
  if (!number.has_value()) return FrameFault::kBadCommunicationNumber;
  request.comm_number = *number;
  if (request.command == Command::kRead) {
    // R takes no data: any digit is one too many.
    return parts.digits.empty() ? FrameFault::kNone : FrameFault::kBadData;
  }
  if (parts.digits.size() > kMaxDataDigits) return FrameFault::kBadData;
  request.data = ParseHex(parts.digits).value_or(0);
  request.ascii_data_digits = static_cast<std::uint8_t>(parts.digits.size());
  return FrameFault::kNone;
}

FrameFault ReadReplyFields(const AsciiParts& parts, DecodedReply& decoded) {
  if (!ChecksumMatches(parts)) return FrameFault::kBadChecksum;
  const ReplyLetter letter = ReadReplyLetter(parts.letter);
  if (letter.upper == kErrorReplyLetter) {
    decoded.kind = ReplyKind::kError;
    decoded.error.tripped = letter.tripped;
    const std::optional<std::uint16_t> code = ParseHex(parts.field);
    if (!code.has_value() || *code > static_cast<std::uint16_t>(ErrorCode::kChecksumError)) {
      return FrameFault::kBadErrorCode;
    }
    decoded.error.code = static_cast<ErrorCode>(*code);
    return parts.digits.empty() ? FrameFault::kNone : FrameFault::kBadData;
  }
  if (letter.upper != 'R' && letter.upper != 'W' && letter.upper != 'P') return FrameFault::kUnknownCommand;
  Reply& reply = decoded.reply;
  reply.command = static_cast<Command>(letter.upper);
  reply.tripped = letter.tripped;
  const std::optional<std::uint16_t> number = ParseHex(parts.field);
  if (!number.has_value()) return FrameFault::kBadCommunicationNumber;
  reply.comm_number = *number;
  // Replies always carry 4 digits: W/P echoes are zero-padded (p.9).
  if (parts.digits.size() != kMaxDataDigits) return FrameFault::kBadData;
  reply.data = ParseHex(parts.digits).value_or(0);
  return FrameFault::kNone;
}

// Writes the inverter number; false if this frame cannot carry it.
bool PutAddress(base::ByteWriter& writer, InverterAddress address, bool wildcards_allowed) {
  const auto digit = [](std::uint8_t d) { return static_cast<std::uint8_t>('0' + d); };
  switch (address.kind) {
    case InverterAddress::Kind::kOmitted:
      return true;
    case InverterAddress::Kind::kNumber:
      if (address.value > kMaxAsciiInverterNumber) return false;
      writer.U8(digit(address.value / 10));
      writer.U8(digit(address.value % 10));
      return true;
    case InverterAddress::Kind::kBroadcast:
      writer.U8('*');
      writer.U8('*');
      return wildcards_allowed;
    case InverterAddress::Kind::kOnesDigitGroup:
      writer.U8('*');
      writer.U8(digit(address.value));
      return wildcards_allowed && address.value <= 9;
    case InverterAddress::Kind::kTensDigitGroup:
      writer.U8(digit(address.value));
      writer.U8('*');
      return wildcards_allowed && address.value <= 9;
  }
  return false;
}

// "&" SUM and ")" as the envelope asks, then CR.
base::Result<std::size_t> FinishFrame(base::ByteWriter& writer, const Envelope& envelope) {
  if (envelope.ascii_checksum) {
    writer.U8(kAsciiChecksumMark);
    const std::array<std::uint8_t, 2> sum = AsciiChecksum(writer.written());
    writer.U8(sum[0]);
    writer.U8(sum[1]);
  }
  if (envelope.ascii_stop_code) writer.U8(kAsciiStopCode);
  writer.U8(kCarriageReturn);
  return writer.Finish();
}

bool DataFitsDigits(std::uint16_t data, std::uint8_t digits) {
  if (digits > kMaxDataDigits) return false;
  return digits == kMaxDataDigits || data < (1U << (4U * digits));
}

}  // namespace

DecodedRequest DecodeAsciiRequest(std::span<const std::uint8_t> frame) {
  DecodedRequest decoded;
  decoded.request.envelope.mode = Mode::kAscii;
  AsciiParts parts;
  decoded.fault = SplitAsciiFrame(frame, /*wildcards_allowed=*/true, parts);
  if (decoded.fault != FrameFault::kNone) return decoded;
  decoded.request.envelope = EnvelopeOf(parts);
  decoded.fault = ReadRequestFields(parts, decoded.request);
  return decoded;
}

DecodedReply DecodeAsciiReply(std::span<const std::uint8_t> frame) {
  DecodedReply decoded;
  decoded.reply.envelope.mode = Mode::kAscii;
  decoded.error.envelope.mode = Mode::kAscii;
  AsciiParts parts;
  decoded.fault = SplitAsciiFrame(frame, /*wildcards_allowed=*/false, parts);
  if (decoded.fault != FrameFault::kNone) return decoded;
  decoded.reply.envelope = EnvelopeOf(parts);
  decoded.error.envelope = decoded.reply.envelope;
  decoded.fault = ReadReplyFields(parts, decoded);
  return decoded;
}

base::Result<std::size_t> EncodeAsciiRequest(const Request& request, std::span<std::uint8_t> out) {
  const bool writes = request.command == Command::kWrite || request.command == Command::kWriteRam;
  if (request.command == Command::kReadTwoWire) return base::InvalidArgument();  // binary only
  if (request.command == Command::kRead && request.data != 0) return base::InvalidArgument();
  if (writes && !DataFitsDigits(request.data, request.ascii_data_digits)) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kAsciiStartCode);
  if (!PutAddress(writer, request.envelope.address, /*wildcards_allowed=*/true)) {
    return base::InvalidArgument();
  }
  writer.U8(static_cast<std::uint8_t>(request.command));
  PutHex(writer, request.comm_number, kFieldLength);
  if (writes) PutHex(writer, request.data, request.ascii_data_digits);
  return FinishFrame(writer, request.envelope);
}

base::Result<std::size_t> EncodeAsciiReply(const Reply& reply, std::span<std::uint8_t> out) {
  if (reply.command == Command::kReadTwoWire) return base::InvalidArgument();  // binary only
  base::ByteWriter writer(out);
  writer.U8(kAsciiStartCode);
  if (!PutAddress(writer, reply.envelope.address, /*wildcards_allowed=*/false)) return base::InvalidArgument();
  writer.U8(WriteReplyLetter(static_cast<std::uint8_t>(reply.command), reply.tripped));
  PutHex(writer, reply.comm_number, kFieldLength);
  PutHex(writer, reply.data, kMaxDataDigits);
  return FinishFrame(writer, reply.envelope);
}

base::Result<std::size_t> EncodeAsciiErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out) {
  if (reply.code > ErrorCode::kChecksumError) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kAsciiStartCode);
  if (!PutAddress(writer, reply.envelope.address, /*wildcards_allowed=*/false)) return base::InvalidArgument();
  writer.U8(WriteReplyLetter(kErrorReplyLetter, reply.tripped));
  PutHex(writer, static_cast<std::uint16_t>(reply.code), kFieldLength);
  return FinishFrame(writer, reply.envelope);
}

}  // namespace drive_link::wire::internal
