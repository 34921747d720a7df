// The ArpGuard (firmware/arp_guard.h, docs/security.md "ARP"): which received ARP frames reach lwIP, the
// exact answer it sends for a stranger's request, replies awaited and not, and, on a real lwIP netif, a
// flood of requests from ever-new senders leaving a peer's cache entry in place.
#include "arp_guard.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "card_netif.h"
#include "fake_frame_port.h"
#include "lwip/etharp.h"
#include "lwip_fixture.h"

namespace firmware {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Verdict = ArpGuard::Verdict;

constexpr base::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
constexpr std::uint32_t kCard = 0xC0A8010C;  // 192.168.1.12
constexpr std::uint32_t kPeer = 0xC0A8011E;  // 192.168.1.30

// An ARP frame: operation 1 request / 2 reply, sender MAC 02:AA:BB:CC:DD:<n>.
Bytes Arp(std::uint16_t operation, std::uint32_t sender, std::uint32_t target, std::uint8_t n = 0xEE) {
  Bytes frame = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02, 0xAA, 0xBB, 0xCC, 0xDD, n, 0x08, 0x06,
                 0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, static_cast<std::uint8_t>(operation),
                 0x02, 0xAA, 0xBB, 0xCC, 0xDD, n};
  for (int shift = 24; shift >= 0; shift -= 8) frame.push_back(static_cast<std::uint8_t>(sender >> shift));
  for (int i = 0; i < 6; ++i) frame.push_back(0);
  for (int shift = 24; shift >= 0; shift -= 8) frame.push_back(static_cast<std::uint8_t>(target >> shift));
  return frame;
}

class FakeCache final : public ArpCacheQuery {
 public:
  bool Has(base::Ipv4Address address) const override { return entries.count(address.HostOrder()) != 0; }
  std::set<std::uint32_t> entries;
};

class ArpGuardTest : public ::testing::Test {
 protected:
  void SetUp() override { guard_.SetIdentity(kCardMac, base::Ipv4Address(kCard)); }
  Verdict Inspect(const Bytes& frame, std::uint32_t now_ms = 1000) { return guard_.Inspect(frame, cache_, now_ms); }

  ArpGuard guard_;
  FakeCache cache_;
};

TEST_F(ArpGuardTest, StrangersRequest_AnsweredHereWithLwipsBytes) {
  EXPECT_EQ(Inspect(Arp(1, kPeer, kCard)), Verdict::kAnswer);
  EXPECT_EQ(Bytes(guard_.reply().begin(), guard_.reply().end()),
            (Bytes{0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 0x08, 0x06,
                   0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x02,
                   0x02, 0x11, 0x22, 0x33, 0x44, 0x55, 192, 168, 1, 12,
                   0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 192, 168, 1, 30}));
  EXPECT_EQ(guard_.counters().answered, 1U);
}

TEST_F(ArpGuardTest, KnownSender_ToLwip) {
  cache_.entries.insert(kPeer);
  EXPECT_EQ(Inspect(Arp(1, kPeer, kCard)), Verdict::kPass);
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard)), Verdict::kPass);
  EXPECT_EQ(guard_.counters().answered, 0U);
}

TEST_F(ArpGuardTest, UnsolicitedReply_Dropped) {
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard)), Verdict::kDrop);
  EXPECT_EQ(guard_.counters().dropped, 1U);
}

TEST_F(ArpGuardTest, ReplyToTheCardsRequest_ToLwipForFiveSeconds) {
  guard_.NoteSent(Arp(1, kCard, kPeer), 1000);
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 1000 + 4999), Verdict::kPass);
  EXPECT_EQ(Inspect(Arp(1, kPeer, kCard), 1000 + 4999), Verdict::kPass);  // it asks us at the same time
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 1000 + 5000), Verdict::kDrop);
}

TEST_F(ArpGuardTest, AwaitedAcrossTheMillisecondClocksWrap) {
  guard_.NoteSent(Arp(1, kCard, kPeer), 0xFFFFFF00U);
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 0x00000100U), Verdict::kPass);  // 512 ms later
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 0x00001400U), Verdict::kDrop);  // 5376 ms later
}

TEST_F(ArpGuardTest, AtMostEightAwaited_TheOldestForgotten) {
  for (std::uint32_t i = 0; i < ArpGuard::kMaxAwaited + 1; ++i) guard_.NoteSent(Arp(1, kCard, kPeer + i), 1000 + i);
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 1010), Verdict::kDrop);
  for (std::uint32_t i = 1; i < ArpGuard::kMaxAwaited + 1; ++i) {
    EXPECT_EQ(Inspect(Arp(2, kPeer + i, kCard), 1010), Verdict::kPass) << i;
  }
  // Asking the same address again takes its own entry, not another one.
  guard_.NoteSent(Arp(1, kCard, kPeer + 1), 1011);
  EXPECT_EQ(Inspect(Arp(2, kPeer + 2, kCard), 1011), Verdict::kPass);
}

TEST_F(ArpGuardTest, FramesLwipDoesNotLearnFrom_ToLwip) {
  EXPECT_EQ(Inspect(Arp(1, 0, kCard)), Verdict::kPass);                // ACD probe for our address
  EXPECT_EQ(Inspect(Arp(1, kCard, kCard)), Verdict::kPass);            // a conflict: someone claims it
  EXPECT_EQ(Inspect(Arp(1, kPeer, kPeer)), Verdict::kPass);            // gratuitous ARP of a peer
  EXPECT_EQ(Inspect(Arp(1, kPeer, 0xC0A80101)), Verdict::kPass);       // a request for another host
  EXPECT_EQ(Inspect(Arp(2, kPeer, 0xC0A80101)), Verdict::kPass);       // a reply to another host
  EXPECT_EQ(Inspect(Arp(3, kPeer, kCard)), Verdict::kPass);            // RARP operations: lwIP ignores them
  Bytes ipv4 = Arp(1, kPeer, kCard);
  ipv4[13] = 0x00;  // EtherType 0x0800
  EXPECT_EQ(Inspect(ipv4), Verdict::kPass);
  const Bytes whole = Arp(1, kPeer, kCard);
  EXPECT_EQ(Inspect(Bytes(whole.begin(), whole.begin() + 41)), Verdict::kPass);  // cut short: lwIP drops it
  EXPECT_EQ(guard_.counters().answered + guard_.counters().dropped, 0U);
}

TEST_F(ArpGuardTest, NoAddressYet_EverythingToLwip) {
  guard_.SetIdentity(kCardMac, base::Ipv4Address());
  EXPECT_EQ(Inspect(Arp(1, kPeer, 0)), Verdict::kPass);
  EXPECT_EQ(Inspect(Arp(2, kPeer, 0)), Verdict::kPass);
}

TEST_F(ArpGuardTest, AcdProbesOfTheCard_AwaitNothing) {
  guard_.NoteSent(Arp(1, 0, kPeer), 1000);
  EXPECT_EQ(Inspect(Arp(2, kPeer, kCard), 1001), Verdict::kDrop);
}

// On lwIP: a peer the card talks to keeps its ARP entry through a flood of requests from 200 strangers
// (without the guard, lwIP recycles the oldest entry for every new sender: ARP_TABLE_SIZE is 24).
TEST(CardNetifArpGuard, StrangersFloodKeepsThePeersEntry) {
  hal::test::EnsureLwipInitialised();
  hal::test::FakeFramePort port(kCardMac);
  CardNetif netif(port);
  netif.Start(Ipv4Config{base::Ipv4Address(kCard), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0xC0A80101)}, "ipe002z");
  ip4_addr_t peer;
  ip4_addr_set_u32(&peer, lwip_htonl(kPeer));
  ASSERT_EQ(etharp_request(&netif.lwip_netif(), &peer), ERR_OK);  // the card asks for its peer ...
  port.Inject(Arp(2, kPeer, kCard));                              // ... which answers
  netif.PumpReceive(8);
  eth_addr* mac = nullptr;
  const ip4_addr_t* found = nullptr;
  ASSERT_GE(etharp_find_addr(&netif.lwip_netif(), &peer, &mac, &found), 0);

  port.sent().clear();
  for (std::uint32_t i = 0; i < 200; ++i) {
    port.Inject(Arp(1, 0xC0A80000 + 0x0100 + 40 + i, kCard, static_cast<std::uint8_t>(i)));
    netif.PumpReceive(8);
  }
  EXPECT_GE(etharp_find_addr(&netif.lwip_netif(), &peer, &mac, &found), 0);
  EXPECT_EQ(port.sent().size(), 200U);  // every stranger got its answer
  EXPECT_EQ(netif.arp_guard_counters().answered, 200U);
  // An unsolicited reply from a stranger is not taken either.
  port.Inject(Arp(2, 0xC0A801FA, kCard));
  netif.PumpReceive(8);
  EXPECT_EQ(netif.arp_guard_counters().dropped, 1U);
  ip4_addr_t stranger;
  ip4_addr_set_u32(&stranger, lwip_htonl(0xC0A801FA));
  EXPECT_LT(etharp_find_addr(&netif.lwip_netif(), &stranger, &mac, &found), 0);
}

}  // namespace
}  // namespace firmware
