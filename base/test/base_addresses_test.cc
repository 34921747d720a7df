// base::Ipv4Address and base::MacAddress: construction from octets and from a host-order integer,
// comparison, and their wire form through base::ByteReader/base::ByteWriter (network order), short input included.
#include "base/addresses.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

namespace base {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes Of(std::span<const std::uint8_t> span) { return Bytes(span.begin(), span.end()); }

TEST(Ipv4Address, OctetsAndHostOrderAreTheSameAddress) {
  constexpr Ipv4Address from_octets(192, 168, 0, 10);
  constexpr Ipv4Address from_integer(0xC0A8000AU);
  static_assert(from_octets == from_integer);
  EXPECT_EQ(from_octets.HostOrder(), 0xC0A8000AU);
  EXPECT_EQ(from_integer.octets(), (Ipv4Address::Octets{192, 168, 0, 10}));
  EXPECT_EQ(Ipv4Address(Ipv4Address::Octets{10, 0, 2, 15}), Ipv4Address(0x0A00020FU));
}

TEST(Ipv4Address, DefaultIsUnspecifiedAndComparisonIsByValue) {
  EXPECT_TRUE(Ipv4Address().IsUnspecified());
  EXPECT_EQ(Ipv4Address(), Ipv4Address(0, 0, 0, 0));
  EXPECT_FALSE(Ipv4Address(0, 0, 0, 1).IsUnspecified());
  EXPECT_NE(Ipv4Address(192, 168, 1, 30), Ipv4Address(192, 168, 1, 31));
  EXPECT_NE(Ipv4Address(1, 0, 0, 0), Ipv4Address(0, 0, 0, 1));
}

TEST(Ipv4Address, WireFormIsNetworkOrder) {
  std::array<std::uint8_t, 4> buffer{};
  base::ByteWriter writer(buffer);
  Ipv4Address(0xC0000201U).Write(writer);
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{192, 0, 2, 1}));

  base::ByteReader reader(buffer);
  EXPECT_EQ(Ipv4Address::Read(reader), Ipv4Address(192, 0, 2, 1));
  EXPECT_TRUE(reader.ok());
  EXPECT_TRUE(reader.empty());
}

TEST(Ipv4Address, ShortInput_YieldsUnspecifiedAndFailsTheReader) {
  const std::array<std::uint8_t, 3> bytes = {192, 0, 2};
  base::ByteReader reader(bytes);
  EXPECT_TRUE(Ipv4Address::Read(reader).IsUnspecified());
  EXPECT_FALSE(reader.ok());

  std::array<std::uint8_t, 3> buffer{};
  base::ByteWriter writer(buffer);
  Ipv4Address(192, 0, 2, 1).Write(writer);
  EXPECT_FALSE(writer.ok());
  EXPECT_EQ(writer.size(), 0U);
}

TEST(MacAddress, OctetsComparisonAndConstants) {
  constexpr MacAddress mac{0x00, 0x00, 0xA0, 0x12, 0x34, 0x56};
  EXPECT_EQ(mac.octets(), (MacAddress::Octets{0x00, 0x00, 0xA0, 0x12, 0x34, 0x56}));
  EXPECT_EQ(MacAddress(MacAddress::Octets{0x00, 0x00, 0xA0, 0x12, 0x34, 0x56}), mac);
  EXPECT_NE(mac, (MacAddress{0x00, 0x00, 0xA0, 0x12, 0x34, 0x57}));
  EXPECT_EQ(MacAddress(), kZeroMac);
  EXPECT_EQ(kBroadcastMac.octets(), (MacAddress::Octets{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
}

TEST(MacAddress, WireFormAndShortInput) {
  std::array<std::uint8_t, 6> buffer{};
  base::ByteWriter writer(buffer);
  MacAddress(0x02, 0x00, 0x5E, 0x10, 0x00, 0x01).Write(writer);
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ(Of(writer.written()), (Bytes{0x02, 0x00, 0x5E, 0x10, 0x00, 0x01}));

  base::ByteReader reader(buffer);
  EXPECT_EQ(MacAddress::Read(reader), (MacAddress{0x02, 0x00, 0x5E, 0x10, 0x00, 0x01}));
  EXPECT_TRUE(reader.ok());

  ByteReader short_reader(std::span<const std::uint8_t>(buffer).first(5));
  EXPECT_EQ(MacAddress::Read(short_reader), kZeroMac);
  EXPECT_FALSE(short_reader.ok());
}

}  // namespace
}  // namespace base
