// Binary mode of the Toshiba inverter protocol (4.1.2, 4.1.3, p.11-17):
//
//   2Fh [INV-NO] COMMAND BODY SUM
//
// The command fixes the body's length (for block frames, together with the count byte that follows
// it); SUM is the low byte of the sum of everything before it. Words are big-endian.
#include <array>

#include "base/byte_reader.h"
#include "drive_link/wire/toshiba_frame.h"
#include "toshiba_internal.h"

namespace drive_link::wire::internal {
namespace {

// Bytes after the command byte, checksum included, per direction (p.11-17, 6.2). 0 = not a command in
// that direction. Lowercase letters exist only in replies (tripped), 'S'/'s' only in requests.
struct BinaryShape {
  std::uint8_t letter;
  std::uint8_t request_tail;
  std::uint8_t reply_tail;
};
constexpr std::uint8_t kBlock = static_cast<std::uint8_t>(kBlockTail);
constexpr std::array<BinaryShape, 15> kShapes = {{
    {'R', 3, 5}, {'W', 5, 5}, {'P', 5, 5}, {'G', 5, 5},   // R: number + sum; W/P/G: number + data + sum
    {'r', 0, 5}, {'w', 0, 5}, {'p', 0, 5}, {'g', 0, 5},   // tripped echoes
    {'N', 0, 3}, {'n', 0, 3},                             // error reply: code + sum
    {'X', kBlock, 0}, {'Y', 0, kBlock}, {'y', 0, kBlock},  // block request / reply
    {'S', 5, 0}, {'s', 5, 0},                             // inter-drive (recognised to be skipped)
}};

// The parts of a binary frame whose length checked out; the checksum is checked by the caller so that
// it can rank a checksum error against the other faults.
struct BinaryParts {
  InverterAddress address;
  std::uint8_t command = 0;
  std::span<const std::uint8_t> body;  // between the command and the checksum
  bool checksum_ok = false;
};

FrameFault ReadAddress(Cursor& cursor, Direction direction, InverterAddress& address) {
  const std::optional<std::uint8_t> next = cursor.Peek();
  if (!next.has_value()) return FrameFault::kTruncated;
  if (IsBinaryAddressByte(direction, *next)) {
    cursor.TakeIf(*next);
    address = *next == kBinaryBroadcast ? InverterAddress::Broadcast() : InverterAddress::Number(*next);
  } else if (*next == kBinaryBroadcast) {
    return FrameFault::kBadInverterNumber;  // a reply names its sender, never "all"
  }
  return FrameFault::kNone;
}

// Length of the body plus checksum, or a fault when the command or block count rules the frame out.
FrameFault TailLength(Cursor& cursor, Direction direction, std::uint8_t command, std::size_t max_count,
                      std::size_t& tail) {
  tail = BinaryTailLength(direction, command);
  if (tail == 0) return FrameFault::kUnknownCommand;
  if (tail != kBlockTail) return FrameFault::kNone;
  const std::optional<std::uint8_t> count = cursor.Peek();
  if (!count.has_value()) return FrameFault::kTruncated;
  if (*count > max_count) {
    return direction == Direction::kRequests ? FrameFault::kBadBlockWriteCount : FrameFault::kBadBlockReadCount;
  }
  tail = BlockTailLength(*count);
  return FrameFault::kNone;
}

FrameFault SplitBinaryFrame(std::span<const std::uint8_t> frame, Direction direction, std::size_t max_count,
                            BinaryParts& parts) {
  if (frame.size() > kMaxFrameLength) return FrameFault::kTooLong;
  Cursor cursor(frame);
  std::uint8_t start = 0;
  if (!cursor.Take(start)) return FrameFault::kTruncated;
  if (start != kBinaryStartCode) return FrameFault::kBadStartCode;
  if (const FrameFault fault = ReadAddress(cursor, direction, parts.address); fault != FrameFault::kNone) {
    return fault;
  }
  if (!cursor.Take(parts.command)) return FrameFault::kTruncated;
  std::size_t tail = 0;
  if (const FrameFault fault = TailLength(cursor, direction, parts.command, max_count, tail);
      fault != FrameFault::kNone) {
    return fault;
  }
  if (cursor.remaining() < tail) return FrameFault::kTruncated;
  if (cursor.remaining() > tail) return FrameFault::kTrailingBytes;
  std::span<const std::uint8_t> sum;
  if (!cursor.TakeSpan(tail - 1, parts.body) || !cursor.TakeSpan(1, sum)) return FrameFault::kTruncated;
  parts.checksum_ok = BinaryChecksum(frame.first(frame.size() - 1)) == sum[0];
  return FrameFault::kNone;
}

// The body's length was proven against the command by SplitBinaryFrame; reading it through a bounded
// reader all the same means a wrong proof yields zeros, never bytes past the frame.
template <std::size_t N>
void ReadWords(base::ByteReader& body, std::size_t count, std::array<std::uint16_t, N>& words) {
  for (std::size_t i = 0; i < count && i < N; ++i) words[i] = body.U16Be();
}

DecodedRequest DecodeBlockRequest(const BinaryParts& parts) {
  DecodedRequest decoded;
  decoded.kind = RequestKind::kBlock;
  BlockRequest& block = decoded.block;
  block.address = parts.address;
  if (!parts.checksum_ok) {
    decoded.fault = FrameFault::kBadChecksum;
    return decoded;
  }
  base::ByteReader body(parts.body);
  block.write_count = body.U8();
  block.read_count = body.U8();
  ReadWords(body, block.write_count, block.write_data);
  return decoded;
}

DecodedReply DecodeBlockReply(const BinaryParts& parts, bool tripped) {
  DecodedReply decoded;
  decoded.kind = ReplyKind::kBlock;
  BlockReply& block = decoded.block;
  block.address = parts.address;
  block.tripped = tripped;
  if (!parts.checksum_ok) {
    decoded.fault = FrameFault::kBadChecksum;
    return decoded;
  }
  base::ByteReader body(parts.body);
  block.read_count = body.U8();
  block.write_status = body.U8();
  ReadWords(body, block.read_count, block.read_data);
  return decoded;
}

DecodedReply DecodeErrorReply(const BinaryParts& parts, bool tripped) {
  DecodedReply decoded;
  decoded.kind = ReplyKind::kError;
  decoded.error.envelope = {.mode = Mode::kBinary, .address = parts.address};
  decoded.error.tripped = tripped;
  base::ByteReader body(parts.body);
  const std::uint16_t code = body.U16Be();
  if (!parts.checksum_ok) {
    decoded.fault = FrameFault::kBadChecksum;
  } else if (code > static_cast<std::uint16_t>(ErrorCode::kChecksumError)) {
    decoded.fault = FrameFault::kBadErrorCode;
  } else {
    decoded.error.code = static_cast<ErrorCode>(code);
  }
  return decoded;
}

// Writes the inverter number; false if this frame cannot carry it (FFh only addresses requests).
bool PutAddress(base::ByteWriter& writer, InverterAddress address, bool broadcast_allowed) {
  switch (address.kind) {
    case InverterAddress::Kind::kOmitted:
      return true;
    case InverterAddress::Kind::kNumber:
      writer.U8(address.value);
      return address.value <= kMaxBinaryInverterNumber;
    case InverterAddress::Kind::kBroadcast:
      writer.U8(kBinaryBroadcast);
      return broadcast_allowed;
    case InverterAddress::Kind::kOnesDigitGroup:
    case InverterAddress::Kind::kTensDigitGroup:
      return false;  // group broadcasts exist in ASCII only
  }
  return false;
}

base::Result<std::size_t> FinishFrame(base::ByteWriter& writer) {
  writer.U8(BinaryChecksum(writer.written()));
  return writer.Finish();
}

}  // namespace

std::size_t BinaryTailLength(Direction direction, std::uint8_t command) {
  for (const BinaryShape& shape : kShapes) {
    if (shape.letter == command) {
      return direction == Direction::kRequests ? shape.request_tail : shape.reply_tail;
    }
  }
  return 0;
}

DecodedRequest DecodeBinaryRequest(std::span<const std::uint8_t> frame, BlockWriteLimit block_limit) {
  BinaryParts parts;
  DecodedRequest decoded;
  decoded.fault = SplitBinaryFrame(frame, Direction::kRequests, static_cast<std::size_t>(block_limit), parts);
  decoded.request.envelope = {.mode = Mode::kBinary, .address = parts.address};
  if (decoded.fault != FrameFault::kNone) {
    if (parts.command == kBlockRequestLetter) decoded.kind = RequestKind::kBlock;
    return decoded;
  }
  if (parts.command == kBlockRequestLetter) return DecodeBlockRequest(parts);
  // S is never answered, whatever its checksum (p.20): decide that before the checksum.
  if (ReadReplyLetter(parts.command).upper == kInterDriveLetter) {
    decoded.fault = FrameFault::kInterDriveCommand;
    return decoded;
  }
  if (!parts.checksum_ok) {
    decoded.fault = FrameFault::kBadChecksum;
    return decoded;
  }
  Request& request = decoded.request;
  request.command = static_cast<Command>(parts.command);
  base::ByteReader body(parts.body);
  request.comm_number = body.U16Be();
  if (request.command != Command::kRead) request.data = body.U16Be();
  return decoded;
}

DecodedReply DecodeBinaryReply(std::span<const std::uint8_t> frame) {
  BinaryParts parts;
  DecodedReply decoded;
  decoded.fault = SplitBinaryFrame(frame, Direction::kReplies, kMaxBlockReads, parts);
  if (decoded.fault != FrameFault::kNone) return decoded;
  const ReplyLetter letter = ReadReplyLetter(parts.command);
  if (letter.upper == kBlockReplyLetter) return DecodeBlockReply(parts, letter.tripped);
  if (letter.upper == kErrorReplyLetter) return DecodeErrorReply(parts, letter.tripped);
  Reply& reply = decoded.reply;
  reply.envelope = {.mode = Mode::kBinary, .address = parts.address};
  reply.tripped = letter.tripped;
  if (!parts.checksum_ok) {
    decoded.fault = FrameFault::kBadChecksum;
    return decoded;
  }
  reply.command = static_cast<Command>(letter.upper);
  base::ByteReader body(parts.body);
  reply.comm_number = body.U16Be();
  reply.data = body.U16Be();
  return decoded;
}

base::Result<std::size_t> EncodeBinaryRequest(const Request& request, std::span<std::uint8_t> out) {
  if (!IsRegisterCommand(static_cast<std::uint8_t>(request.command))) return base::InvalidArgument();
  if (request.command == Command::kRead && request.data != 0) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kBinaryStartCode);
  if (!PutAddress(writer, request.envelope.address, /*broadcast_allowed=*/true)) return base::InvalidArgument();
  writer.U8(static_cast<std::uint8_t>(request.command));
  writer.U16Be(request.comm_number);
  if (request.command != Command::kRead) writer.U16Be(request.data);
  return FinishFrame(writer);
}

base::Result<std::size_t> EncodeBinaryReply(const Reply& reply, std::span<std::uint8_t> out) {
  if (!IsRegisterCommand(static_cast<std::uint8_t>(reply.command))) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kBinaryStartCode);
  if (!PutAddress(writer, reply.envelope.address, /*broadcast_allowed=*/false)) return base::InvalidArgument();
  writer.U8(WriteReplyLetter(static_cast<std::uint8_t>(reply.command), reply.tripped));
  writer.U16Be(reply.comm_number);
  writer.U16Be(reply.data);
  return FinishFrame(writer);
}

base::Result<std::size_t> EncodeBinaryErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out) {
  if (reply.code > ErrorCode::kChecksumError) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kBinaryStartCode);
  if (!PutAddress(writer, reply.envelope.address, /*broadcast_allowed=*/false)) return base::InvalidArgument();
  writer.U8(WriteReplyLetter(kErrorReplyLetter, reply.tripped));
  writer.U16Be(static_cast<std::uint16_t>(reply.code));
  return FinishFrame(writer);
}

}  // namespace drive_link::wire::internal

namespace drive_link::wire {

base::Result<std::size_t> EncodeBlockRequest(const BlockRequest& request, std::span<std::uint8_t> out) {
  if (request.write_count > kMaxLedBlockWrites) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kBinaryStartCode);
  if (!internal::PutAddress(writer, request.address, /*broadcast_allowed=*/true)) return base::InvalidArgument();
  writer.U8(kBlockRequestLetter);
  writer.U8(request.write_count);
  writer.U8(request.read_count);
  for (std::size_t i = 0; i < request.write_count; ++i) writer.U16Be(request.write_data[i]);
  return internal::FinishFrame(writer);
}

base::Result<std::size_t> EncodeBlockReply(const BlockReply& reply, std::span<std::uint8_t> out) {
  if (reply.read_count > kMaxBlockReads) return base::InvalidArgument();
  base::ByteWriter writer(out);
  writer.U8(kBinaryStartCode);
  if (!internal::PutAddress(writer, reply.address, /*broadcast_allowed=*/false)) return base::InvalidArgument();
  writer.U8(internal::WriteReplyLetter(kBlockReplyLetter, reply.tripped));
  writer.U8(reply.read_count);
  writer.U8(reply.write_status);
  for (std::size_t i = 0; i < reply.read_count; ++i) writer.U16Be(reply.read_data[i]);
  return internal::FinishFrame(writer);
}

}  // namespace drive_link::wire
