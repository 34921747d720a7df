// drive_link::wire::SerialFrameReader: bounded reads from a hal::SerialPort into the framer, whole frames
// to the sink with the time of the Poll, the kFrameTimeout receive timer, damaged bytes, NextDeadline.
#include "drive_link/wire/serial_frame_reader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <vector>

namespace drive_link::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::Micros;

constexpr Micros kTimeout = 500 * hal::kMicrosPerMilli;  // kFrameTimeout
const Bytes kReadFd01 = {0x2F, 0x52, 0xFD, 0x01, 0x7F};                // request: read FD01 (seed 003)
const Bytes kFd01Reply = {0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7};  // reply: FD01 = 4800h

// A port whose reads are scripted: each entry is one Read() result (bytes, or a damaged byte).
class ScriptedPort final : public hal::SerialPort {
 public:
  struct Chunk {
    Bytes bytes;
    bool damaged = false;
  };
  base::Status Configure(const hal::SerialConfig&) override { return base::OkStatus(); }
  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override {
    ++reads;
    if (chunks.empty()) return base::Unavailable();
    Chunk& chunk = chunks.front();
    if (chunk.damaged) {
      chunks.pop_front();
      return base::DataLoss();
    }
    const std::size_t n = std::min(buffer.size(), chunk.bytes.size());
    std::copy_n(chunk.bytes.begin(), n, buffer.begin());
    chunk.bytes.erase(chunk.bytes.begin(), chunk.bytes.begin() + static_cast<std::ptrdiff_t>(n));
    if (chunk.bytes.empty()) chunks.pop_front();
    return n;
  }
  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override { return bytes.size(); }

  void Add(const Bytes& bytes) { chunks.push_back({bytes, false}); }
  void AddDamaged() { chunks.push_back({{}, true}); }

  std::deque<Chunk> chunks;
  int reads = 0;
};

class Sink final : public FrameSink {
 public:
  void OnFrame(std::span<const std::uint8_t> frame, Micros now) override {
    frames.emplace_back(frame.begin(), frame.end());
    times.push_back(now);
  }
  std::vector<Bytes> frames;
  std::vector<Micros> times;
};

class SerialFrameReaderTest : public ::testing::Test {
 protected:
  ScriptedPort port_;
  Sink sink_;
  SerialFrameReader replies_{port_, Direction::kReplies};
  SerialFrameReader requests_{port_, Direction::kRequests};
};

TEST_F(SerialFrameReaderTest, DeliversAWholeFrameWithThePollTime) {
  port_.Add(kFd01Reply);
  const ReadOutcome outcome = replies_.Poll(1000, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
  EXPECT_EQ(sink_.times[0], 1000U);
  EXPECT_EQ(outcome.damaged_bytes, 0U);
  EXPECT_FALSE(outcome.partial_frame_timed_out);
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
  EXPECT_EQ(replies_.framer_counters().frames, 1U);
}

TEST_F(SerialFrameReaderTest, CutsRequestsInTheRequestDirection) {
  port_.Add(kReadFd01);
  requests_.Poll(5, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);
  EXPECT_EQ(sink_.frames[0], kReadFd01);
}

TEST_F(SerialFrameReaderTest, AFrameSplitOverPollsIsDeliveredWhenComplete) {
  port_.Add({0x2F, 0x52, 0xFD});
  replies_.Poll(100, sink_);
  EXPECT_TRUE(sink_.frames.empty());
  EXPECT_EQ(replies_.NextDeadline(), 100 + kTimeout);  // the receive timer runs from the start code
  port_.Add({0x01, 0x48, 0x00, 0xC7});
  replies_.Poll(300, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
  EXPECT_EQ(sink_.times[0], 300U);
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
}

TEST_F(SerialFrameReaderTest, TwoFramesInOneReadAreDeliveredInOrder) {
  Bytes both = kFd01Reply;
  const Bytes second = {0x2F, 0x52, 0xFD, 0x00, 0x17, 0x70, 0x05};  // FD00 = 1770h
  both.insert(both.end(), second.begin(), second.end());
  port_.Add(both);
  replies_.Poll(7, sink_);
  ASSERT_EQ(sink_.frames.size(), 2U);
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
  EXPECT_EQ(sink_.frames[1], second);
}

TEST_F(SerialFrameReaderTest, GarbageBeforeTheStartCodeIsCountedAndSkipped) {
  Bytes bytes = {0x00, 0x11, 0x22};
  bytes.insert(bytes.end(), kFd01Reply.begin(), kFd01Reply.end());
  port_.Add(bytes);
  replies_.Poll(1, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
  EXPECT_EQ(replies_.framer_counters().garbage_bytes, 3U);
}

TEST_F(SerialFrameReaderTest, ReadsAreBoundedPerPoll) {
  // 40 replies (280 bytes) waiting: one Poll reads 8 x 32 = 256 bytes and asks for another pass at once.
  Bytes many;
  for (int i = 0; i < 40; ++i) many.insert(many.end(), kFd01Reply.begin(), kFd01Reply.end());
  port_.Add(many);
  replies_.Poll(2000, sink_);
  EXPECT_EQ(port_.reads, static_cast<int>(SerialFrameReader::kMaxReadsPerPoll));
  EXPECT_EQ(sink_.frames.size(), 36U);  // 256 / 7 = 36 whole frames, the 37th begun
  EXPECT_EQ(replies_.NextDeadline(), 2000U);
  replies_.Poll(2001, sink_);
  EXPECT_EQ(sink_.frames.size(), 40U);
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
}

TEST_F(SerialFrameReaderTest, ADamagedByteDropsThePartialFrame) {
  port_.Add({0x2F, 0x52, 0xFD});
  port_.AddDamaged();
  port_.Add({0x01, 0x48, 0x00, 0xC7});
  const ReadOutcome outcome = replies_.Poll(10, sink_);
  EXPECT_EQ(outcome.damaged_bytes, 1U);
  EXPECT_TRUE(sink_.frames.empty());  // the rest is garbage without its start code
  EXPECT_EQ(replies_.framer_counters().dropped_frames, 1U);
  port_.Add(kFd01Reply);
  replies_.Poll(11, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);  // the next frame is whole again
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
}

TEST_F(SerialFrameReaderTest, APartialFrameTimesOutAfterTheFrameTimeout) {
  port_.Add({0x2F, 0x52});
  replies_.Poll(1000, sink_);
  EXPECT_FALSE(replies_.Poll(1000 + kTimeout - 1, sink_).partial_frame_timed_out);
  EXPECT_TRUE(replies_.Poll(1000 + kTimeout, sink_).partial_frame_timed_out);
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
  EXPECT_EQ(replies_.framer_counters().dropped_frames, 1U);
  // Bytes of the lost frame that come later are not glued to a new one.
  port_.Add({0xFD, 0x01, 0x48, 0x00, 0xC7});
  port_.Add(kFd01Reply);
  replies_.Poll(1000 + kTimeout + 1, sink_);
  ASSERT_EQ(sink_.frames.size(), 1U);
  EXPECT_EQ(sink_.frames[0], kFd01Reply);
}

TEST_F(SerialFrameReaderTest, ARestartedFrameRestartsTheTimer) {
  port_.Add({'(', 'R', '0'});
  replies_.Poll(0, sink_);
  EXPECT_EQ(replies_.NextDeadline(), kTimeout);
  // In ASCII any '(' restarts the frame ("the last one wins"): its timer runs from the new start.
  port_.Add({'('});
  replies_.Poll(200, sink_);
  EXPECT_EQ(replies_.NextDeadline(), 200 + kTimeout);
  EXPECT_EQ(replies_.framer_counters().dropped_frames, 1U);
}

TEST_F(SerialFrameReaderTest, DropPartialFrameEndsTheTimer) {
  port_.Add({0x2F, 0x52, 0xFD});
  replies_.Poll(0, sink_);
  replies_.DropPartialFrame();
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
  replies_.DropPartialFrame();  // nothing in progress: no effect
  EXPECT_EQ(replies_.framer_counters().dropped_frames, 1U);
}

TEST_F(SerialFrameReaderTest, NothingToReadIsQuiet) {
  const ReadOutcome outcome = replies_.Poll(3, sink_);
  EXPECT_EQ(port_.reads, 1);
  EXPECT_EQ(outcome.damaged_bytes, 0U);
  EXPECT_TRUE(sink_.frames.empty());
  EXPECT_EQ(replies_.NextDeadline(), hal::kNever);
}

}  // namespace
}  // namespace drive_link::wire
