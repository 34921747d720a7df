// LLDP (net/lldp_frame.h, net/lldp_agent.h, docs/network.md "LLDP"): the card's LLDPDU byte for byte,
// the parser's acceptance and refusals (every truncation), and the agent's timeline: first frame after
// link-up, the 30 s interval, prompt but rate-limited change announcements, the neighbour table's key,
// refresh, TTL 0, ageing, full table and link-down rules, and its counters.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "net/lldp_agent.h"
#include "net/lldp_frame.h"

namespace net {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::Micros;

constexpr Micros kS = hal::kMicrosPerSecond;
// Documentation values: MAC 00-00-5E-00-53-xx (RFC 7042), addresses from 192.0.2.0/24 (RFC 5737).
constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::Ipv4Address kAddress(192, 0, 2, 10);

// The card's LLDPDU on port L: device name "drive-7", system description "IPE002Z test", 192.0.2.10.
const Bytes kCardFrame = {
    0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x88, 0xCC,  // Ethernet
    0x02, 0x07, 0x04, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,                                // chassis: MAC
    0x04, 0x02, 0x07, '1',                                                                // port: local "1"
    0x06, 0x02, 0x00, 0x78,                                                               // TTL 120
    0x08, 0x06, 'p', 'o', 'r', 't', ' ', 'L',                                             // port description
    0x0A, 0x07, 'd', 'r', 'i', 'v', 'e', '-', '7',                                        // system name
    0x0C, 0x0C, 'I', 'P', 'E', '0', '0', '2', 'Z', ' ', 't', 'e', 's', 't',               // system description
    0x0E, 0x04, 0x00, 0x04, 0x00, 0x04,                                                   // capabilities: bridge
    0x10, 0x0C, 0x05, 0x01, 0xC0, 0x00, 0x02, 0x0A, 0x02, 0x00, 0x00, 0x00, 0x01, 0x00,   // mgmt 192.0.2.10 if 1
    0x00, 0x00,                                                                           // End
};

// A neighbour's LLDPDU as lldpd sends it (chassis and port by MAC, interface name as description),
// padded to the Ethernet minimum after the End TLV.
Bytes NeighbourFrame(std::uint8_t mac_last, std::uint16_t ttl, std::string_view name = "host-a") {
  Bytes frame = {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E, 0x02, 0x00, 0x5E, 0x00, 0x53, mac_last, 0x88, 0xCC,
                 0x02, 0x07, 0x04, 0x02, 0x00, 0x5E, 0x00, 0x53, mac_last,
                 0x04, 0x07, 0x03, 0x02, 0x00, 0x5E, 0x00, 0x53, mac_last,
                 0x06, 0x02, static_cast<std::uint8_t>(ttl >> 8), static_cast<std::uint8_t>(ttl)};
  frame.push_back(0x0A);
  frame.push_back(static_cast<std::uint8_t>(name.size()));
  frame.insert(frame.end(), name.begin(), name.end());
  const Bytes rest = {0x08, 0x04, 't', 'a', 'p', 'L',
                      0xFE, 0x06, 0x00, 0x80, 0xC2, 0x01, 0x00, 0x01,  // an organisationally specific TLV
                      0x10, 0x0C, 0x05, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x02, 0x00, 0x00, 0x00, 0x03, 0x00,
                      0x00, 0x00};
  frame.insert(frame.end(), rest.begin(), rest.end());
  if (frame.size() < 60) frame.resize(60, 0);
  return frame;
}

std::string_view Text(std::span<const std::uint8_t> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

// ---- Frames ----------------------------------------------------------------------------------------

TEST(LldpFrameTest, CardFrameExactBytes) {
  const LldpAdvert advert{.mac = kOwnMac, .port_id = "1", .ttl_seconds = 120, .port_description = "port L",
                          .system_name = "drive-7", .system_description = "IPE002Z test",
                          .management = kAddress, .interface_number = 1};
  std::array<std::uint8_t, 256> out{};
  const base::Result<std::size_t> size = BuildLldpFrame(advert, out);
  ASSERT_TRUE(size.ok());
  EXPECT_EQ(Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(size.value())), kCardFrame);
}

TEST(LldpFrameTest, NoAddressNoManagementTlv) {
  LldpAdvert advert{.mac = kOwnMac, .port_id = "2", .ttl_seconds = 120, .port_description = "port R",
                    .system_name = "drive-7", .system_description = "IPE002Z test"};
  std::array<std::uint8_t, 256> out{};
  const base::Result<std::size_t> size = BuildLldpFrame(advert, out);
  ASSERT_TRUE(size.ok());
  ASSERT_EQ(size.value(), kCardFrame.size() - 14);
  EXPECT_EQ(out[26], '2');
  EXPECT_EQ(out[38], 'R');
  EXPECT_EQ(out[size.value() - 2], 0x00);  // End right after the capabilities
  EXPECT_EQ(out[size.value() - 8], 0x0E);
}

TEST(LldpFrameTest, TooSmallBufferIsResourceExhausted) {
  const LldpAdvert advert{.mac = kOwnMac, .port_id = "1", .ttl_seconds = 120};
  std::array<std::uint8_t, 40> out{};
  EXPECT_EQ(BuildLldpFrame(advert, out).status(), base::ResourceExhausted());
}

TEST(LldpFrameTest, ParsesTheCardsOwnFrame) {
  const base::Result<LldpNeighbourInfo> info = ParseLldpFrame(kCardFrame);
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->chassis.subtype, kLldpChassisMac);
  EXPECT_EQ(Bytes(info->chassis.id.view().begin(), info->chassis.id.view().end()),
            Bytes(kOwnMac.begin(), kOwnMac.end()));
  EXPECT_EQ(info->port.subtype, kLldpPortLocal);
  EXPECT_EQ(Text(info->port.id.view()), "1");
  EXPECT_EQ(info->ttl_seconds, 120);
  EXPECT_EQ(Text(info->system_name.view()), "drive-7");
  EXPECT_EQ(Text(info->port_description.view()), "port L");
  EXPECT_EQ(info->management, kAddress);
}

TEST(LldpFrameTest, ParsesANeighbourFrameWithPaddingAndUnknownTlvs) {
  const base::Result<LldpNeighbourInfo> info = ParseLldpFrame(NeighbourFrame(0x07, 8));
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->port.subtype, kLldpPortMac);
  EXPECT_EQ(info->ttl_seconds, 8);
  EXPECT_EQ(Text(info->system_name.view()), "host-a");
  EXPECT_EQ(Text(info->port_description.view()), "tapL");
  EXPECT_EQ(info->management, base::Ipv4Address(192, 0, 2, 1));
}

TEST(LldpFrameTest, LongStringsKeepTheirStart) {
  const std::string name(40, 'n');
  const base::Result<LldpNeighbourInfo> info = ParseLldpFrame(NeighbourFrame(0x07, 8, name));
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(Text(info->system_name.view()), std::string(kLldpTextMax, 'n'));
}

TEST(LldpFrameTest, OtherFramesAreNotFound) {
  Bytes frame = kCardFrame;
  frame[13] = 0xCD;  // EtherType 0x88CD
  EXPECT_EQ(ParseLldpFrame(frame).status(), base::NotFound());
  frame = kCardFrame;
  frame[5] = 0x03;  // 01-80-C2-00-00-03: not the nearest-bridge address
  EXPECT_EQ(ParseLldpFrame(frame).status(), base::NotFound());
  EXPECT_EQ(ParseLldpFrame(Bytes(kCardFrame.begin(), kCardFrame.begin() + 13)).status(), base::NotFound());
}

TEST(LldpFrameTest, EveryTruncationInsideTheMandatoryTlvsOrATlvIsRefused) {
  // Cut points that end exactly after a complete TLV from the TTL on are a list without End (accepted).
  const std::vector<std::size_t> boundaries = {31, 39, 48, 62, 68, 82};
  for (std::size_t size = 14; size < kCardFrame.size(); ++size) {
    const base::Result<LldpNeighbourInfo> info = ParseLldpFrame(Bytes(kCardFrame.begin(), kCardFrame.begin() + static_cast<std::ptrdiff_t>(size)));
    const bool boundary = std::find(boundaries.begin(), boundaries.end(), size) != boundaries.end();
    EXPECT_EQ(info.ok(), boundary) << size;
    if (!boundary) {
      EXPECT_EQ(info.status(), base::DataLoss()) << size;
    }
  }
}

TEST(LldpFrameTest, MandatoryTlvsOutOfOrderOrRepeatedAreRefused) {
  // Port ID before Chassis ID.
  Bytes swapped = {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E, 0x02, 0, 0, 0, 0, 1, 0x88, 0xCC,
                   0x04, 0x02, 0x07, '1', 0x02, 0x02, 0x07, 'c', 0x06, 0x02, 0x00, 0x78, 0x00, 0x00};
  EXPECT_EQ(ParseLldpFrame(swapped).status(), base::DataLoss());
  // A second TTL after the mandatory three.
  Bytes repeated = kCardFrame;
  repeated.insert(repeated.end() - 2, {0x06, 0x02, 0x00, 0x10});
  EXPECT_EQ(ParseLldpFrame(repeated).status(), base::DataLoss());
  // TTL of three bytes.
  Bytes ttl = {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E, 0x02, 0, 0, 0, 0, 1, 0x88, 0xCC,
               0x02, 0x02, 0x07, 'c', 0x04, 0x02, 0x07, '1', 0x06, 0x03, 0x00, 0x00, 0x78, 0x00, 0x00};
  EXPECT_EQ(ParseLldpFrame(ttl).status(), base::DataLoss());
  // A chassis ID without an ID byte.
  Bytes empty_id = {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E, 0x02, 0, 0, 0, 0, 1, 0x88, 0xCC,
                    0x02, 0x01, 0x07, 0x04, 0x02, 0x07, '1', 0x06, 0x02, 0x00, 0x78, 0x00, 0x00};
  EXPECT_EQ(ParseLldpFrame(empty_id).status(), base::DataLoss());
}

TEST(LldpFrameTest, EndWithALengthAndBadManagementLengthsAreRefused) {
  Bytes end(kCardFrame.begin(), kCardFrame.end() - 2);
  end.insert(end.end(), {0x00, 0x01, 0x00});  // End TLV of length 1
  EXPECT_EQ(ParseLldpFrame(end).status(), base::DataLoss());
  Bytes management = kCardFrame;
  management[70] = 0x06;  // address string length 6 in a TLV sized for 5
  EXPECT_EQ(ParseLldpFrame(management).status(), base::DataLoss());
  management = kCardFrame;
  management[70] = 0x01;  // shorter than subtype + one address byte
  EXPECT_EQ(ParseLldpFrame(management).status(), base::DataLoss());
}

// ---- Agent -----------------------------------------------------------------------------------------

struct Sent {
  std::size_t port;
  Bytes frame;
};

class RecordingSink final : public LldpSink {
 public:
  void SendLldp(std::size_t port, std::span<const std::uint8_t> frame) override {
    sent.push_back({port, Bytes(frame.begin(), frame.end())});
  }
  std::vector<Sent> sent;
};

class LldpAgentTest : public ::testing::Test {
 protected:
  LldpAgentTest() : agent_({.mac = kOwnMac, .product = "IPE002Z", .system_description = "IPE002Z test"}, sink_) {}

  // Polls at `now` and returns the frames that went out.
  std::vector<Sent> PollAt(Micros now) {
    sink_.sent.clear();
    agent_.Poll(now);
    return sink_.sent;
  }

  RecordingSink sink_;
  LldpAgent agent_;
};

TEST_F(LldpAgentTest, FirstFrameOneSecondAfterLinkUpThenEveryThirtySeconds) {
  agent_.SetSystemName("drive-7");
  agent_.SetManagementAddress(kAddress);
  EXPECT_EQ(agent_.NextDeadline(), hal::kNever);
  agent_.LinkUp(0, 10 * kS);
  EXPECT_EQ(agent_.NextDeadline(), 11 * kS);
  EXPECT_TRUE(PollAt(11 * kS - 1).empty());
  const std::vector<Sent> first = PollAt(11 * kS);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].port, 0u);
  EXPECT_EQ(first[0].frame, kCardFrame);
  EXPECT_EQ(agent_.NextDeadline(), 41 * kS);
  EXPECT_TRUE(PollAt(41 * kS - 1).empty());
  EXPECT_EQ(PollAt(41 * kS).size(), 1u);
  EXPECT_EQ(agent_.counters().frames_out, 2u);
}

TEST_F(LldpAgentTest, EachPortSendsItsOwnPortId) {
  agent_.LinkUp(0, 0);
  agent_.LinkUp(1, 0);
  const std::vector<Sent> sent = PollAt(1 * kS);
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].port, 0u);
  EXPECT_EQ(sent[0].frame[26], '1');
  EXPECT_EQ(sent[1].port, 1u);
  EXPECT_EQ(sent[1].frame[26], '2');
}

TEST_F(LldpAgentTest, AChangeIsSentAtOnceButNotTwiceWithinASecond) {
  agent_.LinkUp(0, 0);
  ASSERT_EQ(PollAt(1 * kS).size(), 1u);
  agent_.SetManagementAddress(kAddress);
  EXPECT_EQ(agent_.NextDeadline(), 2 * kS);  // the minimum gap after the frame at 1 s
  EXPECT_TRUE(PollAt(2 * kS - 1).empty());
  const std::vector<Sent> sent = PollAt(2 * kS);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(ParseLldpFrame(sent[0].frame)->management, kAddress);
  agent_.SetManagementAddress(kAddress);  // unchanged: nothing to send
  EXPECT_EQ(agent_.NextDeadline(), 32 * kS);
  agent_.SetSystemName("x");
  EXPECT_EQ(agent_.NextDeadline(), 3 * kS);
}

TEST_F(LldpAgentTest, EmptyNameFallsBackToProductAndMac) {
  EXPECT_EQ(agent_.system_name(), "IPE002Z-005301");
  agent_.SetSystemName("drive-7");
  EXPECT_EQ(agent_.system_name(), "drive-7");
  agent_.SetSystemName("");
  EXPECT_EQ(agent_.system_name(), "IPE002Z-005301");
}

TEST_F(LldpAgentTest, LinkDownStopsTransmitAndForgetsThePortsNeighbours) {
  agent_.LinkUp(0, 0);
  agent_.LinkUp(1, 0);
  EXPECT_TRUE(agent_.OnFrame(0, NeighbourFrame(1, 120), 0));
  EXPECT_TRUE(agent_.OnFrame(1, NeighbourFrame(2, 120), 0));
  agent_.LinkDown(0);
  ASSERT_EQ(agent_.neighbours().size(), 1u);
  EXPECT_EQ(agent_.neighbours()[0].port, 1);
  const std::vector<Sent> sent = PollAt(1 * kS);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].port, 1u);
}

TEST_F(LldpAgentTest, NeighboursAreKeyedByPortChassisAndPortId) {
  EXPECT_TRUE(agent_.OnFrame(0, NeighbourFrame(1, 120), 0));
  EXPECT_TRUE(agent_.OnFrame(0, NeighbourFrame(1, 120, "renamed"), 5 * kS));  // refresh: same key
  EXPECT_TRUE(agent_.OnFrame(1, NeighbourFrame(1, 120), 5 * kS));              // same neighbour, other port
  ASSERT_EQ(agent_.neighbours().size(), 2u);
  EXPECT_EQ(agent_.neighbours()[0].port, 0);
  EXPECT_EQ(Text(agent_.neighbours()[0].info.system_name.view()), "renamed");
  EXPECT_EQ(agent_.neighbours()[0].expires, 125 * kS);
  EXPECT_EQ(agent_.neighbours()[1].port, 1);
  EXPECT_EQ(agent_.counters().frames_in, 3u);
}

TEST_F(LldpAgentTest, TtlZeroRemovesAndTtlExpiryAgesOut) {
  agent_.OnFrame(0, NeighbourFrame(1, 10), 0);
  agent_.OnFrame(0, NeighbourFrame(2, 20), 0);
  agent_.OnFrame(0, NeighbourFrame(1, 0), 1 * kS);  // shutdown LLDPDU
  ASSERT_EQ(agent_.neighbours().size(), 1u);
  EXPECT_EQ(agent_.NextDeadline(), 20 * kS);
  agent_.Poll(20 * kS - 1);
  EXPECT_EQ(agent_.neighbours().size(), 1u);
  agent_.Poll(20 * kS);
  EXPECT_TRUE(agent_.neighbours().empty());
  EXPECT_EQ(agent_.counters().aged_out, 1u);
  EXPECT_EQ(agent_.NextDeadline(), hal::kNever);
}

TEST_F(LldpAgentTest, AFullTableKeepsItsEntriesAndCountsTheNewcomer) {
  for (std::uint8_t i = 1; i <= kLldpMaxNeighbours; ++i) agent_.OnFrame(0, NeighbourFrame(i, 120), 0);
  EXPECT_TRUE(agent_.OnFrame(0, NeighbourFrame(9, 120), 0));
  EXPECT_EQ(agent_.neighbours().size(), kLldpMaxNeighbours);
  EXPECT_EQ(agent_.counters().table_full, 1u);
  agent_.OnFrame(0, NeighbourFrame(1, 120), 1 * kS);  // a known one is still refreshed
  EXPECT_EQ(agent_.neighbours()[0].expires, 121 * kS);
  agent_.OnFrame(0, NeighbourFrame(2, 0), 1 * kS);  // room again: the newcomer is taken
  agent_.OnFrame(0, NeighbourFrame(9, 120), 2 * kS);
  EXPECT_EQ(agent_.neighbours().back().info.chassis.id.view().back(), 9);
}

TEST_F(LldpAgentTest, MalformedIsCountedAndOtherFramesAreNotTaken) {
  Bytes broken = NeighbourFrame(1, 120);
  broken[15] = 0x40;  // chassis ID length past the frame
  EXPECT_TRUE(agent_.OnFrame(0, broken, 0));
  Bytes arp(42, 0);
  arp[12] = 0x08;
  arp[13] = 0x06;
  EXPECT_FALSE(agent_.OnFrame(0, arp, 0));
  EXPECT_EQ(agent_.counters().frames_in, 1u);
  EXPECT_EQ(agent_.counters().malformed, 1u);
  EXPECT_TRUE(agent_.neighbours().empty());
}

}  // namespace
}  // namespace net
