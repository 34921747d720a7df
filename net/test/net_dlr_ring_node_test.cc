// The DLR ring node (net/dlr_ring_node.h, docs/network.md "Ring (DLR)"): from idle to normal on the
// first beacon, fault on one port's beacon timeout (the supervisor's parameters), idle when both time out,
// supervisor changes by precedence then MAC, Neighbor_Check answered on the port it came from, Link_Status
// to the supervisor on a link change, Locate_Fault's neighbour checks ending in Neighbor_Status,
// Flush_Tables with and without Learning_Update, Sign_On passed on with the node appended, announce-based
// tracking, malformed frames counted, and the bounded transmit queue.
#include "net/dlr_ring_node.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace net {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::Micros;

constexpr Micros kMs = hal::kMicrosPerMilli;
constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::MacAddress kSupervisorMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x10};
constexpr base::MacAddress kNeighborMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x02};
constexpr base::Ipv4Address kOwnIp(192, 0, 2, 10);
constexpr std::uint32_t kTimeout = 1800;  // µs, the supervisor's beacon timeout

Bytes Padded(Bytes bytes) {
  if (bytes.size() < 60) bytes.resize(60, 0x00);
  return bytes;
}

// A tagged DLR frame: destination, source, frame type, source port, source IP 192.0.2.x, sequence, then
// the type's fields.
Bytes Dlr(const base::MacAddress& destination, const base::MacAddress& source, std::uint8_t type,
          std::uint8_t source_port, std::uint8_t ip_last, std::uint32_t sequence, Bytes fields) {
  Bytes frame(destination.begin(), destination.end());
  frame.insert(frame.end(), source.begin(), source.end());
  frame.insert(frame.end(), {0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1, 0x02, 0x01, type, source_port, 0xC0, 0x00, 0x02,
                             ip_last, static_cast<std::uint8_t>(sequence >> 24),
                             static_cast<std::uint8_t>(sequence >> 16), static_cast<std::uint8_t>(sequence >> 8),
                             static_cast<std::uint8_t>(sequence)});
  frame.insert(frame.end(), fields.begin(), fields.end());
  return Padded(frame);
}

Bytes Beacon(std::uint8_t ring_state, std::uint8_t precedence = 5, const base::MacAddress& from = kSupervisorMac,
             std::uint32_t timeout = kTimeout) {
  return Dlr(kDlrBeaconMac, from, 0x01, 0x01, 0x01, 1,
             {ring_state, precedence, 0x00, 0x00, 0x01, 0x90, static_cast<std::uint8_t>(timeout >> 24),
              static_cast<std::uint8_t>(timeout >> 16), static_cast<std::uint8_t>(timeout >> 8),
              static_cast<std::uint8_t>(timeout)});  // interval 400 µs
}
Bytes Announce(std::uint8_t ring_state) { return Dlr(kDlrAnnounceMac, kSupervisorMac, 0x06, 0, 1, 2, {ring_state}); }
Bytes LocateFault() { return Dlr(kDlrAnnounceMac, kSupervisorMac, 0x05, 0, 1, 3, {}); }
Bytes FlushTables(std::uint8_t learning_update) {
  return Dlr(kDlrAnnounceMac, kSupervisorMac, 0x09, 0, 1, 4, {learning_update});
}
Bytes NeighborRequest(std::uint32_t sequence) {
  return Dlr(kDlrNeighborCheckMac, kNeighborMac, 0x02, 0x02, 0x02, sequence, {});
}

std::array<std::uint8_t, 1518> buffer{};

Bytes Next(DlrRingNode& node, std::size_t expected_port) {
  const auto transmit = node.NextTransmit(buffer, 0);
  EXPECT_TRUE(transmit.has_value());
  if (!transmit) return {};
  EXPECT_EQ(transmit->port, expected_port);
  return Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(transmit->length));
}

class DlrRingNodeTest : public ::testing::Test {
 protected:
  DlrRingNodeTest() { node.SetIpAddress(kOwnIp); }
  // A normal ring: the supervisor's beacons on both ports at `now`.
  void NormalRing(Micros now) {
    node.OnFrame(Beacon(1), 0, now);
    node.OnFrame(Beacon(1), 1, now);
  }
  DlrRingNode node{kOwnMac};
};

TEST_F(DlrRingNodeTest, Idle_LinearNoSupervisor) {
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
  EXPECT_EQ(node.status().topology, DlrTopology::kLinear);
  EXPECT_FALSE(node.status().supervisor_known);
  EXPECT_EQ(node.NextDeadline(), hal::kNever);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, FirstBeacon_RingNormalForwardedAndFlushed) {
  const DlrReceive receive = node.OnFrame(Beacon(1), 0, 1000);
  EXPECT_TRUE(receive.forward);
  EXPECT_TRUE(receive.flush_learning_table);
  EXPECT_FALSE(receive.sign_on);
  const DlrRingStatus& status = node.status();
  EXPECT_EQ(status.node_state, DlrNodeState::kNormal);
  EXPECT_EQ(status.topology, DlrTopology::kRing);
  EXPECT_EQ(status.network_status, DlrNetworkStatus::kNormal);
  EXPECT_TRUE(status.supervisor_known);
  EXPECT_EQ(status.supervisor.mac, kSupervisorMac);
  EXPECT_EQ(status.supervisor.ip, base::Ipv4Address(192, 0, 2, 1));
  EXPECT_EQ(status.supervisor.precedence, 5);
  EXPECT_EQ(status.supervisor.beacon_interval_us, 400U);
  EXPECT_EQ(status.supervisor.beacon_timeout_us, kTimeout);
  EXPECT_EQ(status.ports[0].beacons, 1U);
  EXPECT_EQ(status.counters.flushes, 1U);
  // Both ports now expect beacons within the supervisor's timeout.
  EXPECT_EQ(node.NextDeadline(), 1000 + kTimeout);
  // The next beacons change nothing and flush nothing.
  EXPECT_FALSE(node.OnFrame(Beacon(1), 1, 1400).flush_learning_table);
  EXPECT_TRUE(node.OnFrame(Beacon(1), 1, 1400).forward);
}

TEST_F(DlrRingNodeTest, BeaconTimeoutOnOnePort_Fault) {
  NormalRing(0);
  node.OnFrame(Beacon(1), 0, 1000);  // port 0 keeps receiving, port 1 does not
  EXPECT_FALSE(node.Poll(kTimeout - 1));
  EXPECT_EQ(node.status().node_state, DlrNodeState::kNormal);
  EXPECT_EQ(node.NextDeadline(), kTimeout);
  EXPECT_TRUE(node.Poll(kTimeout));  // port 1's beacons are overdue: flush
  EXPECT_EQ(node.status().node_state, DlrNodeState::kFault);
  EXPECT_EQ(node.status().network_status, DlrNetworkStatus::kRingFault);
  EXPECT_EQ(node.status().topology, DlrTopology::kRing);
  EXPECT_EQ(node.status().counters.ring_faults, 1U);
  // Beacons back on port 1: normal again.
  EXPECT_TRUE(node.OnFrame(Beacon(1), 1, 2000).flush_learning_table);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kNormal);
}

TEST_F(DlrRingNodeTest, BeaconTimeoutOnBothPorts_Idle) {
  NormalRing(0);
  EXPECT_TRUE(node.Poll(kTimeout));
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
  EXPECT_EQ(node.status().topology, DlrTopology::kLinear);
  EXPECT_EQ(node.status().network_status, DlrNetworkStatus::kNormal);
  EXPECT_TRUE(node.status().supervisor_known);  // the last one stays on display
  EXPECT_EQ(node.NextDeadline(), hal::kNever);
}

TEST_F(DlrRingNodeTest, FaultBeacon_FaultState) {
  NormalRing(0);
  EXPECT_TRUE(node.OnFrame(Beacon(2), 0, 100).flush_learning_table);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kFault);
  EXPECT_EQ(node.status().counters.ring_faults, 1U);
}

TEST_F(DlrRingNodeTest, SupervisorChange_PrecedenceThenMac) {
  NormalRing(0);
  const base::MacAddress lower_mac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x0F};
  const base::MacAddress higher_mac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x11};
  // Lower precedence, or equal precedence with a lower MAC: forwarded, not followed.
  EXPECT_TRUE(node.OnFrame(Beacon(1, 4, higher_mac), 0, 10).forward);
  EXPECT_FALSE(node.OnFrame(Beacon(1, 5, lower_mac), 0, 10).flush_learning_table);
  EXPECT_EQ(node.status().supervisor.mac, kSupervisorMac);
  // Equal precedence, higher MAC: the new active supervisor; the table is flushed.
  EXPECT_TRUE(node.OnFrame(Beacon(1, 5, higher_mac), 1, 20).flush_learning_table);
  EXPECT_EQ(node.status().supervisor.mac, higher_mac);
  // Higher precedence beats any MAC.
  EXPECT_TRUE(node.OnFrame(Beacon(1, 6, lower_mac), 1, 30).flush_learning_table);
  EXPECT_EQ(node.status().supervisor.mac, lower_mac);
  EXPECT_EQ(node.status().supervisor.precedence, 6);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kNormal);
}

TEST_F(DlrRingNodeTest, NeighborCheckRequest_AnsweredOnItsPortWithItsSequence) {
  const DlrReceive receive = node.OnFrame(NeighborRequest(0x00001234), 1, 0);
  EXPECT_FALSE(receive.forward);  // between neighbours only
  EXPECT_EQ(node.status().counters.neighbor_checks_answered, 1U);
  EXPECT_EQ(node.status().ports[1].answered, 1U);
  EXPECT_EQ(Next(node, 1), Padded({
                               0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
                               0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                               0x02, 0x01, 0x03, 0x02,              // response, out of our port 2
                               0xC0, 0x00, 0x02, 0x0A,              // our IP
                               0x00, 0x00, 0x12, 0x34,              // the request's sequence id
                               0x02,                                // the request's source port
                           }));
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, LinkDown_LinkStatusToTheSupervisorAndFault) {
  NormalRing(0);
  EXPECT_TRUE(node.OnLinkChange(0, false, 100));
  EXPECT_EQ(node.status().node_state, DlrNodeState::kFault);
  EXPECT_EQ(node.status().counters.link_status_sent, 1U);
  EXPECT_EQ(Next(node, 1), Padded({
                               0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
                               0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                               0x02, 0x01, 0x04, 0x00, 0xC0, 0x00, 0x02, 0x0A, 0x00, 0x00, 0x00, 0x01,
                               0x02,  // Link_Status: port 1 down, port 2 active
                           }));
  // Up again: another Link_Status, both active, out of port 2 (it never went down).
  EXPECT_FALSE(node.OnLinkChange(0, true, 200));
  const Bytes up = Next(node, 1);
  ASSERT_EQ(up.size(), 60U);
  EXPECT_EQ(up[30], 0x03);
  // No repeated event, no frame.
  EXPECT_FALSE(node.OnLinkChange(0, true, 300));
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, BothLinksDown_IdleAndNoWayOut) {
  NormalRing(0);
  EXPECT_TRUE(node.OnLinkChange(0, false, 100));
  EXPECT_TRUE(node.OnLinkChange(1, false, 200));
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
  EXPECT_EQ(node.status().counters.link_status_sent, 1U);  // the first, out of port 2; then no port left
  EXPECT_EQ(Next(node, 1)[30], 0x02);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
  EXPECT_EQ(node.NextDeadline(), hal::kNever);
}

TEST_F(DlrRingNodeTest, LinkChangeWithoutRing_NothingSent) {
  EXPECT_FALSE(node.OnLinkChange(1, false, 0));
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
  EXPECT_EQ(node.status().counters.link_status_sent, 0U);
}

TEST_F(DlrRingNodeTest, LocateFault_NeighborChecksThenNeighborStatus) {
  constexpr std::uint32_t kSlowTimeout = 1000 * 1000;  // a supervisor with a 1 s beacon timeout
  node.OnFrame(Beacon(1, 5, kSupervisorMac, kSlowTimeout), 0, 0);
  node.OnFrame(Beacon(2, 5, kSupervisorMac, kSlowTimeout), 0, 100);  // the supervisor reports a fault
  ASSERT_EQ(node.status().node_state, DlrNodeState::kFault);
  EXPECT_TRUE(node.OnFrame(LocateFault(), 0, 200).forward);
  const Bytes request0 = Next(node, 0);
  const Bytes request1 = Next(node, 1);
  ASSERT_EQ(request0.size(), 60U);
  EXPECT_EQ(request0[20], 0x02);  // Neighbor_Check_Request
  EXPECT_EQ(request0[21], 0x01);  // from our port 1
  EXPECT_EQ(request1[21], 0x02);
  // Port 1's neighbour answers (its port 2 -> our port 1) with our sequence id.
  Bytes response = Dlr(kDlrNeighborCheckMac, kNeighborMac, 0x03, 0x02, 0x02, 0, {0x01});
  std::copy(request0.begin() + 26, request0.begin() + 30, response.begin() + 26);
  EXPECT_FALSE(node.OnFrame(response, 0, 250).forward);
  // Port 2's neighbour stays silent: two retries 100 ms apart, then Neighbor_Status.
  for (Micros attempt = 1; attempt <= 2; ++attempt) {
    const Micros due = 200 + attempt * kDlrNeighborCheckTimeout;
    EXPECT_EQ(node.NextDeadline(), due);
    EXPECT_FALSE(node.Poll(due));
    EXPECT_EQ(Next(node, 1)[20], 0x02) << attempt;
  }
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
  EXPECT_FALSE(node.Poll(200 + 3 * kDlrNeighborCheckTimeout));
  const Bytes status = Next(node, 0);  // out of the port whose neighbour answered
  ASSERT_EQ(status.size(), 60U);
  EXPECT_EQ(Bytes(status.begin(), status.begin() + 6), Bytes(kSupervisorMac.begin(), kSupervisorMac.end()));
  EXPECT_EQ(status[20], 0x04);
  EXPECT_EQ(status[30], 0x81);  // Neighbor_Status: port 1 active, port 2 lost
  EXPECT_EQ(node.status().counters.neighbor_status_sent, 1U);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
  EXPECT_EQ(node.NextDeadline(), 1000 * 1000U);  // port 2's beacon timeout, no check left
}

TEST_F(DlrRingNodeTest, LocateFaultInNormalState_Ignored) {
  NormalRing(0);
  EXPECT_TRUE(node.OnFrame(LocateFault(), 0, 10).forward);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, FlushTablesWithoutLearningUpdate_FlushOnly) {
  NormalRing(0);
  const DlrReceive receive = node.OnFrame(FlushTables(0), 0, 10);
  EXPECT_TRUE(receive.forward);
  EXPECT_TRUE(receive.flush_learning_table);
  EXPECT_EQ(node.status().counters.flushes, 2U);  // the first beacon's, this one
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, FlushTablesWithLearningUpdate_OutOfBothPorts) {
  NormalRing(0);
  EXPECT_TRUE(node.OnFrame(FlushTables(1), 1, 10).flush_learning_table);
  const Bytes expected = Padded({
      0x01, 0x21, 0x6C, 0x00, 0x00, 0x05, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x80, 0xE1,  // untagged
      0x02, 0x01, 0x0A, 0x00, 0xC0, 0x00, 0x02, 0x0A, 0x00, 0x00, 0x00, 0x01,
  });
  EXPECT_EQ(Next(node, 0), expected);
  EXPECT_EQ(Next(node, 1), expected);
}

TEST_F(DlrRingNodeTest, FlushTablesWithoutRing_NotFlushed) {
  const DlrReceive receive = node.OnFrame(FlushTables(1), 0, 0);
  EXPECT_TRUE(receive.forward);
  EXPECT_FALSE(receive.flush_learning_table);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

const Bytes kSignOn = Padded({
    0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
    0x02, 0x01, 0x07, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00, 0x07, 0x00, 0x01,
    0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0xC0, 0x00, 0x02, 0x01,
});

TEST_F(DlrRingNodeTest, SignOn_AppendedOutOfTheOtherPort) {
  NormalRing(0);
  const DlrReceive receive = node.OnFrame(kSignOn, 0, 10);
  EXPECT_TRUE(receive.sign_on);
  EXPECT_FALSE(receive.forward);
  const auto transmit = node.ForwardSignOn(kSignOn, 0, buffer);
  ASSERT_TRUE(transmit.has_value());
  EXPECT_EQ(transmit->port, 1U);
  EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(transmit->length)),
            Padded({
                0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x81, 0x00, 0xE0, 0x00,
                0x80, 0xE1, 0x02, 0x01, 0x07, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00, 0x07, 0x00, 0x02,
                0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0xC0, 0x00, 0x02, 0x01,
                0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0xC0, 0x00, 0x02, 0x0A,
            }));
  EXPECT_EQ(node.status().counters.sign_ons, 1U);
}

TEST_F(DlrRingNodeTest, SignOnOtherPortDown_BackToTheSupervisor) {
  NormalRing(0);
  (void)node.OnLinkChange(1, false, 5);
  node.OnFrame(Beacon(1), 0, 6);
  node.NextTransmit(buffer, 0);  // the Link_Status
  const auto transmit = node.ForwardSignOn(kSignOn, 0, buffer);
  ASSERT_TRUE(transmit.has_value());
  EXPECT_EQ(transmit->port, 0U);
  EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + 6), Bytes(kSupervisorMac.begin(), kSupervisorMac.end()));
  EXPECT_EQ(buffer[31], 0x02);  // still signed on
}

TEST_F(DlrRingNodeTest, SignOnOutsideNormal_Dropped) {
  const DlrReceive receive = node.OnFrame(kSignOn, 0, 0);
  EXPECT_FALSE(receive.sign_on);
  EXPECT_FALSE(receive.forward);
}

TEST_F(DlrRingNodeTest, UnicastDlrToAnotherStation_Forwarded) {
  NormalRing(0);
  const Bytes status = Dlr(kSupervisorMac, kNeighborMac, 0x04, 0, 2, 9, {0x01});
  const DlrReceive receive = node.OnFrame(status, 1, 10);
  EXPECT_TRUE(receive.forward);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, OwnFrameBackRoundTheRing_Dropped) {
  const DlrReceive receive = node.OnFrame(Dlr(kDlrAnnounceMac, kOwnMac, 0x06, 0, 10, 1, {0x01}), 0, 0);
  EXPECT_FALSE(receive.forward);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
}

TEST_F(DlrRingNodeTest, AnnounceOnly_TrackedUntilTheAnnounceTimeout) {
  EXPECT_TRUE(node.OnFrame(Announce(1), 0, 0).flush_learning_table);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kNormal);
  EXPECT_EQ(node.status().supervisor.mac, kSupervisorMac);
  EXPECT_TRUE(node.OnFrame(Announce(2), 1, hal::kMicrosPerSecond).flush_learning_table);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kFault);
  EXPECT_EQ(node.NextDeadline(), hal::kMicrosPerSecond + kDlrAnnounceTimeout);
  EXPECT_TRUE(node.Poll(hal::kMicrosPerSecond + kDlrAnnounceTimeout));
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
}

TEST_F(DlrRingNodeTest, AnnounceWhileBeaconsRun_Forwarded) {
  NormalRing(0);
  EXPECT_TRUE(node.OnFrame(Announce(2), 0, 10).forward);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kNormal);
}

TEST_F(DlrRingNodeTest, MalformedFrames_CountedNotForwarded) {
  Bytes bad = Beacon(1);
  bad[19] = 0x02;  // protocol version 2
  EXPECT_FALSE(node.OnFrame(bad, 0, 0).forward);
  EXPECT_FALSE(node.OnFrame(Bytes(bad.begin(), bad.begin() + 25), 1, 0).forward);
  EXPECT_EQ(node.status().counters.malformed, 2U);
  EXPECT_EQ(node.status().counters.frames_in, 2U);
  EXPECT_EQ(node.status().ports[1].frames, 1U);
  EXPECT_EQ(node.status().node_state, DlrNodeState::kIdle);
  // Not DLR at all: not even counted.
  Bytes ipv4 = Beacon(1);
  ipv4[16] = 0x08;
  ipv4[17] = 0x00;
  EXPECT_FALSE(node.OnFrame(ipv4, 0, 0).forward);
  EXPECT_EQ(node.status().counters.frames_in, 2U);
}

TEST_F(DlrRingNodeTest, RequestFlood_QueueBounded) {
  for (std::uint32_t i = 0; i < 100; ++i) node.OnFrame(NeighborRequest(i), i % 2, 0);
  EXPECT_EQ(node.status().counters.neighbor_checks_answered, DlrRingNode::kTransmitQueue);
  EXPECT_EQ(node.status().counters.transmit_dropped, 100 - DlrRingNode::kTransmitQueue);
  for (std::size_t i = 0; i < DlrRingNode::kTransmitQueue; ++i) EXPECT_EQ(Next(node, i % 2)[29], i);
  EXPECT_FALSE(node.NextTransmit(buffer, 0).has_value());
}

TEST_F(DlrRingNodeTest, TransmitBufferTooSmall_DroppedAndCounted) {
  node.OnFrame(NeighborRequest(1), 0, 0);
  std::array<std::uint8_t, 20> small{};
  EXPECT_FALSE(node.NextTransmit(small, 0).has_value());
  EXPECT_EQ(node.status().counters.transmit_dropped, 1U);
}

}  // namespace
}  // namespace net
