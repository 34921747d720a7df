// libFuzzer target for the Toshiba inverter protocol codec (drive_link/wire).
//
// The first input byte picks what is exercised; the rest is the frame (or the stream):
//   0 ASCII request   1 binary request   2 block request (LED limit)
//   3 ASCII reply     4 binary reply     5 block reply
//   6 request framer  7 reply framer     (fed in chunks whose sizes come from the input)
// For 0-5 the start code (and for blocks the command letter) is supplied, so every input reaches the
// field parsers. Oracle: a frame that decodes must re-encode, fit kMaxFrameLength, and decode to the
// same value (open62541's round-trip oracle). Framer: every frame it delivers is within kMaxFrameLength
// and consumption always makes progress.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "drive_link/wire/toshiba_frame.h"

namespace {

using drive_link::wire::BlockWriteLimit;
using drive_link::wire::DecodedReply;
using drive_link::wire::DecodedRequest;
using drive_link::wire::Direction;
using drive_link::wire::kMaxFrameLength;
using drive_link::wire::RequestKind;
using drive_link::wire::ReplyKind;
using drive_link::wire::StreamFramer;

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

using Buffer = std::array<std::uint8_t, kMaxFrameLength>;

// Re-encodes a decoded value and requires the encoding to decode to the same value.
template <typename Value, typename Encoder, typename Redecode>
void RoundTrip(const Value& value, Encoder encode, Redecode redecode) {
  Buffer buffer{};
  const base::Result<std::size_t> length = encode(value, std::span<std::uint8_t>(buffer));
  Require(length.ok());
  Require(*length <= kMaxFrameLength);
  Require(redecode(std::span<const std::uint8_t>(buffer).first(*length)) == value);
}

void CheckRequest(std::span<const std::uint8_t> frame, BlockWriteLimit limit) {
  const DecodedRequest decoded = drive_link::wire::DecodeRequest(frame, limit);
  if (!decoded.ok()) {
    // Whatever the fault, the mapping to an answer is total.
    (void)drive_link::wire::ErrorReplyFor(decoded);
    return;
  }
  if (decoded.kind == RequestKind::kBlock) {
    RoundTrip(decoded.block, drive_link::wire::EncodeBlockRequest, [limit](std::span<const std::uint8_t> f) {
      const DecodedRequest again = drive_link::wire::DecodeRequest(f, limit);
      Require(again.ok() && again.kind == RequestKind::kBlock);
      return again.block;
    });
    return;
  }
  RoundTrip(decoded.request, drive_link::wire::EncodeRequest, [limit](std::span<const std::uint8_t> f) {
    const DecodedRequest again = drive_link::wire::DecodeRequest(f, limit);
    Require(again.ok() && again.kind == RequestKind::kRegister);
    return again.request;
  });
}

template <typename Member>
auto RedecodeReply(ReplyKind kind, Member member) {
  return [kind, member](std::span<const std::uint8_t> f) {
    const DecodedReply again = drive_link::wire::DecodeReply(f);
    Require(again.ok() && again.kind == kind);
    return again.*member;
  };
}

void CheckReply(std::span<const std::uint8_t> frame) {
  const DecodedReply decoded = drive_link::wire::DecodeReply(frame);
  if (!decoded.ok()) return;
  switch (decoded.kind) {
    case ReplyKind::kRegister:
      RoundTrip(decoded.reply, drive_link::wire::EncodeReply, RedecodeReply(decoded.kind, &DecodedReply::reply));
      return;
    case ReplyKind::kError:
      RoundTrip(decoded.error, drive_link::wire::EncodeErrorReply,
                RedecodeReply(decoded.kind, &DecodedReply::error));
      return;
    case ReplyKind::kBlock:
      RoundTrip(decoded.block, drive_link::wire::EncodeBlockReply,
                RedecodeReply(decoded.kind, &DecodedReply::block));
      return;
  }
}

// The input is: one chunk-size byte, then stream bytes; repeat. A chunk-size byte of 0 tells the
// framer the receive timeout expired. Every frame delivered is also decoded.
void CheckFramer(Direction direction, std::span<const std::uint8_t> input) {
  StreamFramer framer(direction);
  while (!input.empty()) {
    const std::size_t chunk = input[0] % 24U;
    input = input.subspan(1);
    if (chunk == 0) {
      framer.GapElapsed();
      continue;
    }
    std::span<const std::uint8_t> piece = input.first(chunk < input.size() ? chunk : input.size());
    input = input.subspan(piece.size());
    while (!piece.empty()) {
      const StreamFramer::FeedResult result = framer.Feed(piece);
      Require(result.consumed > 0 && result.consumed <= piece.size());
      piece = piece.subspan(result.consumed);
      if (!result.frame_ready) continue;
      Require(!framer.frame().empty() && framer.frame().size() <= kMaxFrameLength);
      if (direction == Direction::kRequests) {
        CheckRequest(framer.frame(), BlockWriteLimit::kLedDisplay);
      } else {
        CheckReply(framer.frame());
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t selector = data[0] % 8U;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  if (selector >= 6) {
    CheckFramer(selector == 6 ? Direction::kRequests : Direction::kReplies, rest);
    return 0;
  }
  // Decoder inputs: a prefix that steers into the chosen decoder, then the fuzz bytes. Frames longer
  // than a few bytes past the protocol's maximum only test the length check, so they are cut there.
  static constexpr std::array<std::array<std::uint8_t, 2>, 6> kPrefixes = {{
      {'(', 0}, {0x2F, 0}, {0x2F, 'X'}, {'(', 0}, {0x2F, 0}, {0x2F, 'Y'}}};
  const std::array<std::uint8_t, 2>& prefix = kPrefixes[selector];
  const std::size_t prefix_length = prefix[1] == 0 ? 1 : 2;
  std::array<std::uint8_t, kMaxFrameLength + 4> frame{};
  std::size_t length = 0;
  for (std::size_t i = 0; i < prefix_length; ++i) frame[length++] = prefix[i];
  for (std::size_t i = 0; i < rest.size() && length < frame.size(); ++i) frame[length++] = rest[i];
  const std::span<const std::uint8_t> bytes(frame.data(), length);
  if (selector <= 2) {
    CheckRequest(bytes, selector == 2 ? BlockWriteLimit::kLedDisplay : BlockWriteLimit::kParameters);
  } else {
    CheckReply(bytes);
  }
  return 0;
}
