// The bounded reader and writer every layer uses (base/byte_reader.h, base/byte_writer.h): each byte
// order, sticky failure at the end through every accessor, child readers, reserving and patching.
#include "base/byte_reader.h"
#include "base/byte_writer.h"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace base {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes Of(std::span<const std::uint8_t> span) { return Bytes(span.begin(), span.end()); }

TEST(ByteReader, ReadsLittleAndBigEndian) {
  const std::array<std::uint8_t, 13> bytes = {0x01, 0x34, 0x12, 0x78, 0x56, 0x34, 0x12,
                                              0xAF, 0x12, 0x0A, 0x00, 0x02, 0x0F};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U8(), 0x01);
  EXPECT_EQ(reader.U16Le(), 0x1234);
  EXPECT_EQ(reader.U32Le(), 0x12345678U);
  EXPECT_EQ(reader.U16Be(), 0xAF12);
  EXPECT_EQ(reader.U32Be(), 0x0A00020FU);
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(ByteReader, HighBitBytesDoNotSignExtend) {
  const std::array<std::uint8_t, 4> bytes = {0xFF, 0xFF, 0xFF, 0xFF};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U32Le(), 0xFFFFFFFFU);
}

TEST(ByteReader, ReadPastEnd_FailsStickyAndReturnsZero) {
  const std::array<std::uint8_t, 3> bytes = {0x11, 0x22, 0x33};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U16Le(), 0x2211);
  EXPECT_EQ(reader.U16Le(), 0);  // only one byte left
  EXPECT_FALSE(reader.ok());
  EXPECT_EQ(reader.remaining(), 0U);
  EXPECT_EQ(reader.U8(), 0);  // the last byte is not handed out after the failure
  EXPECT_FALSE(reader.ok());
}

TEST(ByteReader, BytesAndSkipRespectTheEnd) {
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

TEST(ByteReader, TakeGivesABoundedChildAndAdvancesTheParent) {
  const std::array<std::uint8_t, 5> bytes = {1, 2, 3, 4, 5};
  ByteReader reader(bytes);
  ByteReader child = reader.Take(2);
  EXPECT_EQ(reader.position(), 2U);
  EXPECT_EQ(child.U16Le(), 0x0201);
  EXPECT_EQ(child.U8(), 0);  // the child ends where the field ends
  EXPECT_FALSE(child.ok());
  EXPECT_TRUE(reader.ok());
  EXPECT_EQ(reader.U8(), 3);

  ByteReader too_long = reader.Take(3);  // two bytes remain
  EXPECT_FALSE(too_long.ok());
  EXPECT_FALSE(reader.ok());
}

TEST(ByteReader, RestTakesEverythingLeft) {
  const std::array<std::uint8_t, 3> bytes = {7, 8, 9};
  ByteReader reader(bytes);
  reader.Skip(1);
  EXPECT_EQ(Of(reader.Rest()), (Bytes{8, 9}));
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(ByteReader, SixtyFourBitReadsInEachOrder) {
  const std::array<std::uint8_t, 16> bytes = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x88,
                                              0x88, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01};
  ByteReader reader(bytes);
  EXPECT_EQ(reader.U64Le(), 0x8807060504030201ULL);
  EXPECT_EQ(reader.U64Be(), 0x8807060504030201ULL);
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(ByteReader, SameBytesReadInBothOrders) {
  const std::array<std::uint8_t, 4> bytes = {0x12, 0x34, 0x56, 0x78};
  ByteReader little(bytes);
  ByteReader big(bytes);
  EXPECT_EQ(little.U16Le(), 0x3412);
  EXPECT_EQ(big.U16Be(), 0x1234);
  EXPECT_EQ(little.U16Le(), 0x7856);
  EXPECT_EQ(big.U16Be(), 0x5678);
  ByteReader little32(bytes);
  ByteReader big32(bytes);
  EXPECT_EQ(little32.U32Le(), 0x78563412U);
  EXPECT_EQ(big32.U32Be(), 0x12345678U);
}

// Every accessor, given one byte too few, yields its zero value, fails, and leaves nothing to read:
// there is no way to read past the end.
TEST(ByteReader, EveryAccessorOneByteShort_YieldsZeroAndFails) {
  const std::array<std::uint8_t, 8> bytes = {0xA1, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8};
  const auto short_by_one = [&](std::size_t width) { return ByteReader(std::span<const std::uint8_t>(bytes).first(width - 1)); };
  struct Case {
    std::size_t width;
    std::uint64_t (*read)(ByteReader&);
  };
  const Case cases[] = {
      {1, [](ByteReader& r) -> std::uint64_t { return r.U8(); }},
      {2, [](ByteReader& r) -> std::uint64_t { return r.U16Le(); }},
      {2, [](ByteReader& r) -> std::uint64_t { return r.U16Be(); }},
      {4, [](ByteReader& r) -> std::uint64_t { return r.U32Le(); }},
      {4, [](ByteReader& r) -> std::uint64_t { return r.U32Be(); }},
      {8, [](ByteReader& r) -> std::uint64_t { return r.U64Le(); }},
      {8, [](ByteReader& r) -> std::uint64_t { return r.U64Be(); }},
      {3, [](ByteReader& r) -> std::uint64_t { return r.Bytes(3).size(); }},
      {3, [](ByteReader& r) -> std::uint64_t { return r.Take(3).remaining(); }},
  };
  for (const Case& c : cases) {
    ByteReader reader = short_by_one(c.width);
    EXPECT_EQ(c.read(reader), 0U) << "width " << c.width;
    EXPECT_FALSE(reader.ok()) << "width " << c.width;
    EXPECT_EQ(reader.remaining(), 0U) << "width " << c.width;
    EXPECT_EQ(reader.position(), c.width - 1) << "the cursor is at the end";
  }
}

TEST(ByteReader, EmptyReader_EveryReadFails) {
  ByteReader reader;
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.Rest().empty());  // taking nothing from nothing is fine
  EXPECT_TRUE(reader.ok());
  EXPECT_EQ(reader.U8(), 0);
  EXPECT_FALSE(reader.ok());
}

TEST(ByteReader, AfterAFailure_ReadsThatWouldFitStillFail) {
  const std::array<std::uint8_t, 4> bytes = {1, 2, 3, 4};
  ByteReader reader(bytes);
  EXPECT_TRUE(reader.Bytes(5).empty());
  EXPECT_FALSE(reader.ok());
  EXPECT_EQ(reader.U8(), 0);
  EXPECT_TRUE(reader.Bytes(0).empty());
  EXPECT_FALSE(reader.Take(0).ok());
  EXPECT_TRUE(reader.Rest().empty());
  EXPECT_FALSE(reader.ok());
}

TEST(ByteReader, TakeOfExactlyTheRest_SucceedsAndNestedTakesStayInside) {
  const std::array<std::uint8_t, 6> bytes = {0x04, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
  ByteReader reader(bytes);
  const std::uint8_t length = reader.U8();
  ByteReader field = reader.Take(length);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(reader.U8(), 0xEE);
  EXPECT_TRUE(reader.empty());

  ByteReader inner = field.Take(3);
  EXPECT_EQ(Of(inner.Rest()), (Bytes{0xAA, 0xBB, 0xCC}));
  EXPECT_EQ(field.remaining(), 1U);
  ByteReader too_long = field.Take(2);  // the inner field cannot reach into the parent's bytes
  EXPECT_FALSE(too_long.ok());
  EXPECT_EQ(too_long.U8(), 0);
  EXPECT_FALSE(field.ok());
  EXPECT_TRUE(reader.ok());  // a failed child does not fail its parent
}

TEST(ByteWriter, WritesLittleAndBigEndian) {
  std::array<std::uint8_t, 13> buffer{};
  ByteWriter writer(buffer);
  writer.U8(0x01);
  writer.U16Le(0x1234);
  writer.U32Le(0x12345678);
  writer.U16Be(0xAF12);
  writer.U32Be(0x0A00020F);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()),
            (Bytes{0x01, 0x34, 0x12, 0x78, 0x56, 0x34, 0x12, 0xAF, 0x12, 0x0A, 0x00, 0x02, 0x0F}));
}

TEST(ByteWriter, WritePastCapacity_WritesNothingAndFailsSticky) {
  std::array<std::uint8_t, 3> buffer = {0xEE, 0xEE, 0xEE};
  ByteWriter writer(buffer);
  writer.U16Le(0x2211);
  writer.U16Le(0x4433);  // does not fit
  EXPECT_FALSE(writer.ok());
  EXPECT_EQ(writer.size(), 2U);
  EXPECT_EQ(buffer[2], 0xEE);  // nothing of the failed write landed
  writer.U8(0x55);             // would fit, but the writer has failed
  EXPECT_EQ(writer.size(), 2U);
  EXPECT_EQ(buffer[2], 0xEE);
}

TEST(ByteWriter, PatchFillsAFieldWrittenEarlier) {
  std::array<std::uint8_t, 4> buffer{};
  ByteWriter writer(buffer);
  writer.U16Le(0);
  writer.U16Le(0xBEEF);
  writer.PatchU16Le(0, 0x0102);
  writer.PatchU8(3, 0x99);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{0x02, 0x01, 0xEF, 0x99}));
  writer.PatchU16Le(3, 1);  // would reach past what was written
  EXPECT_FALSE(writer.ok());
}

TEST(ByteWriter, TruncateRewindsAndClearsTheFailure) {
  std::array<std::uint8_t, 4> buffer{};
  ByteWriter writer(buffer);
  writer.U32Le(0x04030201);
  writer.U8(5);
  ASSERT_FALSE(writer.ok());
  writer.Truncate(1);
  EXPECT_TRUE(writer.ok());
  writer.U8(0xAA);
  EXPECT_EQ(Of(writer.written()), (Bytes{0x01, 0xAA}));
}

TEST(ByteWriter, TailAndAdvanceCommitANestedEncoding) {
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

TEST(ByteWriter, SixtyFourBitWritesInEachOrder) {
  std::array<std::uint8_t, 16> buffer{};
  ByteWriter writer(buffer);
  writer.U64Le(0x8807060504030201ULL);
  writer.U64Be(0x8807060504030201ULL);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x88,
                                         0x88, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01}));
}

TEST(ByteWriter, EveryWriteOneByteShort_WritesNothingAndFails) {
  const std::array<std::uint8_t, 3> three = {1, 2, 3};
  struct Case {
    std::size_t width;
    void (*write)(ByteWriter&, std::span<const std::uint8_t>);
  };
  const Case cases[] = {
      {1, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U8(0x5A); }},
      {2, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U16Le(0x5A5A); }},
      {2, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U16Be(0x5A5A); }},
      {4, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U32Le(0x5A5A5A5A); }},
      {4, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U32Be(0x5A5A5A5A); }},
      {8, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U64Le(0x5A5A5A5A5A5A5A5AULL); }},
      {8, [](ByteWriter& w, std::span<const std::uint8_t>) { w.U64Be(0x5A5A5A5A5A5A5A5AULL); }},
      {3, [](ByteWriter& w, std::span<const std::uint8_t> bytes) { w.Bytes(bytes); }},
      {3, [](ByteWriter& w, std::span<const std::uint8_t>) { w.Zeros(3); }},
      {3, [](ByteWriter& w, std::span<const std::uint8_t>) { (void)w.Reserve(3); }},
  };
  for (const Case& c : cases) {
    std::array<std::uint8_t, 8> buffer;
    buffer.fill(0xEE);
    ByteWriter writer(std::span<std::uint8_t>(buffer).first(c.width - 1));
    c.write(writer, three);
    EXPECT_FALSE(writer.ok()) << "width " << c.width;
    EXPECT_EQ(writer.size(), 0U) << "width " << c.width;
    EXPECT_EQ(buffer, (std::array<std::uint8_t, 8>{0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE, 0xEE}));
    EXPECT_EQ(writer.Finish().status(), ResourceExhausted());
  }
}

TEST(ByteWriter, ReserveThenPatchInEachOrder) {
  std::array<std::uint8_t, 14> buffer{};
  ByteWriter writer(buffer);
  const std::size_t length_le = writer.Reserve(2);
  const std::size_t length_be = writer.Reserve(2);
  const std::size_t count_le = writer.Reserve(4);
  const std::size_t count_be = writer.Reserve(4);
  writer.U16Be(0xCAFE);
  EXPECT_EQ(Of(writer.written()), (Bytes{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xCA, 0xFE}));
  writer.PatchU16Le(length_le, 0x1234);
  writer.PatchU16Be(length_be, 0x1234);
  writer.PatchU32Le(count_le, 0x01020304);
  writer.PatchU32Be(count_be, 0x01020304);
  EXPECT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()),
            (Bytes{0x34, 0x12, 0x12, 0x34, 0x04, 0x03, 0x02, 0x01, 0x01, 0x02, 0x03, 0x04, 0xCA, 0xFE}));
  const base::Result<std::size_t> finished = writer.Finish();
  ASSERT_TRUE(finished.ok());
  EXPECT_EQ(*finished, 14U);
}

TEST(ByteWriter, PatchBeyondWhatWasWritten_Fails) {
  std::array<std::uint8_t, 8> buffer{};
  ByteWriter writer(buffer);
  writer.U16Le(0);
  writer.PatchU32Be(0, 1);  // four bytes over a two-byte field
  EXPECT_FALSE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{0, 0}));

  ByteWriter other(buffer);
  other.U8(0);
  other.PatchU8(1, 0x77);  // nothing written at offset 1 yet
  EXPECT_FALSE(other.ok());
}

}  // namespace
}  // namespace base
