// StreamFramer: bytes split across reads, frames back to back, garbage, restarts, overlong frames and
// the caller's receive timeout. The frames are the manual's (E6581222); the manual examples as a whole
// go through the framer in toshiba_frame_test.cc.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "drive_link/wire/toshiba_frame.h"

namespace drive_link::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes Ascii(std::string_view text) {
  Bytes bytes(text.begin(), text.end());
  bytes.push_back(kCarriageReturn);
  return bytes;
}
Bytes Join(std::initializer_list<Bytes> parts) {
  Bytes all;
  for (const Bytes& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

const Bytes kBinaryRead = {0x2F, 0x52, 0xFD, 0x00, 0x7E};                    // p.24
const Bytes kBinaryReadReply = {0x2F, 0x52, 0xFD, 0x00, 0x17, 0x70, 0x05};   // p.24
const Bytes kBinaryWrite = {0x2F, 0x50, 0xFA, 0x01, 0x17, 0x70, 0x01};       // p.24
const Bytes kBroadcastWrite = {0x2F, 0xFF, 0x50, 0xFA, 0x01, 0x17, 0x70, 0x00};  // p.22
const Bytes kBlockRequest = {0x2F, 0x58, 0x02, 0x05, 0xC4, 0x00, 0x17, 0x70, 0xD9};  // p.16
const Bytes kBlockReply = {0x2F, 0x59, 0x05, 0x00, 0x64, 0x00, 0x17, 0x70, 0x1A,
                           0x8A, 0x24, 0xFD, 0x00, 0x00, 0x3D};                         // p.16
const Bytes kErrorReply = {0x2F, 0x4E, 0x00, 0x04, 0x81};                               // p.13
const Bytes kAsciiRead = Ascii("(RFD00)");                                              // p.24
const Bytes kAsciiReadReply = Ascii("(RFD001770)");                                     // p.24

// Feeds `stream` in chunks of `chunk` bytes (0 = all at once) and collects every frame.
std::vector<Bytes> FramesOf(StreamFramer& framer, const Bytes& stream, std::size_t chunk = 0) {
  std::vector<Bytes> frames;
  std::span<const std::uint8_t> rest(stream);
  while (!rest.empty()) {
    const std::size_t size = chunk == 0 ? rest.size() : std::min(chunk, rest.size());
    std::span<const std::uint8_t> piece = rest.first(size);
    rest = rest.subspan(size);
    while (!piece.empty()) {
      const StreamFramer::FeedResult result = framer.Feed(piece);
      EXPECT_GT(result.consumed, 0U);
      piece = piece.subspan(result.consumed);
      if (result.frame_ready) frames.emplace_back(framer.frame().begin(), framer.frame().end());
    }
  }
  return frames;
}

std::vector<Bytes> FramesOf(Direction direction, const Bytes& stream, std::size_t chunk = 0) {
  StreamFramer framer(direction);
  return FramesOf(framer, stream, chunk);
}

TEST(ToshibaFramer, BackToBackFrames_ComeOutInOrder) {
  const Bytes stream = Join({kBinaryRead, kAsciiRead, kBlockRequest, kBroadcastWrite, kBinaryWrite});
  EXPECT_EQ(FramesOf(Direction::kRequests, stream),
            (std::vector<Bytes>{kBinaryRead, kAsciiRead, kBlockRequest, kBroadcastWrite, kBinaryWrite}));
}

TEST(ToshibaFramer, RepliesBackToBack_UseReplyLengths) {
  const Bytes stream = Join({kBinaryReadReply, kErrorReply, kAsciiReadReply, kBlockReply});
  EXPECT_EQ(FramesOf(Direction::kReplies, stream),
            (std::vector<Bytes>{kBinaryReadReply, kErrorReply, kAsciiReadReply, kBlockReply}));
}

TEST(ToshibaFramer, EverySplitPointAndChunkSize_GivesTheSameFrames) {
  const Bytes stream = Join({kBinaryRead, kAsciiRead, kBlockRequest, kBroadcastWrite});
  const std::vector<Bytes> expected = {kBinaryRead, kAsciiRead, kBlockRequest, kBroadcastWrite};
  for (std::size_t chunk = 1; chunk <= stream.size(); ++chunk) {
    EXPECT_EQ(FramesOf(Direction::kRequests, stream, chunk), expected) << "chunk " << chunk;
  }
}

TEST(ToshibaFramer, FeedStopsAfterEachFrame) {
  StreamFramer framer(Direction::kRequests);
  const Bytes stream = Join({kBinaryRead, kBinaryWrite});
  StreamFramer::FeedResult result = framer.Feed(stream);
  EXPECT_TRUE(result.frame_ready);
  EXPECT_EQ(result.consumed, kBinaryRead.size());
  result = framer.Feed(std::span(stream).subspan(result.consumed));
  EXPECT_TRUE(result.frame_ready);
  EXPECT_EQ(Bytes(framer.frame().begin(), framer.frame().end()), kBinaryWrite);
  EXPECT_EQ(framer.counters().frames, 2U);
}

TEST(ToshibaFramer, GarbageBetweenFrames_IsSkippedAndCounted) {
  const Bytes garbage = {0x00, 0xFF, 'A', 0x0D, ')', 0x80};
  const Bytes stream = Join({garbage, kBinaryRead, garbage, kAsciiRead, garbage});
  StreamFramer framer(Direction::kRequests);
  EXPECT_EQ(FramesOf(framer, stream), (std::vector<Bytes>{kBinaryRead, kAsciiRead}));
  EXPECT_EQ(framer.counters().garbage_bytes, 3 * garbage.size());
  EXPECT_FALSE(framer.frame_in_progress());
}

TEST(ToshibaFramer, LastAsciiStartCodeWins) {
  // p.6: "If two or more '(' are entered, the '(' entered last will be valid".
  StreamFramer framer(Direction::kRequests);
  EXPECT_EQ(FramesOf(framer, Join({{'(', '(', 'R', 'F'}, kAsciiRead})), (std::vector<Bytes>{kAsciiRead}));
  EXPECT_EQ(framer.counters().dropped_frames, 2U);
}

TEST(ToshibaFramer, LastBinaryStartCodeWinsInTheCommandPosition) {
  // p.7: "the 2FH entered last will be judged valid". Right after the start code 2Fh is also inverter
  // number 47 (00h-3Fh are numbers), so the restart shows from the command position on.
  EXPECT_EQ(FramesOf(Direction::kRequests, Join({{0x2F, 0x05}, kBinaryRead})),
            (std::vector<Bytes>{kBinaryRead}));
  const Bytes to_inverter_47 = {0x2F, 0x2F, 0x52, 0xFD, 0x00, 0xAD};
  EXPECT_EQ(FramesOf(Direction::kRequests, to_inverter_47), (std::vector<Bytes>{to_inverter_47}));
}

TEST(ToshibaFramer, AsciiCrInsideTheCommunicationNumber_DoesNotEndTheFrame) {
  // p.21: "(R11)CR" takes "11)CR" as the number and waits for a CR; the next '(' restarts.
  StreamFramer framer(Direction::kRequests);
  EXPECT_EQ(FramesOf(framer, Join({Ascii("(R11)"), kAsciiRead})), (std::vector<Bytes>{kAsciiRead}));
  EXPECT_EQ(framer.counters().dropped_frames, 1U);
  // With an inverter number the number field starts 2 characters later.
  const Bytes numbered = Ascii("(07R0\r0)");
  EXPECT_EQ(FramesOf(Direction::kRequests, numbered), (std::vector<Bytes>{numbered}));
}

TEST(ToshibaFramer, OverlongAsciiFrame_IsDroppedAndTheNextFrameSurvives) {
  // p.6: more than 17 bytes without the CR is a transmission error.
  Bytes overlong = {'(', 'W'};
  overlong.resize(30, '7');
  StreamFramer framer(Direction::kRequests);
  EXPECT_EQ(FramesOf(framer, Join({overlong, kAsciiRead})), (std::vector<Bytes>{kAsciiRead}));
  EXPECT_EQ(framer.counters().dropped_frames, 1U);
}

TEST(ToshibaFramer, TheByteThatOverflowsAFrame_MayStartTheNext) {
  Bytes stream(16, '7');
  stream[0] = '(';
  const Bytes joined = Join({stream, kBinaryRead});  // the 17th byte is the binary start code
  EXPECT_EQ(FramesOf(Direction::kRequests, joined), (std::vector<Bytes>{kBinaryRead}));
}

TEST(ToshibaFramer, LongestAsciiFrame_Is17Bytes) {
  const Bytes longest = Ascii("(00W00100064&FF)");
  ASSERT_EQ(longest.size(), kMaxFrameLength);
  EXPECT_EQ(FramesOf(Direction::kRequests, longest), (std::vector<Bytes>{longest}));
}

TEST(ToshibaFramer, UnknownBinaryCommand_IsDroppedAndRescanned) {
  // 41h is no command; the '(' that made it impossible is looked at again and starts a frame.
  const Bytes stream = Join({{0x2F, 0x41}, {0x2F, 0x05, '('}, Bytes(kAsciiRead.begin() + 1, kAsciiRead.end())});
  StreamFramer framer(Direction::kRequests);
  EXPECT_EQ(FramesOf(framer, stream), (std::vector<Bytes>{kAsciiRead}));
  EXPECT_EQ(framer.counters().dropped_frames, 2U);
}

TEST(ToshibaFramer, DirectionDecidesBinaryLengths) {
  // An R request is 5 bytes; its reply 7. Lowercase letters exist only in replies.
  EXPECT_EQ(FramesOf(Direction::kReplies, kBinaryReadReply), (std::vector<Bytes>{kBinaryReadReply}));
  EXPECT_TRUE(FramesOf(Direction::kReplies, kBinaryRead).empty());
  const Bytes tripped = {0x2F, 0x72, 0xFD, 0x01, 0x00, 0x03, 0xA2};
  EXPECT_EQ(FramesOf(Direction::kReplies, tripped), (std::vector<Bytes>{tripped}));
  EXPECT_TRUE(FramesOf(Direction::kRequests, tripped).empty());
}

TEST(ToshibaFramer, BlockCountOutOfRange_IsDropped) {
  StreamFramer requests(Direction::kRequests);
  EXPECT_EQ(FramesOf(requests, Join({{0x2F, 0x58, 0x06}, kBinaryRead})), (std::vector<Bytes>{kBinaryRead}));
  StreamFramer replies(Direction::kReplies);
  EXPECT_EQ(FramesOf(replies, Join({{0x2F, 0x59, 0x06}, kErrorReply})), (std::vector<Bytes>{kErrorReply}));
}

TEST(ToshibaFramer, LedModeBlockRequest_IsFramedWithFiveWords) {
  const Bytes led = {0x2F, 0x58, 0x05, 0x05, 0x00, 0x30, 0x00, 0x31, 0x00,
                     0x32, 0x00, 0x33, 0x00, 0x03, 0x5A};  // p.57
  EXPECT_EQ(FramesOf(Direction::kRequests, led), (std::vector<Bytes>{led}));
}

TEST(ToshibaFramer, GapElapsed_DropsThePartialFrame) {
  StreamFramer framer(Direction::kRequests);
  EXPECT_FALSE(framer.Feed(std::span(kBinaryWrite).first(4)).frame_ready);
  EXPECT_TRUE(framer.frame_in_progress());
  framer.GapElapsed();
  EXPECT_FALSE(framer.frame_in_progress());
  EXPECT_EQ(framer.counters().dropped_frames, 1U);
  // The rest of the old frame is garbage now; the next whole frame comes through.
  EXPECT_EQ(FramesOf(framer, Join({Bytes(kBinaryWrite.begin() + 4, kBinaryWrite.end()), kBinaryRead})),
            (std::vector<Bytes>{kBinaryRead}));
}

TEST(ToshibaFramer, GapWithNothingPending_ChangesNothing) {
  StreamFramer framer(Direction::kReplies);
  framer.GapElapsed();
  EXPECT_EQ(framer.counters().dropped_frames, 0U);
  EXPECT_EQ(FramesOf(framer, kErrorReply), (std::vector<Bytes>{kErrorReply}));
  framer.GapElapsed();  // after a complete frame: nothing pending either
  EXPECT_EQ(framer.counters().dropped_frames, 0U);
  EXPECT_TRUE(framer.frame().empty());
}

TEST(ToshibaFramer, Reset_ForgetsThePartialFrame) {
  StreamFramer framer(Direction::kRequests);
  EXPECT_FALSE(framer.Feed(std::span(kAsciiRead).first(3)).frame_ready);
  framer.Reset();
  EXPECT_FALSE(framer.frame_in_progress());
  EXPECT_EQ(FramesOf(framer, kBinaryRead), (std::vector<Bytes>{kBinaryRead}));
}

TEST(ToshibaFramer, EmptyFeed_DoesNothing) {
  StreamFramer framer(Direction::kRequests);
  const StreamFramer::FeedResult result = framer.Feed({});
  EXPECT_EQ(result.consumed, 0U);
  EXPECT_FALSE(result.frame_ready);
}

TEST(ToshibaFramer, FramesAreDeliveredUnchecked_TheDecoderJudges) {
  // A bad checksum is the decoder's business: the inverter answers it (0004), so the frame must reach it.
  const Bytes bad = {0x2F, 0x58, 0x02, 0x05, 0xC4, 0x00, 0x17, 0x70, 0xD8};  // p.17
  const std::vector<Bytes> frames = FramesOf(Direction::kRequests, bad);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(DecodeRequest(frames[0]).fault, FrameFault::kBadChecksum);
}

TEST(ToshibaFramer, ReceiveTimeoutIsTheManuals) { EXPECT_EQ(kFrameTimeout, std::chrono::milliseconds(500)); }

}  // namespace
}  // namespace drive_link::wire
