// Padded EPATH: logical segments in every format, port segments for route paths, electronic keys, data
// and symbol segments, the application path rules, and the encoders.
#include "cip/epath.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

base::Result<ApplicationPath> Decode(std::string_view hex) {
  const Bytes bytes = Hex(hex);
  return DecodeApplicationPath(bytes);
}

TEST(CipEpath, EightBitClassInstanceAttribute) {
  const base::Result<ApplicationPath> path = Decode("20 01 24 01 30 07");
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path->class_id, 1U);
  EXPECT_EQ(path->instance, 1U);
  EXPECT_EQ(path->attribute, 7U);
  EXPECT_FALSE(path->member.has_value());
}

TEST(CipEpath, SixteenAndThirtyTwoBitFormatsWithPadBytes) {
  const base::Result<ApplicationPath> path = Decode("21 00 F5 00 | 26 00 78 56 34 12 | 31 00 0A 01 | 28 02");
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path->class_id, 0xF5U);
  EXPECT_EQ(path->instance, 0x12345678U);
  EXPECT_EQ(path->attribute, 0x010AU);
  EXPECT_EQ(path->member, 2U);
  // Members and connection points have a 32-bit format too.
  EXPECT_EQ(Decode("20 01 24 01 2A 00 01 00 01 00")->member, 0x00010001U);
  EXPECT_EQ(Decode("20 04 2E 00 96 00 00 00")->instance, 150U);
}

// CIP reserves the 32-bit format for class and attribute IDs (both are 16-bit): refused like any reserved
// format, even when the value would fit (the conformance suite's "32-bit class/attribute segment").
TEST(CipEpath, ThirtyTwoBitClassAndAttributeAreReserved) {
  EXPECT_EQ(Decode("22 00 01 00 00 00 24 01").status(), base::InvalidArgument());
  EXPECT_EQ(Decode("20 01 24 01 32 00 01 00 00 00").status(), base::InvalidArgument());
  EXPECT_EQ(Decode("20 01 24 01 32 00 01 00 01 00").status(), base::InvalidArgument());
}

TEST(CipEpath, ConnectionPointStandsForTheInstance) {
  const base::Result<ApplicationPath> path = Decode("20 04 2C 96 30 03");
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path->instance, 150U);
}

TEST(CipEpath, ClassAndInstanceAreRequiredInOrder) {
  EXPECT_EQ(Decode("").status(), base::InvalidArgument());
  EXPECT_EQ(Decode("20 01").status(), base::InvalidArgument());              // no instance
  EXPECT_EQ(Decode("24 01 20 01").status(), base::InvalidArgument());        // instance first
  EXPECT_EQ(Decode("20 01 30 01").status(), base::InvalidArgument());        // attribute without instance
  EXPECT_EQ(Decode("20 01 20 02 24 01").status(), base::InvalidArgument());  // two classes
  EXPECT_EQ(Decode("20 01 24 01 30 01 30 02").status(), base::InvalidArgument());
  EXPECT_EQ(Decode("20 01 24 01 28 01 30 01").status(), base::InvalidArgument());  // attribute after member
}

TEST(CipEpath, TruncatedSegmentsAreOutOfRange) {
  EXPECT_EQ(Decode("20").status(), base::OutOfRange());
  EXPECT_EQ(Decode("21 00 F5").status(), base::OutOfRange());
  EXPECT_EQ(Decode("20 01 25 00 01").status(), base::OutOfRange());
  EXPECT_EQ(Decode("20 01 26 00 01 00 00").status(), base::OutOfRange());
}

TEST(CipEpath, UnknownSegmentTypesAndFormatsAreRefused) {
  EXPECT_EQ(Decode("23 00 01 00 24 01").status(), base::InvalidArgument());  // reserved logical format
  EXPECT_EQ(Decode("3C 01 24 01").status(), base::InvalidArgument());        // reserved logical type
  EXPECT_EQ(Decode("43 01 20 01 24 01").status(), base::InvalidArgument());  // network segment
  EXPECT_EQ(Decode("E0 01").status(), base::InvalidArgument());              // reserved segment type
  EXPECT_EQ(Decode("35 00 01 00").status(), base::InvalidArgument());        // special, 16-bit format
  // Well-formed segments that do not belong in a request path.
  EXPECT_EQ(Decode("01 00 20 01 24 01").status(), base::InvalidArgument());      // port
  EXPECT_EQ(Decode("91 03 61 62 63 00").status(), base::InvalidArgument());      // symbol
  EXPECT_EQ(Decode("20 01 24 01 80 01 00 00").status(), base::InvalidArgument());  // data
}

TEST(CipEpath, PortSegments) {
  const Bytes route = Hex("01 00 | 12 09 31 30 2E 30 2E 32 2E 31 35 00 | 0F 10 00 05 | 1F 02 12 00 AA BB");
  EpathReader reader(route);
  PathSegment segment;
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.kind, SegmentKind::kPort);
  EXPECT_EQ(segment.value, 1U);
  EXPECT_EQ(Of(segment.bytes), Hex("00"));
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.value, 2U);
  EXPECT_EQ(Of(segment.bytes), Hex("31 30 2E 30 2E 32 2E 31 35"));  // "10.0.2.15", then a pad byte
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.value, 16U);
  EXPECT_EQ(Of(segment.bytes), Hex("05"));
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.value, 0x12U);
  EXPECT_EQ(Of(segment.bytes), Hex("AA BB"));
  EXPECT_FALSE(reader.Next(segment));
  EXPECT_TRUE(reader.at_end());

  // A link address longer than what is left, and a missing pad byte.
  const Bytes short_link_bytes = Hex("12 09 31 30");
  EpathReader short_link(short_link_bytes);
  EXPECT_FALSE(short_link.Next(segment));
  EXPECT_EQ(short_link.status(), base::OutOfRange());
  const Bytes no_pad_bytes = Hex("12 01 05");
  EpathReader no_pad(no_pad_bytes);
  EXPECT_FALSE(no_pad.Next(segment));
  EXPECT_EQ(no_pad.status(), base::OutOfRange());
}

TEST(CipEpath, ElectronicKeyDataAndSymbolSegments) {
  const Bytes path = Hex("34 04 79 01 02 00 00 7D 81 08 | 80 02 01 00 02 00 | 91 03 61 62 63 00");
  EpathReader reader(path);
  PathSegment segment;
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.kind, SegmentKind::kElectronicKey);
  EXPECT_EQ(segment.key.vendor_id, 377);
  EXPECT_EQ(segment.key.device_type, 2);
  EXPECT_EQ(segment.key.product_code, 32000);
  EXPECT_EQ(segment.key.major_revision, 0x81);
  EXPECT_EQ(segment.key.minor_revision, 8);
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.kind, SegmentKind::kSimpleData);
  EXPECT_EQ(Of(segment.bytes), Hex("01 00 02 00"));
  ASSERT_TRUE(reader.Next(segment));
  EXPECT_EQ(segment.kind, SegmentKind::kSymbol);
  EXPECT_EQ(Of(segment.bytes), Hex("61 62 63"));
  EXPECT_TRUE(reader.at_end());

  const Bytes wrong_key_bytes = Hex("34 05 79 01 02 00 00 7D 01 08");
  EpathReader wrong_key_format(wrong_key_bytes);
  EXPECT_FALSE(wrong_key_format.Next(segment));
  EXPECT_EQ(wrong_key_format.status(), base::InvalidArgument());
}

TEST(CipEpath, EncodersUseTheSmallestFormat) {
  std::array<std::uint8_t, 32> buffer{};
  base::ByteWriter out(buffer);
  EncodeLogicalSegment(SegmentKind::kClass, 0xF6, out);
  EncodeLogicalSegment(SegmentKind::kInstance, 0x1234, out);
  EncodeLogicalSegment(SegmentKind::kAttribute, 0x12345, out);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), Hex("20 F6 | 25 00 34 12 | 32 00 45 23 01 00"));

  base::ByteWriter port(buffer);
  const std::string_view ip = "10.0.2.15";
  EncodePortSegment(2, std::span(reinterpret_cast<const std::uint8_t*>(ip.data()), ip.size()), port);
  EncodePortSegment(1, Hex("00"), port);
  EncodePortSegment(20, Hex("07"), port);
  EXPECT_EQ(Of(port.written()), Hex("12 09 31 30 2E 30 2E 32 2E 31 35 00 | 01 00 | 0F 14 00 07"));
}

TEST(CipEpath, EncodedPathsDecodeToTheSameValues) {
  for (std::uint32_t value : {0U, 1U, 0xFFU, 0x100U, 0xFFFFU, 0x10000U, 0xFFFFFFFFU}) {
    std::array<std::uint8_t, 32> buffer{};
    base::ByteWriter out(buffer);
    // Class and attribute IDs are 16-bit (their 32-bit format is reserved); instances and members are not.
    const std::uint32_t attribute = value & 0xFFFFU;
    EncodeLogicalSegment(SegmentKind::kClass, 0x04, out);
    EncodeLogicalSegment(SegmentKind::kInstance, value, out);
    EncodeLogicalSegment(SegmentKind::kAttribute, attribute, out);
    EncodeLogicalSegment(SegmentKind::kMember, value, out);
    const base::Result<ApplicationPath> path = DecodeApplicationPath(out.written());
    ASSERT_TRUE(path.ok()) << value;
    EXPECT_EQ(path->instance, value);
    EXPECT_EQ(path->attribute, attribute);
    EXPECT_EQ(path->member, value);
  }
}

}  // namespace
}  // namespace cip
