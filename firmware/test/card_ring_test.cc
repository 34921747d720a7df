// The DLR ring node in the card's frame path (card_ring.h, docs/network.md "Ring (DLR)"): ring frames go to
// the node from the port they came in on, never to lwIP and never learned; beacons pass to the other port
// unchanged; the node's answers leave by their own port; Flush_Tables empties the switch's learning table;
// a port's link-down is reported to the supervisor; the DLR object reads the node.
#include "card_ring.h"

#include <gtest/gtest.h>

#include <vector>

#include "card_addressing_harness.h"
#include "fake_clock.h"

namespace firmware::test {
namespace {

using hal::PortId;
using hal::test::FakeFramePort;

constexpr std::uint32_t kCardIp = 0xC0A8010C;  // 192.168.1.12
constexpr base::MacAddress kSupervisor = {0x02, 0x00, 0x5E, 0x10, 0x00, 0x01};
constexpr std::uint32_t kSupervisorIp = 0xC0A80101;
constexpr base::MacAddress kStation = {0x02, 0x00, 0x00, 0x00, 0x00, 0x0A};
constexpr base::MacAddress kBeaconGroup = {0x01, 0x21, 0x6C, 0x00, 0x00, 0x01};
constexpr base::MacAddress kNeighborGroup = {0x01, 0x21, 0x6C, 0x00, 0x00, 0x02};
constexpr base::MacAddress kAnnounceGroup = {0x01, 0x21, 0x6C, 0x00, 0x00, 0x03};

// A tagged DLR frame (VLAN 0, priority 7) from the supervisor: common header, then `fields`, padded to
// the 30 bytes every message has.
Bytes DlrFrame(const base::MacAddress& destination, std::uint8_t type, std::uint8_t source_port, std::uint32_t sequence,
               const Bytes& fields) {
  Bytes f;
  PutMac(f, destination);
  PutMac(f, kSupervisor);
  Put16(f, 0x8100);
  Put16(f, 0xE000);
  Put16(f, 0x80E1);
  f.insert(f.end(), {0x02, 0x01, type, source_port});
  Put32(f, kSupervisorIp);
  Put32(f, sequence);
  f.insert(f.end(), fields.begin(), fields.end());
  f.resize(18 + 42, 0);
  return f;
}

Bytes Beacon(std::uint8_t source_port, std::uint32_t sequence) {
  Bytes fields = {0x01, 200};  // ring state normal, precedence 200
  Put32(fields, 400);          // interval 400 µs
  Put32(fields, 1960);         // timeout 1960 µs
  return DlrFrame(kBeaconGroup, 1, source_port, sequence, fields);
}

class CardRingTest : public ::testing::Test {
 protected:
  CardRingTest() {
    hal::test::EnsureLwipInitialised();
    netif_.Start(Ipv4Config{base::Ipv4Address(kCardIp), base::Ipv4Address(0xFFFFFF00), {}}, "ipe002z");
    netif_.SetSwitchProtocol(&ring_);
    netif_.SyncLinkState();  // both ports up: the ring hears of them
    port_.sent().clear();
  }
  ~CardRingTest() override { netif_.SetSwitchProtocol(nullptr); }

  void Pump(const Bytes& frame, PortId from) {
    port_.Inject(frame, from);
    netif_.PumpReceive(8);
  }
  // Beacons from both sides: the ring is normal with kSupervisor active.
  void CloseRing() {
    Pump(Beacon(1, 1), PortId::kLeft);
    Pump(Beacon(2, 2), PortId::kRight);
    ASSERT_EQ(ring_.status().node_state, net::DlrNodeState::kNormal);
    port_.sent().clear();
  }

  hal::test::FakeClock clock_{1'000'000};
  FakeFramePort port_{kCardMac, 2};
  CardNetif netif_{port_};
  CardRing ring_{netif_, clock_};
};

TEST_F(CardRingTest, Beacon_PassesUnchangedToTheOtherPort_NotToLwipNotLearned) {
  const Bytes beacon = Beacon(1, 7);
  const std::uint64_t rx_before = netif_.counters().rx_frames;
  Pump(beacon, PortId::kLeft);
  ASSERT_EQ(port_.sent().size(), 1U);
  EXPECT_EQ(port_.sent()[0].port, PortId::kRight);
  EXPECT_EQ(port_.sent()[0].bytes, beacon);
  EXPECT_EQ(netif_.counters().rx_frames, rx_before);
  EXPECT_EQ(netif_.counters().switch_protocol_frames, 1U);
  EXPECT_EQ(netif_.learned_stations(), 0U);
  EXPECT_EQ(ring_.status().supervisor.mac, kSupervisor);
}

TEST_F(CardRingTest, NeighborCheckRequest_AnsweredOutOfItsOwnPortOnly) {
  CloseRing();
  Pump(DlrFrame(kNeighborGroup, 2, 2, 0x01020304, {}), PortId::kRight);
  ASSERT_EQ(port_.sent().size(), 1U);
  const auto& sent = port_.sent()[0];
  EXPECT_EQ(sent.port, PortId::kRight);
  const Bytes& f = sent.bytes;
  ASSERT_EQ(f.size(), 60U);
  EXPECT_EQ(Bytes(f.begin(), f.begin() + 6), Bytes(kNeighborGroup.begin(), kNeighborGroup.end()));
  EXPECT_EQ(Bytes(f.begin() + 6, f.begin() + 12), Bytes(kCardMac.begin(), kCardMac.end()));
  EXPECT_EQ(Get16(f, 12), 0x8100);
  EXPECT_EQ(Get16(f, 14), 0xE000);
  EXPECT_EQ(Get16(f, 16), 0x80E1);
  // Subtype, version, Neighbor_Check_Response 3, leaving by port 2; the card's IP; the request's
  // sequence id; the request's source port 2.
  EXPECT_EQ(Bytes(f.begin() + 18, f.begin() + 31),
            (Bytes{0x02, 0x01, 0x03, 0x02, 0xC0, 0xA8, 0x01, 0x0C, 0x01, 0x02, 0x03, 0x04, 0x02}));
  EXPECT_EQ(ring_.status().counters.neighbor_checks_answered, 1U);
}

TEST_F(CardRingTest, FlushTables_EmptiesTheLearningTable_LearningUpdateOutOfBothPorts) {
  CloseRing();
  Pump(ArpFrameBytes(1, base::kBroadcastMac, kStation, kStation, 0xC0A8010A, base::kZeroMac, kCardIp),
       PortId::kLeft);
  ASSERT_EQ(netif_.learned_stations(), 1U);
  port_.sent().clear();
  const std::uint64_t flushes = netif_.counters().learning_flushes;
  Pump(DlrFrame(kAnnounceGroup, 9, 1, 9, {0x01}), PortId::kLeft);
  EXPECT_EQ(netif_.learned_stations(), 0U);
  EXPECT_EQ(netif_.counters().learning_flushes, flushes + 1);
  std::vector<PortId> learning_updates;
  for (const auto& sent : port_.sent()) {
    if (Get16(sent.bytes, 12) == 0x80E1 && sent.bytes[16] == 10) learning_updates.push_back(sent.port);
  }
  EXPECT_EQ(learning_updates, (std::vector<PortId>{PortId::kLeft, PortId::kRight}));
}

TEST_F(CardRingTest, LinkDown_LinkStatusToTheSupervisorOutOfTheOtherPort) {
  CloseRing();
  port_.SetLink(PortId::kLeft, false);
  netif_.SyncLinkState();
  ASSERT_EQ(port_.sent().size(), 1U);
  const auto& sent = port_.sent()[0];
  EXPECT_EQ(sent.port, PortId::kRight);
  EXPECT_EQ(Bytes(sent.bytes.begin(), sent.bytes.begin() + 6), Bytes(kSupervisor.begin(), kSupervisor.end()));
  EXPECT_EQ(sent.bytes[20], 4);     // Link_Status
  EXPECT_EQ(sent.bytes[30], 0x02);  // port 1 down, port 2 active, Link_Status (bit 7 clear)
  EXPECT_EQ(ring_.status().node_state, net::DlrNodeState::kFault);
}

TEST_F(CardRingTest, BeaconTimeout_FaultAtThePollAfterTheSupervisorsTimeout) {
  CloseRing();
  const hal::Micros closed = clock_.NowMicros();
  clock_.Advance(1000);
  Pump(Beacon(1, 3), PortId::kLeft);  // port 1 keeps hearing beacons, port 2 does not
  EXPECT_EQ(ring_.NextDeadline(), closed + 1960);  // port 2's last beacon plus the supervisor's timeout
  clock_.Set(closed + 1959);
  ring_.Poll(clock_.NowMicros());
  EXPECT_EQ(ring_.status().node_state, net::DlrNodeState::kNormal);
  clock_.Set(closed + 1960);
  ring_.Poll(clock_.NowMicros());
  EXPECT_EQ(ring_.status().node_state, net::DlrNodeState::kFault);
  EXPECT_EQ(ring_.DlrValues().network_status, 1);
}

TEST_F(CardRingTest, DlrObjectValues_FromTheNode) {
  cip::DlrObjectValues before = ring_.DlrValues();
  EXPECT_EQ(before.network_topology, 0);
  EXPECT_EQ(before.supervisor_ip, 0U);
  CloseRing();
  const cip::DlrObjectValues values = ring_.DlrValues();
  EXPECT_EQ(values.network_topology, 1);
  EXPECT_EQ(values.network_status, 0);
  EXPECT_EQ(values.supervisor_ip, kSupervisorIp);
  EXPECT_EQ(values.supervisor_mac, kSupervisor);
  EXPECT_EQ(values.supervisor_precedence, 200);
}

TEST_F(CardRingTest, NonDlrFrames_NotClaimed) {
  EXPECT_FALSE(ring_.Claims(ArpFrameBytes(1, base::kBroadcastMac, kStation, kStation, 1, base::kZeroMac, 2)));
  EXPECT_FALSE(ring_.Claims(Bytes{0x01, 0x02}));  // a runt: nothing to read
  EXPECT_TRUE(ring_.Claims(Beacon(1, 1)));
  Bytes untagged = Beacon(1, 1);
  untagged.erase(untagged.begin() + 12, untagged.begin() + 16);
  EXPECT_TRUE(ring_.Claims(untagged));
}

}  // namespace
}  // namespace firmware::test
