// The netif's part of QoS (docs/network.md "QoS (DSCP)"): with 802.1Q tagging on, lwIP's frames whose
// DSCP is a CIP class leave with a priority tag; others, and every frame with tagging off, leave as
// lwIP built them. Received priority-tagged IPv4 (VLAN ID 0) reaches lwIP; other VLANs do not.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "card_netif.h"
#include "cip/qos_object.h"
#include "fake_frame_port.h"
#include "lwip/pbuf.h"
#include "lwip/udp.h"
#include "lwip_fixture.h"

namespace firmware {
namespace {

using hal::test::FakeFramePort;

constexpr base::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
constexpr std::uint16_t kPort = 47000;

class CardNetifQosTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hal::test::EnsureLwipInitialised();
    netif_.Start(config_, "ipe002z");
    port_.sent().clear();  // the link-up announcement
    pcb_ = udp_new_ip_type(IPADDR_TYPE_V4);
    ASSERT_NE(pcb_, nullptr);
    ASSERT_EQ(udp_bind(pcb_, IP4_ADDR_ANY, kPort), ERR_OK);
    udp_recv(pcb_, &CardNetifQosTest::OnUdp, this);
  }
  void TearDown() override { udp_remove(pcb_); }

  // A 4-byte broadcast datagram with IP TOS `tos`; returns the frame the port sent.
  std::vector<std::uint8_t> Broadcast(std::uint8_t tos) {
    port_.sent().clear();
    pcb_->tos = tos;
    pbuf* p = pbuf_alloc(PBUF_TRANSPORT, 4, PBUF_RAM);
    pbuf_take(p, "\x01\x02\x03\x04", 4);
    ip_addr_t to;
    IP_ADDR4(&to, 192, 168, 1, 255);
    EXPECT_EQ(udp_sendto(pcb_, p, &to, kPort), ERR_OK);
    pbuf_free(p);
    return port_.sent().empty() ? std::vector<std::uint8_t>{} : port_.sent().back().bytes;
  }

  static void OnUdp(void* arg, udp_pcb*, pbuf* p, const ip_addr_t*, u16_t) {
    ++static_cast<CardNetifQosTest*>(arg)->received_;
    pbuf_free(p);
  }

  FakeFramePort port_{kCardMac};
  CardNetif netif_{port_};
  Ipv4Config config_{base::Ipv4Address(0xC0A8010C), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0xC0A80101)};
  udp_pcb* pcb_ = nullptr;
  int received_ = 0;
};

std::vector<std::uint8_t> Slice(const std::vector<std::uint8_t>& frame, std::size_t from, std::size_t count) {
  return {frame.begin() + static_cast<std::ptrdiff_t>(from), frame.begin() + static_cast<std::ptrdiff_t>(from + count)};
}

TEST_F(CardNetifQosTest, TaggingOn_CipClassesGetTheirPriorityOthersNoTag) {
  cip::QosSettings qos;
  qos.values[0] = 1;
  netif_.SetQosTagging(&qos);
  const std::vector<std::uint8_t> scheduled = Broadcast(cip::TosOfDscp(47));
  ASSERT_EQ(scheduled.size(), 14U + 4 + 20 + 8 + 4);
  EXPECT_EQ(Slice(scheduled, 12, 6), (std::vector<std::uint8_t>{0x81, 0x00, 0xA0, 0x00, 0x08, 0x00}));
  EXPECT_EQ(scheduled[19], 0xBC);  // the IP header follows the tag unchanged
  EXPECT_EQ(Slice(Broadcast(cip::TosOfDscp(27)), 12, 4), (std::vector<std::uint8_t>{0x81, 0x00, 0x60, 0x00}));
  const std::vector<std::uint8_t> unmarked = Broadcast(0);
  ASSERT_EQ(unmarked.size(), 14U + 20 + 8 + 4);
  EXPECT_EQ(Slice(unmarked, 12, 2), (std::vector<std::uint8_t>{0x08, 0x00}));
}

TEST_F(CardNetifQosTest, TaggingOffOrNoValues_NoTag) {
  cip::QosSettings qos;  // tag enable 0, the default
  netif_.SetQosTagging(&qos);
  EXPECT_EQ(Broadcast(cip::TosOfDscp(47)).size(), 14U + 20 + 8 + 4);
  netif_.SetQosTagging(nullptr);
  EXPECT_EQ(Broadcast(cip::TosOfDscp(47)).size(), 14U + 20 + 8 + 4);
}

// A UDP datagram for the card (192.168.1.30 -> 192.168.1.12, port kPort, no UDP checksum) with an
// 802.1Q tag whose TCI is `tci`.
std::vector<std::uint8_t> TaggedDatagram(std::uint16_t tci) {
  std::vector<std::uint8_t> frame = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE,
                                     0x81, 0x00, static_cast<std::uint8_t>(tci >> 8), static_cast<std::uint8_t>(tci),
                                     0x08, 0x00};
  std::vector<std::uint8_t> ip = {0x45, 0x6C, 0x00, 32, 0x00, 0x01, 0x00, 0x00, 64, 17, 0x00, 0x00,
                                  192, 168, 1, 30, 192, 168, 1, 12};
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < ip.size(); i += 2) sum += static_cast<std::uint32_t>(ip[i] << 8 | ip[i + 1]);
  while (sum > 0xFFFF) sum = (sum & 0xFFFF) + (sum >> 16);
  ip[10] = static_cast<std::uint8_t>(~sum >> 8);
  ip[11] = static_cast<std::uint8_t>(~sum);
  frame.insert(frame.end(), ip.begin(), ip.end());
  const std::vector<std::uint8_t> udp = {0xC3, 0x50, kPort >> 8, kPort & 0xFF, 0x00, 12, 0x00, 0x00, 1, 2, 3, 4};
  frame.insert(frame.end(), udp.begin(), udp.end());
  return frame;
}

TEST_F(CardNetifQosTest, ReceivedPriorityTaggedIpv4ReachesLwipOtherVlansDoNot) {
  port_.Inject(TaggedDatagram(0x6000));  // priority 3, VLAN 0
  netif_.PumpReceive(4);
  EXPECT_EQ(received_, 1);
  port_.Inject(TaggedDatagram(0x6005));  // VLAN 5: not the card's
  netif_.PumpReceive(4);
  EXPECT_EQ(received_, 1);
  std::vector<std::uint8_t> untagged = TaggedDatagram(0);
  untagged.erase(untagged.begin() + 12, untagged.begin() + 16);
  port_.Inject(untagged);
  netif_.PumpReceive(4);
  EXPECT_EQ(received_, 2);
}

}  // namespace
}  // namespace firmware
