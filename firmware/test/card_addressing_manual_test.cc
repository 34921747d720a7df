// CardAddressing with c504 = 0 (manual address c505-c516) on lwIP and a fake port: ACD before the
// address reaches lwIP (probe, announce), conflicts while probing and in use (defend, yield), the
// validation of the manual address, ACD off, and when Configure restarts the addressing.
#include <gtest/gtest.h>

#include "card_addressing_harness.h"

namespace firmware::test {
namespace {

constexpr std::uint32_t kAddress = 0xC0A8010C;  // 192.168.1.12
constexpr std::uint32_t kOtherIp = 0xC0A8011E;  // 192.168.1.30

config::CardConfig SeedConfig() { return ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0}, {192, 168, 1, 1}); }

// Another host answering for (or announcing) the card's address.
Bytes ConflictingReply() {
  return ArpFrameBytes(2, kCardMac, kOtherMac, kOtherMac, kAddress, kCardMac, 0);
}
Bytes ConflictingAnnouncement() {
  return ArpFrameBytes(1, base::kBroadcastMac, kOtherMac, kOtherMac, kAddress, base::kZeroMac, kAddress);
}

class ManualAddressingTest : public AddressingHarness {
 protected:
  // Configures the seed's address and runs until ACD has probed and installed it. Returns the instant of
  // the first probe.
  Micros ConfigureAndClaim() {
    const Micros start = Now();
    EXPECT_TRUE(addressing_.Configure(SeedConfig()).ok());
    RunUntil(start + 1100 * kMs);  // probe wait <= 200 ms + 3 x 200 ms + announce wait 200 ms
    EXPECT_EQ(LwipAddress(), kAddress);
    const auto arp = ArpSince();
    return arp.empty() ? start : arp.front().at;
  }
  std::size_t CountSince(std::size_t from, const Bytes& frame) const {
    std::size_t n = 0;
    for (const auto& f : ArpSince(from)) n += f.bytes == frame ? 1 : 0;
    return n;
  }
};

TEST_F(ManualAddressingTest, Probing_FourExactProbes200MsApart_NoAddressUntilAnnounceWaitEnds) {
  const Micros start = Now();
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  EXPECT_EQ(LwipAddress(), 0u);

  RunUntil(start + 200 * kMs);  // PROBE_WAIT is 0..200 ms: the first probe is out by then
  auto arp = ArpSince();
  ASSERT_EQ(arp.size(), 1u);
  const Micros first = arp[0].at;
  EXPECT_LE(first - start, 200 * kMs);

  RunUntil(first + 799 * kMs);  // the last probe went out at +600 ms; ANNOUNCE_WAIT is 200 ms
  arp = ArpSince();
  ASSERT_EQ(arp.size(), 4u);
  for (std::size_t i = 0; i < arp.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(arp[i].bytes, CardProbe(kAddress));  // broadcast, sender IP 0.0.0.0, target the address
    EXPECT_EQ(arp[i].port, hal::PortId::kLeft);
    EXPECT_EQ(arp[i].at, first + static_cast<Micros>(i) * 200 * kMs);
  }
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  EXPECT_FALSE(addressing_.has_address());

  RunUntil(first + 800 * kMs);
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(LwipMask(), 0xFFFFFF00u);
  EXPECT_EQ(LwipGateway(), 0xC0A80101u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kInUse);
  EXPECT_EQ(addressing_.active(), (Ipv4Config{base::Ipv4Address(kAddress), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0xC0A80101)}));
  EXPECT_FALSE(addressing_.duplicate_detected());
  // ACD's first announcement, then lwIP's own gratuitous ARP for the new address (the same bytes).
  arp = ArpSince();
  ASSERT_EQ(arp.size(), 6u);
  EXPECT_EQ(arp[4].bytes, CardAnnouncement(kAddress));
  EXPECT_EQ(arp[4].at, first + 800 * kMs);
  EXPECT_EQ(arp[5].bytes, CardAnnouncement(kAddress));

  RunUntil(first + 2800 * kMs);  // ANNOUNCE_INTERVAL 2 s
  arp = ArpSince();
  ASSERT_EQ(arp.size(), 7u);
  EXPECT_EQ(arp[6].bytes, CardAnnouncement(kAddress));
  EXPECT_EQ(arp[6].at, first + 2800 * kMs);
  EXPECT_EQ(addressing_.counters().acd_frames_sent, 6u);  // 4 probes, 2 announcements
  EXPECT_EQ(addressing_.counters().address_changes, 1u);
  EXPECT_EQ(addressing_.counters().acd_conflicts, 0u);
}

TEST_F(ManualAddressingTest, ConflictWhileProbing_AddressNeverInstalled_RetriedAfterAMinute) {
  const Micros start = Now();
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunUntil(start + 450 * kMs);  // two or three probes out
  ASSERT_GE(ArpSince().size(), 2u);
  const Bytes reply = ConflictingReply();
  Receive(reply);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kConflict);
  EXPECT_TRUE(addressing_.duplicate_detected());
  EXPECT_EQ(addressing_.counters().acd_conflicts, 1u);
  const net::AcdConflictRecord& record = addressing_.last_conflict();
  EXPECT_EQ(record.activity, net::AcdActivity::kProbeIpv4Address);
  EXPECT_EQ(record.remote_mac, kOtherMac);
  EXPECT_TRUE(std::equal(record.arp_pdu.begin(), record.arp_pdu.end(), reply.begin() + 14));

  const std::size_t mark = sent_.size();
  const Micros conflict_at = Now();
  RunUntil(conflict_at + 59 * kSec);
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_TRUE(ArpSince(mark).empty());  // no announcement, no further probe
  EXPECT_EQ(addressing_.counters().address_changes, 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kConflict);

  // 60 s after the conflict ACD probes again; the other host has gone, so the address is taken, and the
  // duplicate indication lasts until then.
  RunUntil(conflict_at + 60 * kSec + 200 * kMs);  // retry_interval, then PROBE_WAIT 0..200 ms
  const auto retry = ArpSince(mark);
  ASSERT_EQ(retry.size(), 1u);
  EXPECT_EQ(retry[0].bytes, CardProbe(kAddress));
  EXPECT_GE(retry[0].at, conflict_at + 60 * kSec);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  EXPECT_TRUE(addressing_.duplicate_detected());
  RunFor(1 * kSec);
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_FALSE(addressing_.duplicate_detected());
  EXPECT_EQ(addressing_.last_conflict().activity, net::AcdActivity::kProbeIpv4Address);  // kept until cleared
}

TEST_F(ManualAddressingTest, ProbeFromAnotherHostForTheSameAddress_IsAConflictToo) {
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(250 * kMs);
  Receive(ArpFrameBytes(1, base::kBroadcastMac, kOtherMac, kOtherMac, 0, base::kZeroMac, kAddress));
  EXPECT_EQ(addressing_.phase(), AddressPhase::kConflict);
  RunFor(5 * kSec);
  EXPECT_EQ(LwipAddress(), 0u);
}

TEST_F(ManualAddressingTest, UnrelatedArpWhileProbing_NoConflict) {
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(250 * kMs);
  // Another host asking for a third address, and our own probe reflected back: neither conflicts.
  Receive(ArpFrameBytes(1, base::kBroadcastMac, kOtherMac, kOtherMac, kOtherIp, base::kZeroMac, 0xC0A80101));
  Receive(CardProbe(kAddress));
  RunFor(1 * kSec);
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(addressing_.counters().acd_conflicts, 0u);
}

TEST_F(ManualAddressingTest, ConflictInUse_DefendedOnce_SecondWithinTenSecondsYields) {
  ConfigureAndClaim();
  RunFor(5 * kSec);  // announcements over: ongoing detection
  std::size_t mark = sent_.size();
  const Bytes conflict = ConflictingAnnouncement();
  Receive(conflict);
  // Defended with one announcement, sent from the frame path at once; the address stays.
  auto arp = ArpSince(mark);
  ASSERT_GE(arp.size(), 1u);
  EXPECT_EQ(arp[0].bytes, CardAnnouncement(kAddress));
  EXPECT_EQ(CountSince(mark, CardAnnouncement(kAddress)), 1u);
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kInUse);
  EXPECT_FALSE(addressing_.duplicate_detected());
  EXPECT_EQ(addressing_.last_conflict().activity, net::AcdActivity::kOngoingDetection);
  EXPECT_EQ(addressing_.last_conflict().remote_mac, kOtherMac);

  RunFor(9 * kSec);
  mark = sent_.size();
  Receive(conflict);  // 9 s after the first: within DEFEND_INTERVAL
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kConflict);
  EXPECT_TRUE(addressing_.duplicate_detected());
  // No defence this time, and no ARP reply from lwIP either: the address left lwIP before it read the
  // frame.
  EXPECT_TRUE(ArpSince(mark).empty());
  EXPECT_EQ(addressing_.counters().acd_conflicts, 2u);
  EXPECT_EQ(addressing_.counters().address_changes, 2u);  // installed, removed
  EXPECT_TRUE(std::equal(addressing_.last_conflict().arp_pdu.begin(), addressing_.last_conflict().arp_pdu.end(),
                         conflict.begin() + 14));
}

TEST_F(ManualAddressingTest, ConflictsMoreThanTenSecondsApart_EachDefended) {
  ConfigureAndClaim();
  RunFor(5 * kSec);
  Receive(ConflictingReply());
  RunFor(10 * kSec + 1 * kMs);
  const std::size_t mark = sent_.size();
  Receive(ConflictingReply());
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(CountSince(mark, CardAnnouncement(kAddress)), 1u);
  EXPECT_FALSE(addressing_.duplicate_detected());
}

TEST_F(ManualAddressingTest, PortLinkUpInUse_TwoSemiActiveProbes) {
  ConfigureAndClaim();
  RunFor(5 * kSec);
  port_.SetLink(hal::PortId::kLeft, false);
  Step();
  port_.SetLink(hal::PortId::kLeft, true);
  const Micros up = Now();
  const std::size_t mark = sent_.size();
  Step();
  RunUntil(up + 500 * kMs);
  std::vector<TimedFrame> probes;
  for (const auto& f : ArpSince(mark)) {
    if (f.bytes == CardProbe(kAddress)) probes.push_back(f);
  }
  ASSERT_EQ(probes.size(), 2u);
  EXPECT_EQ(probes[0].at, up + 200 * kMs);
  EXPECT_EQ(probes[1].at, up + 400 * kMs);
  // A conflict right after the burst is recorded as found by the semi-active probe.
  Receive(ConflictingReply());
  EXPECT_EQ(addressing_.last_conflict().activity, net::AcdActivity::kSemiActiveProbe);
}

class UnusableManualAddressTest : public AddressingHarness,
                                  public ::testing::WithParamInterface<base::Ipv4Address> {};

TEST_P(UnusableManualAddressTest, NoAddressNoArp_NotConfigured) {
  ASSERT_TRUE(addressing_.Configure(ManualConfig(GetParam(), {255, 0, 0, 0})).ok());
  RunFor(3 * kSec);
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kNotConfigured);
  EXPECT_TRUE(addressing_.configured());
  EXPECT_FALSE(addressing_.acquiring());
  EXPECT_TRUE(sent_.empty());
  EXPECT_EQ(addressing_.counters().restarts, 1u);
}

INSTANTIATE_TEST_SUITE_P(Addresses, UnusableManualAddressTest,
                         ::testing::Values(base::Ipv4Address{0, 0, 0, 0},
                                           base::Ipv4Address{127, 0, 0, 1},
                                           base::Ipv4Address{224, 0, 0, 5},
                                           base::Ipv4Address{255, 255, 255, 255},
                                           base::Ipv4Address{0, 1, 2, 3}));

TEST(ClassfulMaskTest, ClassAbc) {
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0x0A010203)), base::Ipv4Address(0xFF000000u));  // 10.1.2.3
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0x7E000001)), base::Ipv4Address(0xFF000000u));  // 126.0.0.1
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0x80000001)), base::Ipv4Address(0xFFFF0000u));  // 128.0.0.1
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0xAC100005)), base::Ipv4Address(0xFFFF0000u));  // 172.16.0.5
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0xC0A8010C)), base::Ipv4Address(0xFFFFFF00u));  // 192.168.1.12
  EXPECT_EQ(ClassfulMask(base::Ipv4Address(0xDFFFFF01)), base::Ipv4Address(0xFFFFFF00u));  // 223.255.255.1
}

class ManualAcdOffTest : public AddressingHarness {
 protected:
  ManualAcdOffTest() { addressing_.SetAcdEnabled(false); }
};

TEST_F(ManualAcdOffTest, InstalledAtOnce_NoAcdFrame) {
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  EXPECT_EQ(LwipAddress(), kAddress);  // by Configure itself, before any poll
  EXPECT_EQ(addressing_.phase(), AddressPhase::kInUse);
  RunFor(3 * kSec);
  // Only lwIP's own gratuitous ARP for the new address: no probe, no ACD announcement.
  const auto arp = ArpSince();
  ASSERT_EQ(arp.size(), 1u);
  EXPECT_EQ(arp[0].bytes, CardAnnouncement(kAddress));
  EXPECT_EQ(addressing_.counters().acd_frames_sent, 0u);
  EXPECT_EQ(addressing_.NextDeadline(), hal::kNever);
  // Without ACD a conflicting frame changes nothing.
  Receive(ConflictingReply());
  Receive(ConflictingReply());
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_FALSE(addressing_.duplicate_detected());
  EXPECT_EQ(addressing_.counters().acd_conflicts, 0u);
}

TEST_F(ManualAddressingTest, SelectAcdChanged_AppliesAtTheNextRestartOnly) {
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(100 * kMs);
  addressing_.SetAcdEnabled(false);  // TCP/IP attribute 10 set while ACD probes
  RunFor(300 * kMs);
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  RunFor(1 * kSec);
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(addressing_.counters().acd_frames_sent, 5u);  // 4 probes, the first announcement

  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 20}, {255, 255, 255, 0})).ok());
  EXPECT_EQ(LwipAddress(), 0xC0A80114u);  // the restart: no ACD from now on
  RunFor(5 * kSec);
  EXPECT_EQ(addressing_.counters().acd_frames_sent, 5u);
}

TEST_F(ManualAcdOffTest, MaskZeroOrNonContiguous_ClassfulMask) {
  ASSERT_TRUE(addressing_.Configure(ManualConfig({10, 1, 2, 3}, {0, 0, 0, 0}, {10, 0, 0, 1})).ok());
  EXPECT_EQ(LwipAddress(), 0x0A010203u);
  EXPECT_EQ(LwipMask(), 0xFF000000u);
  EXPECT_EQ(LwipGateway(), 0x0A000001u);
  ASSERT_TRUE(addressing_.Configure(ManualConfig({172, 16, 0, 5}, {255, 0, 255, 0})).ok());
  EXPECT_EQ(LwipAddress(), 0xAC100005u);
  EXPECT_EQ(LwipMask(), 0xFFFF0000u);
  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {0, 0, 0, 0})).ok());
  EXPECT_EQ(LwipMask(), 0xFFFFFF00u);
}

TEST_F(ManualAcdOffTest, GatewayOffSubnet_NoGateway) {
  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0}, {192, 168, 2, 1})).ok());
  EXPECT_EQ(LwipAddress(), kAddress);
  EXPECT_EQ(LwipGateway(), 0u);
  EXPECT_EQ(addressing_.active().gateway, base::Ipv4Address(0u));
}

TEST_F(ManualAddressingTest, SamePlanAgain_NoRestartNoProbe) {
  ConfigureAndClaim();
  RunFor(5 * kSec);
  const AddressingCounters before = addressing_.counters();
  const std::size_t mark = sent_.size();
  config::CardConfig same = SeedConfig();
  same.protocol = config::Protocol::kEtherNetIp;  // not part of the addressing plan
  same.timeout_tenths = 50;
  ASSERT_TRUE(addressing_.Configure(same).ok());
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(5 * kSec);
  EXPECT_EQ(addressing_.counters().restarts, before.restarts);
  EXPECT_EQ(addressing_.counters().address_changes, before.address_changes);
  EXPECT_EQ(addressing_.counters().acd_frames_sent, before.acd_frames_sent);
  EXPECT_TRUE(ArpSince(mark).empty());
  EXPECT_EQ(LwipAddress(), kAddress);
}

TEST_F(ManualAddressingTest, ChangedPlan_RestartsWithTheNewAddress) {
  ConfigureAndClaim();
  RunFor(5 * kSec);
  const std::size_t mark = sent_.size();
  constexpr std::uint32_t kNew = 0xC0A80114;  // 192.168.1.20
  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 20}, {255, 255, 255, 0})).ok());
  EXPECT_EQ(addressing_.counters().restarts, 2u);
  EXPECT_EQ(LwipAddress(), 0u);  // the old address goes at once
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  RunFor(1100 * kMs);
  const auto arp = ArpSince(mark);
  ASSERT_GE(arp.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(arp[i].bytes, CardProbe(kNew)) << i;
  EXPECT_EQ(arp[4].bytes, CardAnnouncement(kNew));
  EXPECT_EQ(LwipAddress(), kNew);
  EXPECT_EQ(addressing_.counters().address_changes, 3u);  // old in, old out, new in

  // A change of the device name alone restarts too (it is the DHCP host name).
  config::CardConfig renamed = ManualConfig({192, 168, 1, 20}, {255, 255, 255, 0});
  renamed.device_name[0] = 'X';
  ASSERT_TRUE(addressing_.Configure(renamed).ok());
  EXPECT_EQ(addressing_.counters().restarts, 3u);
}

// A conflict is about the address that was probed: a restart with another plan starts without it (the
// LEDs show the new sequence, e.g. BOOTP's, not "duplicate"; TCP/IP status bit 6 clears). Attribute 11
// keeps the record until it is cleared.
TEST_F(ManualAddressingTest, ConflictThenRestartWithAnotherPlan_NoLongerDuplicate) {
  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(250 * kMs);
  Receive(ConflictingReply());
  ASSERT_TRUE(addressing_.duplicate_detected());
  ASSERT_TRUE(addressing_.Configure(ModeConfig(config::IpMode::kBootp)).ok());
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
  EXPECT_FALSE(addressing_.duplicate_detected());
  EXPECT_EQ(addressing_.last_conflict().activity, net::AcdActivity::kProbeIpv4Address);

  ASSERT_TRUE(addressing_.Configure(SeedConfig()).ok());
  RunFor(250 * kMs);
  Receive(ConflictingReply());
  ASSERT_TRUE(addressing_.duplicate_detected());
  ASSERT_TRUE(addressing_.Configure(ManualConfig({0, 0, 0, 0}, {0, 0, 0, 0})).ok());
  EXPECT_EQ(addressing_.phase(), AddressPhase::kNotConfigured);
  EXPECT_FALSE(addressing_.duplicate_detected());
}

TEST_F(ManualAddressingTest, BeforeConfigure_NotConfiguredAndSilent) {
  EXPECT_FALSE(addressing_.configured());
  EXPECT_EQ(addressing_.phase(), AddressPhase::kNotConfigured);
  EXPECT_EQ(addressing_.NextDeadline(), hal::kNever);
  RunFor(2 * kSec);
  EXPECT_TRUE(sent_.empty());
  EXPECT_EQ(std::string(AddressPhaseName(AddressPhase::kConflict)), "conflict");
}

}  // namespace
}  // namespace firmware::test
