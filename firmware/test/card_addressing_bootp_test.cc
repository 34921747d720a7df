// CardAddressing with c504 = 1 (BOOTP by MAC) on lwIP and a fake port: the BOOTREQUEST as it leaves the
// card (Ethernet, IPv4, UDP, RFC 951 message), its retransmission, a BOOTREPLY injected as a frame (lwIP
// checks the IP and UDP checksums on the way in), ACD on the leased address, and replies that are not
// ours.
#include <gtest/gtest.h>

#include "card_addressing_harness.h"
#include "net/bootp_client.h"

namespace firmware::test {
namespace {

constexpr base::MacAddress kServerMac = {0x02, 0x00, 0x00, 0x00, 0x00, 0x67};
constexpr std::uint32_t kServerIp = 0xC0A80101;  // 192.168.1.1
constexpr std::uint32_t kLeased = 0xC0A80132;    // 192.168.1.50

// A BOOTREPLY (RFC 951 §3) with vendor options (RFC 1497 cookie, mask, router, end), 300 bytes.
Bytes BootReplyPayload(std::uint32_t xid, const base::MacAddress& chaddr, std::uint32_t yiaddr,
                       std::uint32_t mask, std::uint32_t router) {
  Bytes m;
  m.push_back(2);  // BOOTREPLY
  m.push_back(1);
  m.push_back(6);
  m.push_back(0);
  Put32(m, xid);
  Put16(m, 0);       // secs
  Put16(m, 0x8000);  // broadcast
  Put32(m, 0);       // ciaddr
  Put32(m, yiaddr);
  Put32(m, kServerIp);  // siaddr
  Put32(m, 0);          // giaddr
  PutMac(m, chaddr);
  m.resize(236, 0);  // chaddr padding, sname, file
  const Bytes vend = {0x63, 0x82, 0x53, 0x63, 1, 4};
  m.insert(m.end(), vend.begin(), vend.end());
  Put32(m, mask);
  m.push_back(3);
  m.push_back(4);
  Put32(m, router);
  m.push_back(255);
  m.resize(300, 0);
  return m;
}

Bytes BootReplyFrame(const Bytes& payload, std::uint16_t source_port = 67) {
  return UdpFrameBytes(base::kBroadcastMac, kServerMac, kServerIp, 0xFFFFFFFF, source_port, 68, payload);
}

class BootpAddressingTest : public AddressingHarness {
 protected:
  // Configures BOOTP and returns the first BOOTREQUEST (sent from Configure itself).
  SentUdp ConfigureBootp() {
    start_ = Now();
    EXPECT_TRUE(addressing_.Configure(ModeConfig(config::IpMode::kBootp)).ok());
    Step();
    const auto udp = UdpSince();
    EXPECT_EQ(udp.size(), 1u);
    return udp.empty() ? SentUdp{} : ParseUdp(udp[0].bytes);
  }
  static std::uint32_t Xid(const SentUdp& request) { return request.payload.size() >= 8 ? Get32(request.payload, 4) : 0; }

  Micros start_ = 0;
};

TEST_F(BootpAddressingTest, FirstRequest_ExactFrameFromPort68ToTheLimitedBroadcast) {
  const SentUdp request = ConfigureBootp();
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
  EXPECT_TRUE(addressing_.acquiring());
  EXPECT_EQ(addressing_.counters().bootp_requests, 1u);
  const auto frames = UdpSince();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].at, start_);  // at once
  const Bytes& f = frames[0].bytes;
  ASSERT_EQ(f.size(), 14u + 20u + 8u + 300u);
  EXPECT_EQ(Bytes(f.begin(), f.begin() + 6), Bytes(6, 0xFF));         // Ethernet broadcast
  EXPECT_EQ(Bytes(f.begin() + 6, f.begin() + 12), Bytes(kCardMac.octets().begin(), kCardMac.octets().end()));
  EXPECT_EQ(Get16(f, 16), 328u);  // IP total length
  EXPECT_TRUE(request.ip_checksum_ok);
  EXPECT_EQ(request.src_ip, 0u);
  EXPECT_EQ(request.dst_ip, 0xFFFFFFFFu);
  EXPECT_EQ(request.src_port, 68u);
  EXPECT_EQ(request.dst_port, 67u);
  EXPECT_EQ(Get16(f, 38), 308u);  // UDP length

  // RFC 951 §3, field by field.
  const Bytes& m = request.payload;
  ASSERT_EQ(m.size(), 300u);
  EXPECT_EQ(m[0], 1);  // BOOTREQUEST
  EXPECT_EQ(m[1], 1);  // htype Ethernet
  EXPECT_EQ(m[2], 6);  // hlen
  EXPECT_EQ(m[3], 0);  // hops
  EXPECT_EQ(Get16(m, 8), 0u);        // secs
  EXPECT_EQ(Get16(m, 10), 0x8000u);  // the BROADCAST flag (RFC 1542)
  EXPECT_EQ(Bytes(m.begin() + 12, m.begin() + 28), Bytes(16, 0));  // ciaddr, yiaddr, siaddr, giaddr
  EXPECT_EQ(Bytes(m.begin() + 28, m.begin() + 34), Bytes(kCardMac.octets().begin(), kCardMac.octets().end()));
  EXPECT_EQ(Bytes(m.begin() + 34, m.begin() + 236), Bytes(202, 0));  // chaddr padding, sname, file
  Bytes vend = {0x63, 0x82, 0x53, 0x63, 0xFF};
  vend.resize(64, 0);
  EXPECT_EQ(Bytes(m.begin() + 236, m.end()), vend);

  // And exactly what the BOOTP core encodes for this transaction.
  std::array<std::uint8_t, net::kBootpMessageSize> encoded{};
  net::EncodeBootRequest({.mac = kCardMac, .xid = Xid(request), .secs = 0, .broadcast = true}, encoded);
  EXPECT_EQ(m, Bytes(encoded.begin(), encoded.end()));
}

TEST_F(BootpAddressingTest, NoAnswer_RetransmittedAfterAboutFourSecondsSameXid) {
  const SentUdp first = ConfigureBootp();
  RunUntil(start_ + 2900 * kMs);
  EXPECT_EQ(UdpSince().size(), 1u);
  RunUntil(start_ + 5 * kSec);
  auto frames = UdpSince();
  ASSERT_EQ(frames.size(), 2u);
  const Micros second_at = frames[1].at;
  EXPECT_GE(second_at - start_, 3 * kSec);  // 4 s +- 1 s
  EXPECT_LE(second_at - start_, 5 * kSec);
  const SentUdp second = ParseUdp(frames[1].bytes);
  EXPECT_EQ(Xid(second), Xid(first));
  EXPECT_EQ(Get16(second.payload, 8), static_cast<std::uint16_t>((second_at - start_) / kSec));  // secs
  EXPECT_EQ(second.payload[0], 1);
  // The next one 8 s +- 1 s later.
  RunUntil(second_at + 9 * kSec);
  frames = UdpSince();
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_GE(frames[2].at - second_at, 7 * kSec);
  EXPECT_LE(frames[2].at - second_at, 9 * kSec);
  EXPECT_EQ(addressing_.counters().bootp_requests, 3u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
  EXPECT_EQ(LwipAddress(), 0u);
}

TEST_F(BootpAddressingTest, Reply_AcdProbesTheLeaseThenInstallsItWithMaskAndRouter) {
  const SentUdp request = ConfigureBootp();
  RunFor(1 * kSec);
  Receive(BootReplyFrame(BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFF0000, kServerIp)));
  EXPECT_EQ(addressing_.counters().bootp_replies, 1u);
  EXPECT_EQ(addressing_.counters().bootp_ignored, 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
  EXPECT_FALSE(addressing_.acquiring());
  EXPECT_EQ(LwipAddress(), 0u);  // not before ACD

  const std::size_t mark = sent_.size();
  RunFor(1100 * kMs);
  const auto arp = ArpSince(mark);
  ASSERT_GE(arp.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(arp[i].bytes, CardProbe(kLeased)) << i;
    if (i > 0) {
      EXPECT_EQ(arp[i].at - arp[i - 1].at, 200 * kMs) << i;
    }
  }
  EXPECT_EQ(arp[4].bytes, CardAnnouncement(kLeased));
  EXPECT_EQ(LwipAddress(), kLeased);
  EXPECT_EQ(LwipMask(), 0xFFFF0000u);
  EXPECT_EQ(LwipGateway(), kServerIp);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kInUse);

  // Bound: no more requests (BOOTP has no lease to renew).
  RunFor(130 * kSec);
  EXPECT_EQ(UdpSince().size(), 1u);
  EXPECT_EQ(addressing_.counters().bootp_requests, 1u);
  EXPECT_EQ(LwipAddress(), kLeased);
}

TEST_F(BootpAddressingTest, ReplyWithoutMask_ClassfulMask_RouterOffSubnetDropped) {
  const SentUdp request = ConfigureBootp();
  addressing_.SetAcdEnabled(false);  // applies at the next restart only: this lease is still probed
  Bytes payload = BootReplyPayload(Xid(request), kCardMac, 0x0A000105, 0xFFFFFF00, 0xC0A80101);
  payload[236 + 4] = 0;  // option 1 becomes pad, pad, pad... : no mask, router 192.168.1.1 (off 10/8)
  payload[236 + 5] = 0;
  payload[236 + 6] = 0;
  payload[236 + 7] = 0;
  payload[236 + 8] = 0;
  payload[236 + 9] = 0;
  Receive(BootReplyFrame(payload));
  ASSERT_EQ(addressing_.counters().bootp_replies, 1u);
  RunFor(1100 * kMs);
  EXPECT_EQ(LwipAddress(), 0x0A000105u);
  EXPECT_EQ(LwipMask(), 0xFF000000u);
  EXPECT_EQ(LwipGateway(), 0u);
}

TEST_F(BootpAddressingTest, RepliesForAnotherMacOrXidOrFromAnotherPort_Ignored) {
  const SentUdp request = ConfigureBootp();
  constexpr base::MacAddress kOtherClient = {0x00, 0x80, 0xF4, 0x7D, 0x02, 0xC1};
  Receive(BootReplyFrame(BootReplyPayload(Xid(request), kOtherClient, kLeased, 0xFFFFFF00, kServerIp)));
  Receive(BootReplyFrame(BootReplyPayload(Xid(request) + 1, kCardMac, kLeased, 0xFFFFFF00, kServerIp)));
  Receive(BootReplyFrame(BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFFFF00, kServerIp), 1067));
  Bytes truncated = BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFFFF00, kServerIp);
  truncated.resize(235);
  Receive(BootReplyFrame(truncated));
  EXPECT_EQ(addressing_.counters().bootp_ignored, 4u);
  EXPECT_EQ(addressing_.counters().bootp_replies, 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
  // The transaction goes on: the retransmission still comes, and our answer is still taken.
  RunUntil(start_ + 5 * kSec);
  EXPECT_EQ(UdpSince().size(), 2u);
  Receive(BootReplyFrame(BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFFFF00, kServerIp)));
  EXPECT_EQ(addressing_.counters().bootp_replies, 1u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kProbing);
}

TEST_F(BootpAddressingTest, BadUdpChecksum_DroppedByLwip) {
  const SentUdp request = ConfigureBootp();
  Bytes frame = BootReplyFrame(BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFFFF00, kServerIp));
  frame[40] ^= 0x01;  // UDP checksum
  Receive(frame);
  EXPECT_EQ(addressing_.counters().bootp_replies + addressing_.counters().bootp_ignored, 0u);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
}

TEST_F(BootpAddressingTest, SwitchToManual_StopsBootpAndLateRepliesChangeNothing) {
  const SentUdp request = ConfigureBootp();
  addressing_.SetAcdEnabled(false);
  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
  EXPECT_EQ(LwipAddress(), 0xC0A8010Cu);
  Receive(BootReplyFrame(BootReplyPayload(Xid(request), kCardMac, kLeased, 0xFFFFFF00, kServerIp)));
  RunFor(70 * kSec);
  EXPECT_EQ(UdpSince().size(), 1u);  // no retransmission
  EXPECT_EQ(addressing_.counters().bootp_replies, 0u);
  EXPECT_EQ(LwipAddress(), 0xC0A8010Cu);
}

}  // namespace
}  // namespace firmware::test
