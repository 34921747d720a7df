// The netif drives the frame port's multicast filter from lwIP's IGMP (netif->igmp_mac_filter): the
// all-systems group from the start, then every group joined and left, each as its 01:00:5e MAC.
#include <gtest/gtest.h>

#include <vector>

#include "card_netif.h"
#include "fake_frame_port.h"
#include "ipv4_lwip.h"
#include "lwip/igmp.h"
#include "lwip_fixture.h"

namespace {

using base::MacAddress;
using hal::test::FakeFramePort;

constexpr base::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
constexpr base::MacAddress kAllSystems = {0x01, 0x00, 0x5E, 0x00, 0x00, 0x01};  // 224.0.0.1

class CardNetifMulticastTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hal::test::EnsureLwipInitialised();
    netif_.Start(firmware::Ipv4Config{base::Ipv4Address(0xC0A8010C), base::Ipv4Address(0xFFFFFF00), {}}, "ipe002z");
  }

  err_t Join(std::uint32_t group) {
    const ip4_addr_t address = firmware::ToLwip(base::Ipv4Address(group));
    return igmp_joingroup_netif(&netif_.lwip_netif(), &address);
  }
  err_t Leave(std::uint32_t group) {
    const ip4_addr_t address = firmware::ToLwip(base::Ipv4Address(group));
    return igmp_leavegroup_netif(&netif_.lwip_netif(), &address);
  }

  FakeFramePort port_{kCardMac};
  firmware::CardNetif netif_{port_};
};

TEST_F(CardNetifMulticastTest, AllSystemsGroupJoinedAtStart) {
  EXPECT_EQ(port_.joined(), std::vector<base::MacAddress>{kAllSystems});
}

TEST_F(CardNetifMulticastTest, JoinedGroupReachesThePortAsItsMac) {
  ASSERT_EQ(Join(0xEF010203), ERR_OK);  // 239.1.2.3
  // The 24th bit of the group address is not in the MAC: 239.129.2.3 shares 01:00:5e:01:02:03.
  ASSERT_EQ(Join(0xEF810203), ERR_OK);
  const base::MacAddress group = {0x01, 0x00, 0x5E, 0x01, 0x02, 0x03};
  EXPECT_EQ(port_.joined(), (std::vector<base::MacAddress>{kAllSystems, group, group}));

  ASSERT_EQ(Leave(0xEF010203), ERR_OK);
  EXPECT_EQ(port_.joined(), (std::vector<base::MacAddress>{kAllSystems, group}));
  ASSERT_EQ(Leave(0xEF810203), ERR_OK);
  EXPECT_EQ(port_.joined(), std::vector<base::MacAddress>{kAllSystems});
}

TEST_F(CardNetifMulticastTest, SecondJoinOfOneGroupIsCountedByLwipNotThePort) {
  ASSERT_EQ(Join(0xE0000116), ERR_OK);  // 224.0.1.22
  ASSERT_EQ(Join(0xE0000116), ERR_OK);
  const base::MacAddress group = {0x01, 0x00, 0x5E, 0x00, 0x01, 0x16};
  EXPECT_EQ(port_.joined(), (std::vector<base::MacAddress>{kAllSystems, group}));
  ASSERT_EQ(Leave(0xE0000116), ERR_OK);
  EXPECT_EQ(port_.joined(), (std::vector<base::MacAddress>{kAllSystems, group}));
  ASSERT_EQ(Leave(0xE0000116), ERR_OK);
  EXPECT_EQ(port_.joined(), std::vector<base::MacAddress>{kAllSystems});
}

}  // namespace
