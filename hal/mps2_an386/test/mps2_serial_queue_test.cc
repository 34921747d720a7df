// The board's UART receive queue under hal::SerialPort's contract (bytes, then kDataLoss once where
// bytes were lost, then the bytes after), its byte ring and the 64-bit tick count of the clock.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "byte_ring.h"
#include "serial_receive_queue.h"
#include "tick_counter.h"

namespace hal::mps2 {
namespace {

std::vector<std::uint8_t> ReadAll(SerialReceiveQueue<8>& queue, base::StatusCode& last) {
  std::array<std::uint8_t, 16> buffer{};
  const base::Result<std::size_t> read = queue.Read(buffer);
  last = read.status().code();
  if (!read.ok()) return {};
  return std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(read.value()));
}

TEST(Mps2ByteRing, HoldsCapacityBytesInOrder) {
  ByteRing<4> ring;
  for (std::uint8_t i = 1; i <= 4; ++i) EXPECT_TRUE(ring.Push(i));
  EXPECT_FALSE(ring.Push(5));
  EXPECT_EQ(ring.size(), 4u);
  std::uint8_t byte = 0;
  for (std::uint8_t i = 1; i <= 4; ++i) {
    ASSERT_TRUE(ring.Pop(byte));
    EXPECT_EQ(byte, i);
  }
  EXPECT_FALSE(ring.Pop(byte));
  EXPECT_TRUE(ring.empty());
}

TEST(Mps2SerialQueue, NothingWaiting_Unavailable) {
  SerialReceiveQueue<8> queue;
  base::StatusCode code{};
  EXPECT_TRUE(ReadAll(queue, code).empty());
  EXPECT_EQ(code, base::StatusCode::kUnavailable);
}

TEST(Mps2SerialQueue, LossReportedOnceAtItsPlace) {
  SerialReceiveQueue<8> queue;
  queue.Store(0x10);
  queue.Store(0x11);
  queue.MarkLoss();  // e.g. an overrun: bytes between 0x11 and 0x20 are gone
  queue.Store(0x20);
  base::StatusCode code{};
  EXPECT_EQ(ReadAll(queue, code), (std::vector<std::uint8_t>{0x10, 0x11}));
  EXPECT_TRUE(ReadAll(queue, code).empty());
  EXPECT_EQ(code, base::StatusCode::kDataLoss);
  EXPECT_EQ(ReadAll(queue, code), (std::vector<std::uint8_t>{0x20}));
  EXPECT_TRUE(ReadAll(queue, code).empty());
  EXPECT_EQ(code, base::StatusCode::kUnavailable);
  EXPECT_EQ(queue.losses(), 1u);
}

TEST(Mps2SerialQueue, FullQueueLosesTheByteAndSaysSo) {
  SerialReceiveQueue<8> queue;
  for (std::uint8_t i = 0; i < 10; ++i) queue.Store(i);  // 8 fit; 8 and 9 are lost
  base::StatusCode code{};
  EXPECT_EQ(ReadAll(queue, code), (std::vector<std::uint8_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_TRUE(ReadAll(queue, code).empty());
  EXPECT_EQ(code, base::StatusCode::kDataLoss);
  queue.Store(0x42);
  EXPECT_EQ(ReadAll(queue, code), (std::vector<std::uint8_t>{0x42}));
  EXPECT_EQ(queue.losses(), 2u);
}

TEST(Mps2SerialQueue, LossBeforeAnyByteComesFirst) {
  SerialReceiveQueue<8> queue;
  queue.MarkLoss();
  queue.Store(0x01);
  base::StatusCode code{};
  EXPECT_TRUE(ReadAll(queue, code).empty());
  EXPECT_EQ(code, base::StatusCode::kDataLoss);
  EXPECT_EQ(ReadAll(queue, code), (std::vector<std::uint8_t>{0x01}));
}

TEST(Mps2TickCounter, CountsDownAcrossTheWrap) {
  DownCounterTicks ticks(0xFFFFFFFFU);
  EXPECT_EQ(ticks.Update(0xFFFFFF00U), 0xFFu);
  EXPECT_EQ(ticks.Update(0x00000010U), 0xFFFFFFEFULL);
  // Through zero and the reload: 0x10 -> 0 -> 0xFFFFFFFF -> 0xFFFFFFF0 is 0x20 ticks.
  EXPECT_EQ(ticks.Update(0xFFFFFFF0U), 0x10000000FULL);
  EXPECT_EQ(ticks.total(), 0x10000000FULL);
}

}  // namespace
}  // namespace hal::mps2
