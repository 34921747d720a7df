#include "card_netif.h"

#include <gtest/gtest.h>

#include <vector>

#include "fake_frame_port.h"
#include "lwip_fixture.h"

namespace {

using hal::PortId;
using hal::test::FakeFramePort;

constexpr base::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};

// ARP request from 192.168.1.30 (peer) asking for 192.168.1.12 (the card).
std::vector<std::uint8_t> ArpRequestForCard() {
  return {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0x08, 0x06,
          0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x01,
          0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 192, 168, 1, 30,
          0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 192, 168, 1, 12};
}

std::vector<std::uint8_t> ExpectedArpReply() {
  return {0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 0x08, 0x06,
          0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x02,
          0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 192, 168, 1, 12,
          0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 192, 168, 1, 30};
}

class CardNetifTest : public ::testing::Test {
 protected:
  void SetUp() override { hal::test::EnsureLwipInitialised(); }
  firmware::Ipv4Config config_{base::Ipv4Address(0xC0A8010C), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0xC0A80101)};  // 192.168.1.12/24 (seed §9 example)
};

TEST_F(CardNetifTest, ArpRequestForCard_AnsweredWithExactReply) {
  FakeFramePort port(kCardMac);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  port.sent().clear();  // link-up announcement (gratuitous ARP)

  port.Inject(ArpRequestForCard());
  EXPECT_EQ(netif.PumpReceive(8), 1u);

  ASSERT_EQ(port.sent().size(), 1u);
  // lwIP pads nothing (ETH_PAD_SIZE 0) and the port adds no FCS: 42 bytes exactly.
  EXPECT_EQ(port.sent()[0].bytes, ExpectedArpReply());
  EXPECT_EQ(netif.counters().rx_frames, 1u);
  EXPECT_EQ(netif.counters().tx_frames, 2u);  // the link-up announcement and the reply
}

TEST_F(CardNetifTest, LinkUpAtStart_SendsGratuitousArp) {
  FakeFramePort port(kCardMac);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  EXPECT_TRUE(netif.link_up());
  ASSERT_FALSE(port.sent().empty());
  const auto& garp = port.sent()[0].bytes;
  ASSERT_EQ(garp.size(), 42u);
  EXPECT_EQ(garp[12], 0x08);
  EXPECT_EQ(garp[13], 0x06);
  // Sender and target protocol address are both the card's.
  EXPECT_EQ(std::vector<std::uint8_t>(garp.begin() + 28, garp.begin() + 32),
            (std::vector<std::uint8_t>{192, 168, 1, 12}));
  EXPECT_EQ(std::vector<std::uint8_t>(garp.begin() + 38, garp.begin() + 42),
            (std::vector<std::uint8_t>{192, 168, 1, 12}));
}

TEST_F(CardNetifTest, AllPortsDown_LinkDownAndFramesDropped) {
  FakeFramePort port(kCardMac, 2);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  port.SetLink(PortId::kLeft, false);
  EXPECT_FALSE(netif.SyncLinkState());  // R still has link: no change
  EXPECT_TRUE(netif.link_up());
  port.SetLink(PortId::kRight, false);
  EXPECT_TRUE(netif.SyncLinkState());
  EXPECT_FALSE(netif.link_up());
  EXPECT_FALSE(netif.SyncLinkState());  // no change the second time

  port.sent().clear();
  port.Inject(ArpRequestForCard());
  netif.PumpReceive(8);
  EXPECT_TRUE(port.sent().empty());
  EXPECT_EQ(netif.counters().tx_dropped, 1u);
}

TEST_F(CardNetifTest, TwoPortsUp_FrameFloodsBoth) {
  FakeFramePort port(kCardMac, 2);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  port.sent().clear();
  port.Inject(ArpRequestForCard(), PortId::kRight);
  netif.PumpReceive(8);
  ASSERT_EQ(port.sent().size(), 2u);
  EXPECT_EQ(port.sent()[0].port, PortId::kLeft);
  EXPECT_EQ(port.sent()[1].port, PortId::kRight);
  EXPECT_EQ(port.sent()[1].bytes, ExpectedArpReply());
}

TEST_F(CardNetifTest, PumpReceive_StopsAtItsBound) {
  FakeFramePort port(kCardMac);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  for (int i = 0; i < 5; ++i) port.Inject(ArpRequestForCard());
  EXPECT_EQ(netif.PumpReceive(3), 3u);
  EXPECT_EQ(port.pending(), 2u);
  EXPECT_EQ(netif.PumpReceive(3), 2u);
}

TEST_F(CardNetifTest, OversizeFrameFromPort_CountedAndSkipped) {
  FakeFramePort port(kCardMac);
  firmware::CardNetif netif(port);
  netif.Start(config_, "ipe002z");
  port.Inject(std::vector<std::uint8_t>(hal::kMaxFrameBytes + 1, 0));
  port.Inject(ArpRequestForCard());
  EXPECT_EQ(netif.PumpReceive(8), 2u);
  EXPECT_EQ(netif.counters().rx_port_errors, 1u);
  EXPECT_EQ(netif.counters().rx_frames, 1u);
}

}  // namespace
