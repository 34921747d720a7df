// The LAN9118 multicast hash filter the board programs from lwIP's IGMP joins. The expected hash
// indexes were computed independently (the top 6 bits of the bit-reversed, uninverted CRC-32 of zlib).
#include "multicast_filter.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace hal::mps2 {
namespace {

constexpr base::MacAddress kAllSystems = {0x01, 0x00, 0x5E, 0x00, 0x00, 0x01};  // 224.0.0.1
constexpr base::MacAddress kGroup = {0x01, 0x00, 0x5E, 0x01, 0x02, 0x03};       // 239.1.2.3
constexpr base::MacAddress kPtp = {0x01, 0x00, 0x5E, 0x00, 0x01, 0x16};         // 224.0.1.22

TEST(Mps2MulticastFilter, HashIndexIsTheTopSixBitsOfTheEthernetCrc) {
  EXPECT_EQ(Lan9118HashIndex(kAllSystems), 31);
  EXPECT_EQ(Lan9118HashIndex(kGroup), 57);
  EXPECT_EQ(Lan9118HashIndex(kPtp), 7);
  EXPECT_EQ(Lan9118HashIndex({0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}), 63);
  EXPECT_EQ(Lan9118HashIndex({0x01, 0x80, 0xC2, 0x00, 0x00, 0x00}), 25);
  EXPECT_EQ(Lan9118HashIndex({0x33, 0x33, 0x00, 0x00, 0x00, 0x01}), 62);
}

TEST(Mps2MulticastFilter, TableHasTheBitOfEachJoinedGroup) {
  MulticastFilter filter;
  EXPECT_EQ(filter.HashTable(), 0u);
  filter.Join(kAllSystems);
  filter.Join(kGroup);
  EXPECT_EQ(filter.HashTable(), (std::uint64_t{1} << 31) | (std::uint64_t{1} << 57));
  EXPECT_FALSE(filter.PassAll());
}

TEST(Mps2MulticastFilter, GroupStaysUntilLeftAsOftenAsJoined) {
  MulticastFilter filter;
  filter.Join(kPtp);
  filter.Join(kPtp);
  EXPECT_EQ(filter.groups(), 1u);
  ASSERT_TRUE(filter.Leave(kPtp).ok());
  EXPECT_EQ(filter.HashTable(), std::uint64_t{1} << 7);
  ASSERT_TRUE(filter.Leave(kPtp).ok());
  EXPECT_EQ(filter.HashTable(), 0u);
  EXPECT_EQ(filter.Leave(kPtp), base::NotFound());
}

TEST(Mps2MulticastFilter, FullTablePassesAllMulticastUntilEnoughLeave) {
  MulticastFilter filter;
  for (std::size_t i = 0; i < MulticastFilter::kCapacity; ++i) {
    filter.Join({0x01, 0x00, 0x5E, 0x00, 0x02, static_cast<std::uint8_t>(i)});
  }
  EXPECT_FALSE(filter.PassAll());
  filter.Join(kGroup);  // one too many
  EXPECT_TRUE(filter.PassAll());
  EXPECT_EQ(filter.HashTable() & (std::uint64_t{1} << 57), 0u);  // not in the table: passed by MCPAS
  ASSERT_TRUE(filter.Leave(kGroup).ok());
  EXPECT_FALSE(filter.PassAll());
  EXPECT_EQ(filter.Leave(kGroup), base::NotFound());
}

}  // namespace
}  // namespace hal::mps2
