// CardNetif with two ports and its internal switch (net::FrameSwitch in the frame path, seed 000 §2.3):
// frames for other stations pass between L and R without reaching lwIP, group frames go to both lwIP and
// the other port, the card's own frames go out of the port the destination was learned on, a port's
// link-down forgets its stations, and the observer sees what the card gets and each link-up edge; the
// port frame handler takes its frames (LLDP) with their port before lwIP; SendFrameOn uses one port.
#include <gtest/gtest.h>

#include <vector>

#include "card_addressing_harness.h"
#include "card_netif.h"
#include "lwip/etharp.h"

namespace firmware::test {
namespace {

using hal::PortId;
using hal::test::FakeFramePort;

constexpr std::uint32_t kCardIp = 0xC0A8010C;  // 192.168.1.12
constexpr base::MacAddress kStationA = {0x02, 0x00, 0x00, 0x00, 0x00, 0x0A};
constexpr base::MacAddress kStationB = {0x02, 0x00, 0x00, 0x00, 0x00, 0x0B};
constexpr std::uint32_t kIpA = 0xC0A8010A;
constexpr std::uint32_t kIpB = 0xC0A8010B;

class RecordingObserver final : public NetifObserver {
 public:
  void OnFrameToCard(std::span<const std::uint8_t> frame) override { frames.emplace_back(frame.begin(), frame.end()); }
  void OnPortLinkUp(hal::PortId port) override { link_ups.push_back(port); }
  std::vector<Bytes> frames;
  std::vector<PortId> link_ups;
};

// Ethernet + IPv4 + ICMP echo request (RFC 792), checksums set.
Bytes EchoRequest(const base::MacAddress& destination, const base::MacAddress& source, std::uint32_t src_ip,
                  std::uint32_t dst_ip) {
  Bytes icmp = {8, 0, 0, 0, 0x12, 0x34, 0x00, 0x01, 'p', 'i', 'n', 'g'};
  const std::uint16_t icmp_checksum = FoldComplement(OnesSum(icmp));
  icmp[2] = static_cast<std::uint8_t>(icmp_checksum >> 8);
  icmp[3] = static_cast<std::uint8_t>(icmp_checksum);
  return Ipv4FrameBytes(destination, source, src_ip, dst_ip, 1, icmp);
}

bool IsEchoReplyTo(const Bytes& f, const base::MacAddress& destination) {
  return f.size() >= 35 && std::equal(destination.begin(), destination.end(), f.begin()) && Get16(f, 12) == 0x0800 &&
         f[23] == 1 && f[34] == 0;
}

// Takes LLDP frames (EtherType 0x88CC), as CardLldp does.
class RecordingPortHandler final : public PortFrameHandler {
 public:
  bool TakeFrame(PortId port, std::span<const std::uint8_t> frame) override {
    if (frame.size() < 14 || Get16(frame, 12) != 0x88CC) return false;
    taken.push_back({port, Bytes(frame.begin(), frame.end())});
    return true;
  }
  std::vector<hal::test::FakeFramePort::Sent> taken;
};

Bytes LldpFrame(const base::MacAddress& source) {
  Bytes lldp;
  PutMac(lldp, {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E});
  PutMac(lldp, source);
  Put16(lldp, 0x88CC);
  lldp.resize(60, 0);
  return lldp;
}

class CardNetifSwitchTest : public ::testing::Test {
 protected:
  CardNetifSwitchTest() {
    hal::test::EnsureLwipInitialised();
    netif_.Start(Ipv4Config{base::Ipv4Address(kCardIp), base::Ipv4Address(0xFFFFFF00), {}}, "ipe002z");
    netif_.SetObserver(&observer_);
    port_.sent().clear();  // the link-up gratuitous ARP
  }
  ~CardNetifSwitchTest() override { netif_.SetObserver(nullptr); }

  void Pump(const Bytes& frame, PortId from) {
    port_.Inject(frame, from);
    netif_.PumpReceive(8);
  }
  // The station asks for the card (the switch learns its port); the card asks back and the station
  // answers (lwIP learns its MAC: the ArpGuard lets no stranger's request into the cache).
  void Introduce(const base::MacAddress& mac, std::uint32_t ip, PortId from) {
    Pump(ArpFrameBytes(1, base::kBroadcastMac, mac, mac, ip, base::kZeroMac, kCardIp), from);
    ip4_addr_t address;
    ip4_addr_set_u32(&address, lwip_htonl(ip));
    ASSERT_EQ(etharp_request(&netif_.lwip_netif(), &address), ERR_OK);
    Pump(ArpFrameBytes(2, kCardMac, mac, mac, ip, kCardMac, kCardIp), from);
    port_.sent().clear();
  }

  FakeFramePort port_{kCardMac, 2};
  CardNetif netif_{port_};
  RecordingObserver observer_;
};

TEST_F(CardNetifSwitchTest, UnicastForAnotherStation_PassesToTheOtherPortOnly_NotToLwip) {
  // An echo request to the card's IP address but another MAC: lwIP would answer it if it saw it.
  const Bytes frame = EchoRequest(kStationB, kStationA, kIpA, kCardIp);
  Pump(frame, PortId::kLeft);
  ASSERT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);
  EXPECT_EQ(port_.sent()[0].bytes, frame);
  EXPECT_EQ(netif_.traffic(PortId::kRight).forwarded, 1u);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).forwarded, 0u);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).in_ucast, 1u);
  EXPECT_EQ(netif_.counters().rx_frames, 0u);
  EXPECT_TRUE(observer_.frames.empty());

  // And back from R to L.
  const Bytes back = EchoRequest(kStationA, kStationB, kIpB, kIpA);
  Pump(back, PortId::kRight);
  ASSERT_EQ(port_.sent().size(), 2u);
  EXPECT_EQ(port_.sent()[1].port, PortId::kLeft);
  EXPECT_EQ(port_.sent()[1].bytes, back);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).forwarded, 1u);
}

TEST_F(CardNetifSwitchTest, UnicastToAStationOnTheSamePort_Filtered) {
  Introduce(kStationB, kIpB, PortId::kLeft);
  const std::uint64_t flooded = netif_.traffic(PortId::kRight).forwarded;  // the introduction's broadcast
  EXPECT_EQ(flooded, 1u);
  Pump(EchoRequest(kStationB, kStationA, kIpA, kIpB), PortId::kLeft);
  EXPECT_TRUE(port_.sent().empty());
  EXPECT_EQ(netif_.traffic(PortId::kRight).forwarded, flooded);
  EXPECT_EQ(netif_.counters().rx_frames, 2u);  // only the introduction's ARP request and reply
}

TEST_F(CardNetifSwitchTest, Broadcast_ToLwipAndTheOtherPort_ReplyOutOfTheLearnedPortOnly) {
  const Bytes request = ArpFrameBytes(1, base::kBroadcastMac, kStationA, kStationA, kIpA, base::kZeroMac, kCardIp);
  Pump(request, PortId::kLeft);
  ASSERT_EQ(port_.sent().size(), 2u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);  // flooded first, then lwIP answers
  EXPECT_EQ(port_.sent()[0].bytes, request);
  EXPECT_EQ(port_.sent()[1].port, PortId::kLeft);
  EXPECT_EQ(port_.sent()[1].bytes, ArpFrameBytes(2, kStationA, kCardMac, kCardMac, kCardIp, kStationA, kIpA));
  EXPECT_EQ(netif_.counters().rx_frames, 1u);
  ASSERT_EQ(observer_.frames.size(), 1u);
  EXPECT_EQ(observer_.frames[0], request);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).in_nucast, 1u);
  EXPECT_EQ(netif_.traffic(PortId::kRight).forwarded, 1u);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).out_ucast, 1u);
  EXPECT_EQ(netif_.traffic(PortId::kRight).out_ucast, 0u);
}

TEST_F(CardNetifSwitchTest, EchoFromALearnedStation_AnsweredOutOfItsPortOnly) {
  Introduce(kStationA, kIpA, PortId::kRight);
  const PortTraffic left = netif_.traffic(PortId::kLeft);
  Pump(EchoRequest(kCardMac, kStationA, kIpA, kCardIp), PortId::kRight);
  ASSERT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);
  EXPECT_TRUE(IsEchoReplyTo(port_.sent()[0].bytes, kStationA));
  EXPECT_EQ(netif_.traffic(PortId::kLeft).out_ucast, left.out_ucast);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).forwarded, left.forwarded);
  EXPECT_EQ(netif_.traffic(PortId::kRight).out_ucast, 2u);  // the guard's ARP reply and the echo reply
}

TEST_F(CardNetifSwitchTest, ReservedGroupAddress_CardOnly) {
  Pump(LldpFrame(kStationA), PortId::kLeft);
  EXPECT_TRUE(port_.sent().empty());
  EXPECT_EQ(netif_.traffic(PortId::kRight).forwarded, 0u);
  EXPECT_EQ(observer_.frames.size(), 1u);
}

TEST_F(CardNetifSwitchTest, PortFrameHandler_TakesItsFramesWithTheirPort_OthersGoToLwip) {
  RecordingPortHandler handler;
  netif_.SetPortFrameHandler(&handler);
  const Bytes lldp = LldpFrame(kStationA);
  Pump(lldp, PortId::kRight);
  ASSERT_EQ(handler.taken.size(), 1u);
  EXPECT_EQ(handler.taken[0].port, PortId::kRight);
  EXPECT_EQ(handler.taken[0].bytes, lldp);
  EXPECT_EQ(observer_.frames.size(), 1u);      // the observer still reads it first
  EXPECT_EQ(netif_.counters().rx_frames, 0u);  // but lwIP does not get it
  Pump(ArpFrameBytes(1, base::kBroadcastMac, kStationA, kStationA, kIpA, base::kZeroMac, kCardIp), PortId::kLeft);
  EXPECT_EQ(handler.taken.size(), 1u);
  EXPECT_EQ(netif_.counters().rx_frames, 1u);
  netif_.SetPortFrameHandler(nullptr);
}

TEST_F(CardNetifSwitchTest, SendFrameOn_OnePortOnly_FalseWithoutLink) {
  const Bytes lldp = LldpFrame(kCardMac);
  const PortTraffic left = netif_.traffic(PortId::kLeft);
  const PortTraffic right = netif_.traffic(PortId::kRight);  // the start-up gratuitous ARP went out of both
  ASSERT_TRUE(netif_.SendFrameOn(PortId::kRight, lldp));
  ASSERT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);
  EXPECT_EQ(netif_.traffic(PortId::kRight).out_nucast, right.out_nucast + 1);
  EXPECT_EQ(netif_.traffic(PortId::kLeft).out_nucast, left.out_nucast);
  const NetifCounters before = netif_.counters();
  port_.SetLink(PortId::kRight, false);
  EXPECT_FALSE(netif_.SendFrameOn(PortId::kRight, lldp));
  EXPECT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(netif_.counters().tx_dropped, before.tx_dropped + 1);
  EXPECT_EQ(netif_.counters().tx_frames, before.tx_frames);
}

TEST_F(CardNetifSwitchTest, PortLinkDown_ForgetsItsStations_LinkUpToldToTheObserver) {
  Introduce(kStationA, kIpA, PortId::kRight);
  const Bytes to_a = EchoRequest(kStationA, kCardMac, kCardIp, kIpA);
  ASSERT_TRUE(netif_.SendFrame(to_a));
  ASSERT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);
  port_.sent().clear();

  port_.SetLink(PortId::kRight, false);
  EXPECT_FALSE(netif_.SyncLinkState());  // L still up: the netif's link does not change
  EXPECT_TRUE(netif_.link_up());
  // A is unknown now: flooded, and only L has link.
  ASSERT_TRUE(netif_.SendFrame(to_a));
  ASSERT_EQ(port_.sent().size(), 1u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kLeft);
  port_.sent().clear();

  EXPECT_TRUE(observer_.link_ups.empty());
  port_.SetLink(PortId::kRight, true);
  netif_.SyncLinkState();
  ASSERT_EQ(observer_.link_ups.size(), 1u);
  EXPECT_EQ(observer_.link_ups[0], PortId::kRight);
  netif_.SyncLinkState();
  EXPECT_EQ(observer_.link_ups.size(), 1u);  // an edge, not a level
  ASSERT_TRUE(netif_.SendFrame(to_a));
  ASSERT_EQ(port_.sent().size(), 2u);
  EXPECT_EQ(port_.sent()[0].port, PortId::kLeft);
  EXPECT_EQ(port_.sent()[1].port, PortId::kRight);
}

TEST_F(CardNetifSwitchTest, ForwardToAPortWithoutLink_NotSent) {
  port_.SetLink(PortId::kRight, false);
  netif_.SyncLinkState();
  Pump(EchoRequest(kStationB, kStationA, kIpA, kIpB), PortId::kLeft);
  EXPECT_TRUE(port_.sent().empty());
  EXPECT_EQ(netif_.traffic(PortId::kRight).forwarded, 0u);
  EXPECT_EQ(netif_.traffic(PortId::kRight).out_discards, 0u);
}

TEST_F(CardNetifSwitchTest, AllPortsDown_SendFrameFails) {
  port_.SetLink(PortId::kLeft, false);
  port_.SetLink(PortId::kRight, false);
  EXPECT_TRUE(netif_.SyncLinkState());
  EXPECT_FALSE(netif_.link_up());
  EXPECT_FALSE(netif_.SendFrame(CardAnnouncement(kCardIp)));
  EXPECT_TRUE(port_.sent().empty());
}

}  // namespace
}  // namespace firmware::test
