// The BOOTP client and the BOOTP/DHCP options area (net/bootp_client.h, net/dhcp_options.h,
// docs/network.md "BOOTP"): exact request bytes, the retransmission schedule with its jitter and the
// secs field, the checks on a reply, and the bounded option walk with its refusals.
#include <gtest/gtest.h>

#include <vector>

#include "net/bootp_client.h"
#include "net/dhcp_options.h"

#include "queued_random.h"

namespace net {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::Micros;

constexpr Micros kS = hal::kMicrosPerSecond;
constexpr base::MacAddress kMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};  // RFC 7042 documentation MAC
constexpr std::uint32_t kXid = 0x12345678;

using hal::test::QueuedRandom;

// The request the card sends, byte for byte, with the given secs.
Bytes ExpectedRequest(std::uint16_t secs) {
  Bytes bytes = {
      0x01, 0x01, 0x06, 0x00,                          // op BOOTREQUEST, Ethernet, hlen 6, hops 0
      0x12, 0x34, 0x56, 0x78,                          // xid
      static_cast<std::uint8_t>(secs >> 8), static_cast<std::uint8_t>(secs), 0x80, 0x00,  // secs, broadcast
      0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // ciaddr, yiaddr, siaddr, giaddr
      0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,              // chaddr: the MAC, then 10 zero bytes
  };
  bytes.resize(236, 0x00);  // chaddr padding, sname, file
  bytes.insert(bytes.end(), {0x63, 0x82, 0x53, 0x63, 0xFF});  // cookie, end
  bytes.resize(300, 0x00);
  return bytes;
}

// A BOOTREPLY as dnsmasq sends it for a dhcp-host entry: 192.0.2.10/24, router 192.0.2.1, server
// 192.0.2.1, with a host name option before the ones the card uses.
Bytes Reply(const Bytes& options = {0x0C, 0x04, 'c', 'a', 'r', 'd',          // 12 host name (skipped)
                                    0x00,                                    // pad
                                    0x01, 0x04, 0xFF, 0xFF, 0xFF, 0x00,      // 1 subnet mask
                                    0x03, 0x08, 0xC0, 0x00, 0x02, 0x01,      // 3 routers: the first counts
                                    0xC0, 0x00, 0x02, 0x02, 0xFF}) {
  Bytes bytes = {
      0x02, 0x01, 0x06, 0x00, 0x12, 0x34, 0x56, 0x78, 0x00, 0x00, 0x80, 0x00,
      0x00, 0x00, 0x00, 0x00,  // ciaddr
      0xC0, 0x00, 0x02, 0x0A,  // yiaddr 192.0.2.10
      0xC0, 0x00, 0x02, 0x01,  // siaddr 192.0.2.1
      0x00, 0x00, 0x00, 0x00,  // giaddr
      0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
  };
  bytes.resize(236, 0x00);
  bytes.insert(bytes.end(), {0x63, 0x82, 0x53, 0x63});
  bytes.insert(bytes.end(), options.begin(), options.end());
  if (bytes.size() < 300) bytes.resize(300, 0x00);
  return bytes;
}

struct BootpFixture : ::testing::Test {
  QueuedRandom random;
  BootpClient client{kMac, random};
  std::array<std::uint8_t, kBootpMessageSize> out{};

  // Polls at `now`; the request bytes, or empty when nothing was due.
  Bytes PollAt(Micros now) {
    const std::size_t size = client.Poll(now, out);
    return Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(size));
  }

  void StartWithXid(Micros now) {
    random.Push(kXid);
    client.Start(now);
  }
};

TEST(BootpClientTest, RequestBytes) {
  std::array<std::uint8_t, kBootpMessageSize> out{};
  out.fill(0xAA);  // every byte is written
  EncodeBootRequest({.mac = kMac, .xid = kXid, .secs = 0x0102, .broadcast = true}, out);
  EXPECT_EQ(Bytes(out.begin(), out.end()), ExpectedRequest(0x0102));
  EncodeBootRequest({.mac = kMac, .xid = kXid, .secs = 0, .broadcast = false}, out);
  EXPECT_EQ(out[10], 0x00);
  EXPECT_EQ(out[11], 0x00);
}

TEST_F(BootpFixture, RetransmitsAtFourEightSixteenThirtyTwoThenSixtyFourSecondsWithJitter) {
  StartWithXid(0);
  EXPECT_EQ(client.state(), BootpClient::State::kRequesting);
  EXPECT_EQ(client.xid(), kXid);
  EXPECT_EQ(client.NextDeadline(), 0U);
  // Each delay is base - 1 s + (draw mod 2 000 001) µs.
  random.Push(1000000);  // 4 s exactly
  EXPECT_EQ(PollAt(0), ExpectedRequest(0));
  EXPECT_EQ(client.NextDeadline(), 4 * kS);
  EXPECT_TRUE(PollAt(4 * kS - 1).empty());
  random.Push(0);  // 8 - 1 = 7 s
  EXPECT_EQ(PollAt(4 * kS), ExpectedRequest(4));
  EXPECT_EQ(client.NextDeadline(), 11 * kS);
  random.Push(2000000);  // 16 + 1 = 17 s
  EXPECT_EQ(PollAt(11 * kS), ExpectedRequest(11));
  EXPECT_EQ(client.NextDeadline(), 28 * kS);
  random.Push(1000000);  // 32 s
  EXPECT_EQ(PollAt(28 * kS + 500000), ExpectedRequest(28));  // secs counts whole seconds
  EXPECT_EQ(client.NextDeadline(), 60 * kS + 500000);
  for (int i = 0; i < 3; ++i) {  // 64 s from now on
    const Micros t = client.NextDeadline();
    random.Push(1000000);
    EXPECT_EQ(PollAt(t).size(), kBootpMessageSize);
    EXPECT_EQ(client.NextDeadline(), t + 64 * kS) << i;
  }
  EXPECT_EQ(client.transmissions(), 7U);
}

TEST_F(BootpFixture, NothingIsSentWhenIdleOrBound) {
  EXPECT_TRUE(PollAt(0).empty());
  EXPECT_EQ(client.NextDeadline(), hal::kNever);
  StartWithXid(0);
  ASSERT_FALSE(PollAt(0).empty());
  ASSERT_TRUE(client.OnReply(Reply()).ok());
  EXPECT_TRUE(PollAt(100 * kS).empty());
  EXPECT_EQ(client.NextDeadline(), hal::kNever);
}

TEST_F(BootpFixture, SecsSaturates) {
  StartWithXid(0);
  const Bytes request = PollAt(70000 * kS);
  ASSERT_EQ(request.size(), kBootpMessageSize);
  EXPECT_EQ(request[8], 0xFF);
  EXPECT_EQ(request[9], 0xFF);
}

TEST_F(BootpFixture, ReplyGivesAddressMaskAndFirstRouter) {
  StartWithXid(5 * kS);
  ASSERT_FALSE(PollAt(5 * kS).empty());
  EXPECT_EQ(client.OnReply(Reply()), base::OkStatus());
  EXPECT_EQ(client.state(), BootpClient::State::kBound);
  const BootReply& lease = client.Lease();
  EXPECT_EQ(lease.your_address, base::Ipv4Address(0xC000020AU));
  EXPECT_EQ(lease.server_address, base::Ipv4Address(0xC0000201U));
  EXPECT_EQ(lease.subnet_mask, std::optional<base::Ipv4Address>(0xFFFFFF00U));
  EXPECT_EQ(lease.router, std::optional<base::Ipv4Address>(0xC0000201U));
  // A second answer (a second server) no longer counts.
  EXPECT_EQ(client.OnReply(Reply()), base::FailedPrecondition());
}

TEST_F(BootpFixture, RepliesNotForUsAreIgnoredAndTheTransactionGoesOn) {
  StartWithXid(0);
  ASSERT_FALSE(PollAt(0).empty());
  auto status_of = [&](std::size_t offset, std::uint8_t value) {
    Bytes reply = Reply();
    reply[offset] = value;
    return client.OnReply(reply);
  };
  EXPECT_EQ(status_of(7, 0x79), base::NotFound());         // xid 0x12345679
  EXPECT_EQ(status_of(33, 0x02), base::NotFound());        // chaddr ...:53:02
  EXPECT_EQ(status_of(0, 0x01), base::InvalidArgument());  // a BOOTREQUEST (another client's)
  EXPECT_EQ(status_of(1, 0x06), base::InvalidArgument());  // htype IEEE 802
  EXPECT_EQ(status_of(2, 0x10), base::InvalidArgument());  // hlen 16
  EXPECT_EQ(status_of(16, 0x00), base::InvalidArgument());  // yiaddr 0.0.2.10
  EXPECT_EQ(status_of(16, 0x7F), base::InvalidArgument());  // 127.0.2.10
  EXPECT_EQ(status_of(16, 0xE0), base::InvalidArgument());  // 224.0.2.10 multicast
  EXPECT_EQ(status_of(16, 0xFF), base::InvalidArgument());  // 255.0.2.10
  EXPECT_EQ(status_of(251, 0x0F), base::InvalidArgument());  // mask 255.255.15.0: not contiguous
  EXPECT_EQ(client.state(), BootpClient::State::kRequesting);
  EXPECT_EQ(client.OnReply(Reply()), base::OkStatus());
}

TEST_F(BootpFixture, EveryTruncationOfTheFixedPartIsOutOfRange) {
  StartWithXid(0);
  const Bytes reply = Reply();
  for (std::size_t size = 0; size < kBootpFixedSize; ++size) {
    EXPECT_EQ(client.OnReply(std::span(reply).first(size)), base::OutOfRange()) << size;
  }
  EXPECT_EQ(client.state(), BootpClient::State::kRequesting);
}

TEST_F(BootpFixture, AReplyWithoutVendorInformationGivesTheAddressOnly) {
  StartWithXid(0);
  const Bytes reply = Reply();
  // Only the fixed part; then a vendor area in some other format (no cookie).
  const base::Result<BootReply> bare = ParseBootReply(std::span(reply).first(kBootpFixedSize), kXid, kMac);
  ASSERT_TRUE(bare.ok());
  EXPECT_EQ(bare->your_address, base::Ipv4Address(0xC000020AU));
  EXPECT_FALSE(bare->subnet_mask.has_value());
  EXPECT_FALSE(bare->router.has_value());
  Bytes other = reply;
  other[kBootpFixedSize] = 0x00;
  EXPECT_TRUE(client.OnReply(other).ok());
  EXPECT_FALSE(client.Lease().subnet_mask.has_value());
}

TEST_F(BootpFixture, TruncatedOrMalformedOptionsRefuseTheReply) {
  StartWithXid(0);
  // The options area ends inside the router option (no zero padding after it).
  Bytes cut = Reply({0x01, 0x04, 0xFF, 0xFF, 0xFF, 0x00, 0x03, 0x04, 0xC0, 0x00});
  cut.resize(kBootpFixedSize + 4 + 10);
  EXPECT_EQ(client.OnReply(cut), base::DataLoss());
  EXPECT_EQ(client.OnReply(Reply({0x01, 0x03, 0xFF, 0xFF, 0xFF, 0xFF})), base::InvalidArgument());
  EXPECT_EQ(client.OnReply(Reply({0x03, 0x06, 1, 2, 3, 4, 5, 6, 0xFF})), base::InvalidArgument());
  EXPECT_EQ(client.state(), BootpClient::State::kRequesting);
}

TEST_F(BootpFixture, ALongerReplyFromADhcpServerIsRead) {
  StartWithXid(0);
  Bytes options = {0x35, 0x01, 0x05};  // a DHCP message type: not ours to interpret, skipped
  options.resize(250, 0x00);           // padding: a 497-byte message, as DHCP servers send
  options.insert(options.end(), {0x01, 0x04, 0xFF, 0xFF, 0x00, 0x00, 0xFF});
  const Bytes reply = Reply(options);
  EXPECT_GT(reply.size(), 300U);
  ASSERT_TRUE(client.OnReply(reply).ok());
  EXPECT_EQ(client.Lease().subnet_mask, std::optional<base::Ipv4Address>(0xFFFF0000U));
}

TEST_F(BootpFixture, StopIgnoresALateReply) {
  StartWithXid(0);
  ASSERT_FALSE(PollAt(0).empty());
  client.Stop();
  EXPECT_EQ(client.OnReply(Reply()), base::FailedPrecondition());
  EXPECT_TRUE(PollAt(10 * kS).empty());
}

TEST(BootpClientTest, AddressAndMaskChecks) {
  EXPECT_TRUE(IsUsableUnicast(base::Ipv4Address(0x0A000001)));   // 10.0.0.1
  EXPECT_TRUE(IsUsableUnicast(base::Ipv4Address(0xDFFFFFFE)));   // 223.255.255.254
  EXPECT_FALSE(IsUsableUnicast(base::Ipv4Address(0x00000000)));
  EXPECT_FALSE(IsUsableUnicast(base::Ipv4Address(0x7F000001)));
  EXPECT_FALSE(IsUsableUnicast(base::Ipv4Address(0xE0000001)));
  EXPECT_FALSE(IsUsableUnicast(base::Ipv4Address(0xFFFFFFFF)));
  EXPECT_TRUE(IsContiguousMask(base::Ipv4Address(0xFFFFFF00)));
  EXPECT_TRUE(IsContiguousMask(base::Ipv4Address(0xFFFFFFFF)));
  EXPECT_TRUE(IsContiguousMask(base::Ipv4Address(0x80000000)));
  EXPECT_FALSE(IsContiguousMask(base::Ipv4Address(0x00000000)));
  EXPECT_FALSE(IsContiguousMask(base::Ipv4Address(0xFFFF0F00)));
  EXPECT_FALSE(IsContiguousMask(base::Ipv4Address(0x00FFFFFF)));
}

// ---- The options area ---------------------------------------------------------------------------

std::vector<DhcpOption> ReadAll(std::span<const std::uint8_t> area, base::Status& last) {
  DhcpOptionReader reader(area);
  std::vector<DhcpOption> options;
  DhcpOption option;
  while ((last = reader.Next(option)).ok()) options.push_back(option);
  return options;
}

TEST(DhcpOptionsTest, WalksPadsAndOptionsToTheEnd) {
  const Bytes area = {0x00, 0x00, 0x01, 0x04, 0xFF, 0xFF, 0xFF, 0x00, 0x2B, 0x00, 0x00, 0xFF, 0x01, 0x04};
  base::Status last;
  const std::vector<DhcpOption> options = ReadAll(area, last);
  EXPECT_EQ(last, base::NotFound());
  ASSERT_EQ(options.size(), 2U);
  EXPECT_EQ(options[0].code, 1);
  EXPECT_EQ(options[0].data.data(), area.data() + 4);
  EXPECT_EQ(options[0].data.size(), 4U);
  EXPECT_EQ(options[1].code, 43);  // vendor-specific, empty
  EXPECT_TRUE(options[1].data.empty());
  // After the end option nothing is read, not even the bytes that follow it.
}

TEST(DhcpOptionsTest, MissingEndOptionEndsAtTheAreaEnd) {
  const Bytes area = {0x03, 0x04, 0xC0, 0x00, 0x02, 0x01};
  base::Status last;
  EXPECT_EQ(ReadAll(area, last).size(), 1U);
  EXPECT_EQ(last, base::NotFound());
}

TEST(DhcpOptionsTest, TruncationIsDataLossAndSticks) {
  base::Status last;
  EXPECT_TRUE(ReadAll(Bytes{0x01}, last).empty());  // code without length
  EXPECT_EQ(last, base::DataLoss());
  const Bytes short_data = {0x0C, 0x01, 'a', 0x01, 0x04, 0xFF, 0xFF};
  EXPECT_EQ(ReadAll(short_data, last).size(), 1U);
  EXPECT_EQ(last, base::DataLoss());
  DhcpOptionReader reader(short_data);
  DhcpOption option;
  EXPECT_TRUE(reader.Next(option).ok());
  EXPECT_EQ(reader.Next(option), base::DataLoss());
  EXPECT_EQ(reader.Next(option), base::DataLoss());
}

TEST(DhcpOptionsTest, EveryTruncationOfAnAreaEndsCleanly) {
  const Bytes area = {0x0C, 0x04, 'c', 'a', 'r', 'd', 0x01, 0x04, 0xFF, 0xFF, 0xFF, 0x00, 0x03, 0x04,
                      0xC0, 0x00, 0x02, 0x01, 0xFF};
  for (std::size_t size = 0; size <= area.size(); ++size) {
    const base::Result<IpOptions> parsed = ParseIpOptions(std::span(area).first(size));
    // A cut on an option boundary is a list without an end option; any other cut is truncation.
    const bool on_boundary = size == 0 || size == 6 || size == 12 || size == 18 || size == 19;
    EXPECT_EQ(parsed.ok(), on_boundary) << size;
    if (!on_boundary) {
      EXPECT_EQ(parsed.status(), base::DataLoss()) << size;
    }
  }
}

TEST(DhcpOptionsTest, FirstInstanceWinsAndLengthsAreChecked) {
  const base::Result<IpOptions> twice =
      ParseIpOptions(Bytes{0x01, 0x04, 0xFF, 0x00, 0x00, 0x00, 0x01, 0x04, 0xFF, 0xFF, 0x00, 0x00, 0xFF});
  ASSERT_TRUE(twice.ok());
  EXPECT_EQ(twice->subnet_mask, std::optional<base::Ipv4Address>(0xFF000000U));
  EXPECT_EQ(ParseIpOptions(Bytes{0x01, 0x05, 0, 0, 0, 0, 0}).status(), base::InvalidArgument());
  EXPECT_EQ(ParseIpOptions(Bytes{0x03, 0x00}).status(), base::InvalidArgument());
  EXPECT_EQ(ParseIpOptions(Bytes{0x03, 0x05, 1, 2, 3, 4, 5}).status(), base::InvalidArgument());
  const base::Result<IpOptions> none = ParseIpOptions(Bytes{0xFF});
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->subnet_mask.has_value());
  EXPECT_FALSE(none->router.has_value());
}

TEST(DhcpOptionsTest, CookieIsRequired) {
  EXPECT_EQ(OptionsAfterCookie(Bytes{0x63, 0x82, 0x53}).status(), base::NotFound());
  EXPECT_EQ(OptionsAfterCookie(Bytes{0x63, 0x82, 0x53, 0x64, 0xFF}).status(), base::NotFound());
  const Bytes area = {0x63, 0x82, 0x53, 0x63, 0xFF};
  const base::Result<std::span<const std::uint8_t>> options = OptionsAfterCookie(area);
  ASSERT_TRUE(options.ok());
  EXPECT_EQ(options->data(), area.data() + 4);
  EXPECT_EQ(options->size(), 1U);
}

TEST(DhcpOptionsTest, WriterBytesAndStickyOverflow) {
  std::array<std::uint8_t, 12> buffer{};
  DhcpOptionWriter writer(buffer);
  writer.Cookie();
  const std::array<std::uint8_t, 4> name = {'c', 'a', 'r', 'd'};
  writer.Option(DhcpOptionCode::kHostName, name);
  writer.End();
  EXPECT_TRUE(writer.status().ok());
  EXPECT_EQ(writer.size(), 11U);
  EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + 11),
            (Bytes{0x63, 0x82, 0x53, 0x63, 0x0C, 0x04, 'c', 'a', 'r', 'd', 0xFF}));
  writer.Option(DhcpOptionCode::kHostName, name);  // 6 more bytes do not fit in 1
  EXPECT_EQ(writer.status(), base::ResourceExhausted());
  writer.End();  // would fit, but the error sticks
  EXPECT_EQ(writer.size(), 11U);
  std::array<std::uint8_t, 300> big{};
  DhcpOptionWriter too_long(big);
  const std::array<std::uint8_t, 256> data{};
  too_long.Option(DhcpOptionCode::kHostName, data);
  EXPECT_EQ(too_long.status(), base::InvalidArgument());
  EXPECT_EQ(too_long.size(), 0U);
}

}  // namespace
}  // namespace net
