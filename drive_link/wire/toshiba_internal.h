// Private to ipe_toshiba_wire: the cursor the decoders split a frame with, hex helpers, and the per-mode
// codecs behind the public dispatchers in toshiba_frame.h. Frames are written with base::ByteWriter
// (words big-endian, high byte first, p.11).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/byte_writer.h"
#include "base/status.h"
#include "drive_link/wire/toshiba_frame.h"

namespace drive_link::wire::internal {

// Reads a span front to back; every read says whether the bytes were there. The cursor only moves on
// success, so a failed read leaves it where it was.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::optional<std::uint8_t> Peek() const {
    if (position_ >= bytes_.size()) return std::nullopt;
    return bytes_[position_];
  }
  [[nodiscard]] bool Take(std::uint8_t& byte) {
    if (position_ >= bytes_.size()) return false;
    byte = bytes_[position_++];
    return true;
  }
  // Takes `byte` if it is next.
  bool TakeIf(std::uint8_t byte) {
    if (Peek() != byte) return false;
    ++position_;
    return true;
  }
  [[nodiscard]] bool TakeSpan(std::size_t count, std::span<const std::uint8_t>& out) {
    if (count > remaining()) return false;
    out = bytes_.subspan(position_, count);
    position_ += count;
    return true;
  }
  // The longest run of bytes satisfying `accept`, possibly empty.
  template <typename Predicate>
  std::span<const std::uint8_t> TakeWhile(Predicate accept) {
    const std::size_t start = position_;
    while (position_ < bytes_.size() && accept(bytes_[position_])) ++position_;
    return bytes_.subspan(start, position_ - start);
  }
  std::size_t remaining() const { return bytes_.size() - position_; }
  // Everything read so far.
  std::span<const std::uint8_t> consumed() const { return bytes_.first(position_); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

// The low `digits` hex digits of `value`, most significant first, uppercase as in every example.
void PutHex(base::ByteWriter& writer, std::uint16_t value, std::size_t digits);

constexpr bool IsDecimalDigit(std::uint8_t c) { return c >= '0' && c <= '9'; }
constexpr bool IsHexDigit(std::uint8_t c) {
  return IsDecimalDigit(c) || (c >= 'A' && c <= 'F') || (c >= 'a' && c <= 'f');
}
// 0-4 hex digits (either case) as a number; nullopt if any is not a hex digit or there are more than 4.
std::optional<std::uint16_t> ParseHex(std::span<const std::uint8_t> digits);
std::uint8_t HexCharacter(unsigned nibble);

// A reply letter read back: the command letter in uppercase, and whether it came in lowercase (tripped).
struct ReplyLetter {
  std::uint8_t upper = 0;
  bool tripped = false;
};
constexpr ReplyLetter ReadReplyLetter(std::uint8_t letter) {
  if (letter >= 'a' && letter <= 'z') return {static_cast<std::uint8_t>(letter - kTrippedOffset), true};
  return {letter, false};
}
constexpr std::uint8_t WriteReplyLetter(std::uint8_t upper, bool tripped) {
  return tripped ? static_cast<std::uint8_t>(upper + kTrippedOffset) : upper;
}
constexpr bool IsRegisterCommand(std::uint8_t letter) {
  return letter == 'R' || letter == 'W' || letter == 'P' || letter == 'G';
}

// Binary frame lengths, shared by the decoders and the stream framer so both cut frames alike.
// Bytes after the command byte, checksum included; 0 for a command this direction does not know;
// kBlockTail for block commands, whose length is BlockTailLength(the count byte after the command).
inline constexpr std::size_t kBlockTail = 0xFF;
std::size_t BinaryTailLength(Direction direction, std::uint8_t command);
constexpr std::size_t BlockTailLength(std::uint8_t count) { return 3U + 2U * count; }
// Whether a byte right after the start code is an inverter number: 00h-3Fh, and FFh (broadcast) in
// requests. Commands (47h-79h) never fall in that range, which is how an omitted number is told apart.
constexpr bool IsBinaryAddressByte(Direction direction, std::uint8_t byte) {
  return byte <= kMaxBinaryInverterNumber || (direction == Direction::kRequests && byte == kBinaryBroadcast);
}

DecodedRequest DecodeAsciiRequest(std::span<const std::uint8_t> frame);
DecodedReply DecodeAsciiReply(std::span<const std::uint8_t> frame);
DecodedRequest DecodeBinaryRequest(std::span<const std::uint8_t> frame, BlockWriteLimit block_limit);
DecodedReply DecodeBinaryReply(std::span<const std::uint8_t> frame);

base::Result<std::size_t> EncodeAsciiRequest(const Request& request, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeAsciiReply(const Reply& reply, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeAsciiErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeBinaryRequest(const Request& request, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeBinaryReply(const Reply& reply, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeBinaryErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out);

}  // namespace drive_link::wire::internal
