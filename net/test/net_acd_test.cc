// Address Conflict Detection (net/arp.h, net/acd.h, docs/network.md "Address Conflict Detection"):
// exact ARP probe/announcement bytes, the ARP parser's refusals, the probe/announce timelines of both
// timing profiles, conflicts while probing (the address is not taken), defend then yield while in use,
// semi-active probing, the retry, and the exact contents of TCP/IP attributes 10 and 11.
#include "net/acd.h"

#include <gtest/gtest.h>

#include <vector>

#include "queued_random.h"

namespace net {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::Micros;

constexpr Micros kMs = hal::kMicrosPerMilli;
constexpr Micros kS = hal::kMicrosPerSecond;
// Documentation values: MAC 00-00-5E-00-53-xx (RFC 7042), addresses from 192.0.2.0/24 (RFC 5737).
constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::MacAddress kOtherMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x99};
constexpr base::Ipv4Address kAddress(0xC000020A);  // 192.0.2.10
constexpr base::Ipv4Address kOtherAddress(0xC0000214);  // 192.0.2.20

using hal::test::QueuedRandom;

class RecordingSink final : public ArpSink {
 public:
  void SendArp(std::span<const std::uint8_t, kArpFrameSize> frame) override {
    frames.emplace_back(frame.begin(), frame.end());
  }
  std::vector<Bytes> frames;
};

const Bytes kProbeBytes = {
    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x08, 0x06,  // Ethernet
    0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x01,                                      // request
    0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x00, 0x00, 0x00, 0x00,                          // sender, 0.0.0.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xC0, 0x00, 0x02, 0x0A,                          // target 192.0.2.10
};
const Bytes kAnnouncementBytes = {
    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x08, 0x06,
    0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x01,
    0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0xC0, 0x00, 0x02, 0x0A,  // sender 192.0.2.10
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xC0, 0x00, 0x02, 0x0A,
};
// The other host answers our probe: a unicast reply "192.0.2.10 is at 00:00:5e:00:53:99", padded to 60.
const Bytes kConflictingReply = [] {
  Bytes bytes = {
      0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x99, 0x08, 0x06,
      0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x02,
      0x00, 0x00, 0x5E, 0x00, 0x53, 0x99, 0xC0, 0x00, 0x02, 0x0A,
      0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x00, 0x00, 0x00, 0x00,
  };
  bytes.resize(60, 0x00);
  return bytes;
}();

Bytes Frame(const ArpPacket& packet) {
  const ArpFrame frame = EncodeArpFrame(packet);
  return Bytes(frame.begin(), frame.end());
}

// A gratuitous ARP of the other host claiming `ip`.
Bytes OtherAnnounces(base::Ipv4Address ip) { return Frame(ArpAnnouncement(kOtherMac, ip)); }

TEST(AcdArpTest, ProbeAndAnnouncementBytes) {
  EXPECT_EQ(Frame(ArpProbe(kOwnMac, kAddress)), kProbeBytes);
  EXPECT_EQ(Frame(ArpAnnouncement(kOwnMac, kAddress)), kAnnouncementBytes);
}

TEST(AcdArpTest, ParsesAPaddedReply) {
  const base::Result<ArpPacket> parsed = ParseArpFrame(kConflictingReply);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->destination, kOwnMac);
  EXPECT_EQ(parsed->source, kOtherMac);
  EXPECT_EQ(parsed->operation, ArpOperation::kReply);
  EXPECT_EQ(parsed->sender_mac, kOtherMac);
  EXPECT_EQ(parsed->sender_ip, kAddress);
  EXPECT_EQ(parsed->target_mac, kOwnMac);
  EXPECT_EQ(parsed->target_ip, base::Ipv4Address(0U));
  // Round trip of the 42 bytes.
  EXPECT_EQ(Frame(*parsed), Bytes(kConflictingReply.begin(), kConflictingReply.begin() + 42));
}

TEST(AcdArpTest, EveryTruncationIsOutOfRange) {
  for (std::size_t size = 0; size < kArpFrameSize; ++size) {
    EXPECT_EQ(ParseArpFrame(std::span(kProbeBytes).first(size)).status(), base::OutOfRange()) << size;
  }
  EXPECT_TRUE(ParseArpFrame(kProbeBytes).ok());
}

TEST(AcdArpTest, RefusesOtherEtherTypesAndNonIpv4Arp) {
  auto mutated = [](std::size_t offset, std::uint8_t value) {
    Bytes bytes = kProbeBytes;
    bytes[offset] = value;
    return ParseArpFrame(bytes).status();
  };
  EXPECT_EQ(mutated(13, 0x00), base::NotFound());          // EtherType 0x0800 (IPv4)
  EXPECT_EQ(mutated(12, 0x81), base::NotFound());          // 0x8106: not ARP (and no VLAN support)
  EXPECT_EQ(mutated(15, 0x06), base::InvalidArgument());   // hardware type 6 (IEEE 802)
  EXPECT_EQ(mutated(16, 0x86), base::InvalidArgument());   // protocol type 0x8600
  EXPECT_EQ(mutated(18, 0x08), base::InvalidArgument());   // hardware length 8
  EXPECT_EQ(mutated(19, 0x10), base::InvalidArgument());   // protocol length 16
  EXPECT_EQ(mutated(21, 0x03), base::InvalidArgument());   // RARP request
  EXPECT_EQ(mutated(21, 0x00), base::InvalidArgument());   // operation 0
  EXPECT_EQ(mutated(20, 0x01), base::InvalidArgument());   // operation 0x0101
}

struct AcdFixture : ::testing::Test {
  QueuedRandom random;
  RecordingSink sink;
  Acd acd{kOwnMac, kEtherNetIpTimings, random, sink};

  // Polls at `now` and returns the frames sent by that call.
  std::vector<Bytes> PollAt(Micros now) {
    const std::size_t before = sink.frames.size();
    acd.Poll(now);
    return {sink.frames.begin() + static_cast<std::ptrdiff_t>(before), sink.frames.end()};
  }

  // Runs the EtherNet/IP start-up with every random wait at its minimum (probe wait 0): probes at 0,
  // 200, 400, 600 ms, announcements at 800 ms and 2.8 s.
  void ClaimAddress() {
    acd.Start(kAddress, 0);
    for (const Micros t : {0 * kMs, 200 * kMs, 400 * kMs, 600 * kMs, 800 * kMs, 2800 * kMs}) acd.Poll(t);
    ASSERT_EQ(acd.State(), AcdState::kOngoing);
    sink.frames.clear();
  }
};

TEST_F(AcdFixture, EtherNetIpTimelineFourProbesThenTwoAnnouncements) {
  random.Push(150000);  // probe wait 150 ms of 0..200 ms
  acd.Start(kAddress, 10 * kS);
  EXPECT_EQ(acd.State(), AcdState::kProbing);
  EXPECT_FALSE(acd.AddressUsable());
  EXPECT_EQ(acd.NextDeadline(), 10 * kS + 150 * kMs);
  EXPECT_TRUE(PollAt(10 * kS + 150 * kMs - 1).empty());
  const std::vector<Bytes> probe = {kProbeBytes};
  Micros t = 10 * kS + 150 * kMs;
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(PollAt(t), probe);
    t += 200 * kMs;  // PROBE_MIN = PROBE_MAX = 200 ms; after the 4th, ANNOUNCE_WAIT 200 ms
    EXPECT_EQ(acd.NextDeadline(), t);
    EXPECT_TRUE(PollAt(t - 1).empty());
  }
  EXPECT_EQ(PollAt(t), std::vector<Bytes>{kAnnouncementBytes});
  EXPECT_EQ(acd.State(), AcdState::kAnnouncing);
  EXPECT_TRUE(acd.AddressUsable());
  EXPECT_EQ(acd.NextDeadline(), t + 2 * kS);
  EXPECT_EQ(PollAt(t + 2 * kS), std::vector<Bytes>{kAnnouncementBytes});
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
  // Ongoing probe 90 s (random minimum) after the last announcement.
  EXPECT_EQ(acd.NextDeadline(), t + 2 * kS + 90 * kS);
  random.Push(60 * 1000 * 1000);  // the next one 90 + 60 = 150 s later
  EXPECT_EQ(PollAt(t + 92 * kS), std::vector<Bytes>{kProbeBytes});
  EXPECT_EQ(acd.NextDeadline(), t + 92 * kS + 150 * kS);
  EXPECT_FALSE(acd.DuplicateDetected());
}

TEST(AcdRfcTimingsTest, ThreeProbesOneToTwoSecondsApartThenAnnounceWait) {
  QueuedRandom random;
  RecordingSink sink;
  Acd acd(kOwnMac, kRfc5227Timings, random, sink);
  random.Push(1000000);  // probe wait: the whole PROBE_WAIT, 1 s
  random.Push(0);        // 1 s to the 2nd probe
  random.Push(1000000);  // 2 s to the 3rd
  acd.Start(kAddress, 0);
  const std::vector<Micros> expected_deadlines = {1 * kS, 2 * kS, 4 * kS, 6 * kS, 8 * kS};
  EXPECT_EQ(acd.NextDeadline(), 1 * kS);
  for (std::size_t i = 0; i < 3; ++i) {
    acd.Poll(expected_deadlines[i]);
    EXPECT_EQ(acd.NextDeadline(), expected_deadlines[i + 1]) << i;
  }
  EXPECT_EQ(sink.frames, (std::vector<Bytes>{kProbeBytes, kProbeBytes, kProbeBytes}));
  acd.Poll(6 * kS);  // ANNOUNCE_WAIT 2 s after the 3rd probe
  EXPECT_EQ(acd.State(), AcdState::kAnnouncing);
  acd.Poll(8 * kS);
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
  EXPECT_EQ(sink.frames.size(), 5U);
  EXPECT_EQ(sink.frames[4], kAnnouncementBytes);
  EXPECT_EQ(acd.NextDeadline(), hal::kNever);  // RFC 5227: passive from here on
}

TEST_F(AcdFixture, ALatePollSendsOneFrameAndSchedulesFromNow) {
  acd.Start(kAddress, 0);
  EXPECT_EQ(PollAt(5 * kS).size(), 1U);
  EXPECT_EQ(acd.NextDeadline(), 5 * kS + 200 * kMs);
}

TEST_F(AcdFixture, ConflictWhileProbingTheAddressIsNotTaken) {
  acd.Start(kAddress, 0);
  acd.Poll(0);
  acd.Poll(200 * kMs);  // two probes out
  EXPECT_EQ(acd.OnFrame(kConflictingReply, 300 * kMs), AcdEvent::kProbeConflict);
  EXPECT_EQ(acd.State(), AcdState::kConflict);
  EXPECT_FALSE(acd.AddressUsable());
  EXPECT_TRUE(acd.DuplicateDetected());
  // Nothing more is sent, and never an announcement, until the retry 60 s later.
  EXPECT_EQ(acd.NextDeadline(), 60 * kS + 300 * kMs);
  for (Micros t = 300 * kMs; t < 60 * kS + 300 * kMs; t += 100 * kMs) EXPECT_TRUE(PollAt(t).empty()) << t;
  EXPECT_EQ(sink.frames, (std::vector<Bytes>{kProbeBytes, kProbeBytes}));
  // Attribute 11: activity 1, the replying MAC, its ARP PDU as received (without the padding).
  const AcdConflictRecord& record = acd.LastConflict();
  EXPECT_EQ(record.activity, AcdActivity::kProbeIpv4Address);
  EXPECT_EQ(record.remote_mac, kOtherMac);
  EXPECT_EQ(Bytes(record.arp_pdu.begin(), record.arp_pdu.end()),
            Bytes(kConflictingReply.begin() + 14, kConflictingReply.begin() + 42));
}

TEST_F(AcdFixture, AnotherHostProbingForTheSameAddressIsAConflict) {
  acd.Start(kAddress, 0);
  EXPECT_EQ(acd.OnFrame(Frame(ArpProbe(kOtherMac, kOtherAddress)), 1), AcdEvent::kNone);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kOtherAddress), 2), AcdEvent::kNone);
  EXPECT_EQ(acd.State(), AcdState::kProbing);
  EXPECT_EQ(acd.OnFrame(Frame(ArpProbe(kOtherMac, kAddress)), 3), AcdEvent::kProbeConflict);
  EXPECT_EQ(acd.LastConflict().activity, AcdActivity::kProbeIpv4Address);
}

TEST_F(AcdFixture, AnArpReplyAsProbeIsNotASimultaneousProbe) {
  acd.Start(kAddress, 0);
  ArpPacket odd = ArpProbe(kOtherMac, kAddress);
  odd.operation = ArpOperation::kReply;  // sender IP 0 in a reply: not an ARP probe (RFC 5227 §1.1)
  EXPECT_EQ(acd.OnFrame(Frame(odd), 1), AcdEvent::kNone);
}

TEST_F(AcdFixture, OwnFramesAndNonArpFramesAreIgnored) {
  ClaimAddress();
  EXPECT_EQ(acd.OnFrame(kAnnouncementBytes, 3 * kS), AcdEvent::kNone);  // our own, reflected
  EXPECT_EQ(acd.OnFrame(kProbeBytes, 3 * kS), AcdEvent::kNone);
  Bytes ipv4 = kConflictingReply;
  ipv4[13] = 0x00;  // EtherType 0x0800
  EXPECT_EQ(acd.OnFrame(ipv4, 3 * kS), AcdEvent::kNone);
  EXPECT_EQ(acd.OnFrame(std::span(kConflictingReply).first(41), 3 * kS), AcdEvent::kNone);
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
  EXPECT_TRUE(sink.frames.empty());
  EXPECT_EQ(acd.LastConflict(), AcdConflictRecord{});
}

TEST_F(AcdFixture, InUseAProbeFromAnotherHostIsLeftToLwip) {
  ClaimAddress();
  EXPECT_EQ(acd.OnFrame(Frame(ArpProbe(kOtherMac, kAddress)), 3 * kS), AcdEvent::kNone);
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
}

TEST_F(AcdFixture, InUseDefendOnceThenYieldOnASecondConflictWithinTenSeconds) {
  ClaimAddress();
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 20 * kS), AcdEvent::kDefended);
  EXPECT_EQ(sink.frames, std::vector<Bytes>{kAnnouncementBytes});
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
  EXPECT_TRUE(acd.AddressUsable());
  EXPECT_FALSE(acd.DuplicateDetected());
  EXPECT_EQ(acd.LastConflict().activity, AcdActivity::kOngoingDetection);
  EXPECT_EQ(acd.OnFrame(kConflictingReply, 30 * kS - 1), AcdEvent::kYielded);
  EXPECT_EQ(acd.State(), AcdState::kConflict);
  EXPECT_FALSE(acd.AddressUsable());
  EXPECT_TRUE(acd.DuplicateDetected());
  EXPECT_EQ(sink.frames.size(), 1U);  // no second defence
  // Attribute 11 has the second conflict: activity 2, its MAC and PDU.
  std::array<std::uint8_t, kLastConflictDetectedSize> encoded{};
  EncodeLastConflictDetected(acd.LastConflict(), encoded);
  Bytes expected = {0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x99};
  expected.insert(expected.end(), kConflictingReply.begin() + 14, kConflictingReply.begin() + 42);
  EXPECT_EQ(Bytes(encoded.begin(), encoded.end()), expected);
}

TEST_F(AcdFixture, ClaimAnnouncesAtOnceWithoutProbingThenDefends) {
  acd.Start(kOtherAddress, 0);  // an earlier transaction: Claim replaces it
  acd.Claim(kAddress, 5 * kS);
  EXPECT_EQ(acd.State(), AcdState::kAnnouncing);
  EXPECT_TRUE(acd.AddressUsable());
  EXPECT_EQ(acd.NextDeadline(), 5 * kS);
  EXPECT_EQ(PollAt(5 * kS), std::vector<Bytes>{kAnnouncementBytes});
  EXPECT_EQ(acd.NextDeadline(), 7 * kS);
  EXPECT_EQ(PollAt(7 * kS), std::vector<Bytes>{kAnnouncementBytes});
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 8 * kS), AcdEvent::kDefended);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 9 * kS), AcdEvent::kYielded);
  EXPECT_TRUE(acd.DuplicateDetected());
}

TEST_F(AcdFixture, ConflictsMoreThanTenSecondsApartAreEachDefended) {
  ClaimAddress();
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 20 * kS), AcdEvent::kDefended);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 30 * kS), AcdEvent::kDefended);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 40 * kS), AcdEvent::kDefended);
  EXPECT_EQ(sink.frames.size(), 3U);
  EXPECT_EQ(acd.State(), AcdState::kOngoing);
}

TEST_F(AcdFixture, AConflictWhileAnnouncingIsDefendedToo) {
  acd.Start(kAddress, 0);
  for (const Micros t : {0 * kMs, 200 * kMs, 400 * kMs, 600 * kMs, 800 * kMs}) acd.Poll(t);
  ASSERT_EQ(acd.State(), AcdState::kAnnouncing);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 900 * kMs), AcdEvent::kDefended);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 1000 * kMs), AcdEvent::kYielded);
}

TEST_F(AcdFixture, RetryAfterAConflictClaimsTheAddressOnceTheOtherHostIsGone) {
  ClaimAddress();
  ASSERT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 20 * kS), AcdEvent::kDefended);
  ASSERT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 21 * kS), AcdEvent::kYielded);
  sink.frames.clear();
  EXPECT_EQ(acd.NextDeadline(), 81 * kS);
  acd.Poll(81 * kS);  // probing again, still "duplicate" until the address is claimed
  EXPECT_EQ(acd.State(), AcdState::kProbing);
  EXPECT_TRUE(acd.DuplicateDetected());
  for (const Micros t : {81 * kS, 81 * kS + 200 * kMs, 81 * kS + 400 * kMs, 81 * kS + 600 * kMs}) acd.Poll(t);
  EXPECT_TRUE(acd.DuplicateDetected());
  acd.Poll(81 * kS + 800 * kMs);
  EXPECT_EQ(acd.State(), AcdState::kAnnouncing);
  EXPECT_FALSE(acd.DuplicateDetected());
  EXPECT_EQ(sink.frames,
            (std::vector<Bytes>{kProbeBytes, kProbeBytes, kProbeBytes, kProbeBytes, kAnnouncementBytes}));
  // The record of the last conflict stays until a client clears it.
  EXPECT_EQ(acd.LastConflict().activity, AcdActivity::kOngoingDetection);
  acd.ClearLastConflict();
  EXPECT_EQ(acd.LastConflict(), AcdConflictRecord{});
}

TEST_F(AcdFixture, LinkUpWhileInUseSendsTwoSemiActiveProbes) {
  ClaimAddress();
  acd.LinkUp(10 * kS);
  EXPECT_EQ(acd.NextDeadline(), 10 * kS + 200 * kMs);
  EXPECT_EQ(PollAt(10 * kS + 200 * kMs), std::vector<Bytes>{kProbeBytes});
  EXPECT_EQ(PollAt(10 * kS + 400 * kMs), std::vector<Bytes>{kProbeBytes});
  // An answer within the burst's window is a semi-active conflict (and is defended).
  EXPECT_EQ(acd.OnFrame(kConflictingReply, 10 * kS + 450 * kMs), AcdEvent::kDefended);
  EXPECT_EQ(acd.LastConflict().activity, AcdActivity::kSemiActiveProbe);
  EXPECT_TRUE(PollAt(10 * kS + 600 * kMs).empty());  // the window ends; regular ongoing probes resume
  EXPECT_EQ(acd.NextDeadline(), 10 * kS + 600 * kMs + 90 * kS);
  EXPECT_EQ(acd.OnFrame(kConflictingReply, 30 * kS), AcdEvent::kDefended);
  EXPECT_EQ(acd.LastConflict().activity, AcdActivity::kOngoingDetection);
}

TEST_F(AcdFixture, LinkUpOutsideOngoingDoesNothing) {
  acd.LinkUp(0);
  EXPECT_EQ(acd.NextDeadline(), hal::kNever);
  acd.Start(kAddress, 0);
  acd.LinkUp(0);
  EXPECT_EQ(acd.NextDeadline(), 0U);  // still the probe wait
  EXPECT_EQ(PollAt(0), std::vector<Bytes>{kProbeBytes});
}

TEST_F(AcdFixture, StopEndsEverything) {
  ClaimAddress();
  acd.Stop();
  EXPECT_EQ(acd.State(), AcdState::kIdle);
  EXPECT_EQ(acd.NextDeadline(), hal::kNever);
  EXPECT_EQ(acd.OnFrame(OtherAnnounces(kAddress), 5 * kS), AcdEvent::kNone);
  EXPECT_TRUE(PollAt(500 * kS).empty());
}

TEST(AcdAttributesTest, LastConflictDetectedRoundTripAndRefusals) {
  AcdConflictRecord record;
  record.activity = AcdActivity::kSemiActiveProbe;
  record.remote_mac = kOtherMac;
  for (std::size_t i = 0; i < record.arp_pdu.size(); ++i) record.arp_pdu[i] = static_cast<std::uint8_t>(i + 1);
  std::array<std::uint8_t, kLastConflictDetectedSize> bytes{};
  EncodeLastConflictDetected(record, bytes);
  EXPECT_EQ(bytes[0], 3);
  EXPECT_EQ(bytes[6], 0x99);
  EXPECT_EQ(bytes[7], 1);
  EXPECT_EQ(bytes[34], 28);
  const base::Result<AcdConflictRecord> decoded = DecodeLastConflictDetected(bytes);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(*decoded, record);
  const std::array<std::uint8_t, kLastConflictDetectedSize> zeros{};
  EXPECT_EQ(DecodeLastConflictDetected(zeros).value(), AcdConflictRecord{});
  EXPECT_EQ(DecodeLastConflictDetected(std::span(bytes).first(34)).status(), base::OutOfRange());
  const Bytes longer(36, 0);
  EXPECT_EQ(DecodeLastConflictDetected(longer).status(), base::OutOfRange());
  bytes[0] = 4;
  EXPECT_EQ(DecodeLastConflictDetected(bytes).status(), base::InvalidArgument());
}

TEST(AcdAttributesTest, SelectAcdIsOneByteZeroOrOne) {
  EXPECT_EQ(EncodeSelectAcd(true), 1);
  EXPECT_EQ(EncodeSelectAcd(false), 0);
  EXPECT_EQ(DecodeSelectAcd(Bytes{1}).value(), true);
  EXPECT_EQ(DecodeSelectAcd(Bytes{0}).value(), false);
  EXPECT_EQ(DecodeSelectAcd(Bytes{2}).status(), base::InvalidArgument());
  EXPECT_EQ(DecodeSelectAcd(Bytes{}).status(), base::OutOfRange());
  EXPECT_EQ(DecodeSelectAcd(Bytes{1, 0}).status(), base::OutOfRange());
}

}  // namespace
}  // namespace net
