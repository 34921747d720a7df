// The bounded reader and writer every EtherNet/IP decoder and encoder uses: byte order, sticky failure
// at the end, child readers, patching.
#include "cip/byte_io.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

namespace cip {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes Of(std::span<const std::uint8_t> span) { return Bytes(span.begin(), span.end()); }

TEST(CipByteReader, ReadsLittleAndBigEndian) {
  const std::array<std::uint8_t, 13> bytes = {0x01, 0x34, 0x12, 0x78, 0x56, 0x34, 0x12,
                                              0xAF, 0x12, 0x0A, 0x00, 0x02, 0x0F};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U8(), 0x01);
  EXPECT_EQ(reader.U16(), 0x1234);
  EXPECT_EQ(reader.U32(), 0x12345678U);
  EXPECT_EQ(reader.U16Be(), 0xAF12);
  EXPECT_EQ(reader.U32Be(), 0x0A00020FU);
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(CipByteReader, HighBitBytesDoNotSignExtend) {
  const std::array<std::uint8_t, 4> bytes = {0xFF, 0xFF, 0xFF, 0xFF};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U32(), 0xFFFFFFFFU);
}

TEST(CipByteReader, ReadPastEnd_FailsStickyAndReturnsZero) {
  const std::array<std::uint8_t, 3> bytes = {0x11, 0x22, 0x33};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U16(), 0x2211);
  EXPECT_EQ(reader.U16(), 0);  // only one byte left
  EXPECT_FALSE(reader.ok());
  EXPECT_EQ(reader.remaining(), 0U);
  EXPECT_EQ(reader.U8(), 0);  // the last byte is not handed out after the failure
  EXPECT_FALSE(reader.ok());
}

TEST(CipByteReader, BytesAndSkipRespectTheEnd) {
  const std::array<std::uint8_t, 4> bytes = {1, 2, 3, 4};
  ByteReader reader(bytes);
  EXPECT_EQ(Of(reader.Bytes(2)), (Bytes{1, 2}));
  EXPECT_TRUE(reader.Bytes(3).empty());
  EXPECT_FALSE(reader.ok());

  ByteReader skipper(bytes);
  skipper.Skip(4);
  EXPECT_TRUE(skipper.ok());
  EXPECT_TRUE(skipper.empty());
  skipper.Skip(1);
  EXPECT_FALSE(skipper.ok());
}

TEST(CipByteReader, TakeGivesABoundedChildAndAdvancesTheParent) {
  const std::array<std::uint8_t, 5> bytes = {1, 2, 3, 4, 5};
  ByteReader reader(bytes);
  ByteReader child = reader.Take(2);
  EXPECT_EQ(reader.position(), 2U);
  EXPECT_EQ(child.U16(), 0x0201);
  EXPECT_EQ(child.U8(), 0);  // the child ends where the field ends
  EXPECT_FALSE(child.ok());
  EXPECT_TRUE(reader.ok());
  EXPECT_EQ(reader.U8(), 3);

  ByteReader too_long = reader.Take(3);  // two bytes remain
  EXPECT_FALSE(too_long.ok());
  EXPECT_FALSE(reader.ok());
}

TEST(CipByteReader, RestTakesEverythingLeft) {
  const std::array<std::uint8_t, 3> bytes = {7, 8, 9};
  ByteReader reader(bytes);
  reader.Skip(1);
  EXPECT_EQ(Of(reader.Rest()), (Bytes{8, 9}));
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(CipByteWriter, WritesLittleAndBigEndian) {
  std::array<std::uint8_t, 13> buffer{};
  ByteWriter writer(buffer);
  writer.U8(0x01);
  writer.U16(0x1234);
  writer.U32(0x12345678);
  writer.U16Be(0xAF12);
  writer.U32Be(0x0A00020F);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()),
            (Bytes{0x01, 0x34, 0x12, 0x78, 0x56, 0x34, 0x12, 0xAF, 0x12, 0x0A, 0x00, 0x02, 0x0F}));
}

TEST(CipByteWriter, WritePastCapacity_WritesNothingAndFailsSticky) {
  std::array<std::uint8_t, 3> buffer = {0xEE, 0xEE, 0xEE};
  ByteWriter writer(buffer);
  writer.U16(0x2211);
  writer.U16(0x4433);  // does not fit
  EXPECT_FALSE(writer.ok());
  EXPECT_EQ(writer.size(), 2U);
  EXPECT_EQ(buffer[2], 0xEE);  // nothing of the failed write landed
  writer.U8(0x55);             // would fit, but the writer has failed
  EXPECT_EQ(writer.size(), 2U);
  EXPECT_EQ(buffer[2], 0xEE);
}

TEST(CipByteWriter, PatchFillsAFieldWrittenEarlier) {
  std::array<std::uint8_t, 4> buffer{};
  ByteWriter writer(buffer);
  writer.U16(0);
  writer.U16(0xBEEF);
  writer.PatchU16(0, 0x0102);
  writer.PatchU8(3, 0x99);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{0x02, 0x01, 0xEF, 0x99}));
  writer.PatchU16(3, 1);  // would reach past what was written
  EXPECT_FALSE(writer.ok());
}

TEST(CipByteWriter, TruncateRewindsAndClearsTheFailure) {
  std::array<std::uint8_t, 4> buffer{};
  ByteWriter writer(buffer);
  writer.U32(0x04030201);
  writer.U8(5);
  ASSERT_FALSE(writer.ok());
  writer.Truncate(1);
  EXPECT_TRUE(writer.ok());
  writer.U8(0xAA);
  EXPECT_EQ(Of(writer.written()), (Bytes{0x01, 0xAA}));
}

TEST(CipByteWriter, TailAndAdvanceCommitANestedEncoding) {
  std::array<std::uint8_t, 4> buffer{};
  ByteWriter writer(buffer);
  writer.U8(0x10);
  std::span<std::uint8_t> tail = writer.Tail();
  ASSERT_EQ(tail.size(), 3U);
  tail[0] = 0x20;
  tail[1] = 0x30;
  writer.Advance(2);
  EXPECT_EQ(Of(writer.written()), (Bytes{0x10, 0x20, 0x30}));
  writer.Advance(2);  // only one byte of room
  EXPECT_FALSE(writer.ok());
  EXPECT_EQ(writer.size(), 3U);
}

}  // namespace
}  // namespace cip
