// SlirpFramePort against the real libslirp: ARP, host forwards (TCP, UDP, both directions), the
// simulated cable, counters, the bounded ring and the fallback ports. Only loopback addresses are used:
// forwards bind 127.0.0.3 (not the firmware's default 127.0.0.2) on ports derived from the pid, so a
// running firmware or a parallel test process does not collide. Every wait is bounded.
#include "slirp_frame_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host_clock.h"
#include "poll_waiter.h"

namespace hal::host {
namespace {

// A frame in a fixed buffer (GCC's -Wnull-dereference distrusts indexing into a fresh std::vector).
struct Bytes {
  Bytes() = default;
  explicit Bytes(std::size_t n) : size_(n) {}
  std::uint8_t& operator[](std::size_t i) { return bytes_[i]; }
  std::uint8_t operator[](std::size_t i) const { return bytes_[i]; }
  std::size_t size() const { return size_; }
  auto begin() { return bytes_.begin(); }
  auto begin() const { return bytes_.begin(); }
  auto end() const { return bytes_.begin() + static_cast<std::ptrdiff_t>(size_); }

 private:
  std::array<std::uint8_t, kMaxFrameBytes> bytes_{};
  std::size_t size_ = 0;
};

constexpr base::MacAddress kCardMac = {0x02, 0x1c, 0x0e, 0x12, 0x34, 0x56};
constexpr std::array<std::uint8_t, 4> kCardIp = {10, 0, 2, 15};
constexpr std::array<std::uint8_t, 4> kGatewayIp = {10, 0, 2, 2};
// slirp's own MAC: 52:55 followed by the gateway's IPv4 address.
constexpr base::MacAddress kSlirpMac = {0x52, 0x55, 10, 0, 2, 2};
constexpr char kTestHost[] = "127.0.0.3";
constexpr Micros kPumpLimit = 2 * kMicrosPerSecond;

// Eight consecutive ports per process, 40000..55999, different for (almost) every pid.
std::uint16_t BasePort() { return static_cast<std::uint16_t>(40000 + (getpid() % 2000) * 8); }

std::uint16_t Get16(const Bytes& f, std::size_t at) {
  return static_cast<std::uint16_t>((f[at] << 8) | f[at + 1]);
}
void Put16(Bytes& f, std::size_t at, std::uint16_t v) {
  f[at] = static_cast<std::uint8_t>(v >> 8);
  f[at + 1] = static_cast<std::uint8_t>(v);
}
template <std::size_t N>
bool Equal(const Bytes& f, std::size_t at, const std::array<std::uint8_t, N>& expected) {
  return f.size() >= at + N && std::equal(expected.begin(), expected.end(), f.begin() + at);
}
bool Equal(const Bytes& f, std::size_t at, const base::MacAddress& expected) { return Equal(f, at, expected.octets()); }

std::uint16_t Ipv4HeaderChecksum(const Bytes& f, std::size_t at) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < 20; i += 2) sum += Get16(f, at + i);
  while (sum > 0xffff) sum = (sum & 0xffff) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

// 42-byte ARP frame (no padding, as lwIP sends it).
Bytes ArpFrame(std::uint16_t op, const base::MacAddress& eth_dst, const base::MacAddress& sha,
               const std::array<std::uint8_t, 4>& spa, const base::MacAddress& tha,
               const std::array<std::uint8_t, 4>& tpa) {
  Bytes f(42);
  std::copy(eth_dst.begin(), eth_dst.end(), f.begin());
  std::copy(sha.begin(), sha.end(), f.begin() + 6);
  Put16(f, 12, 0x0806);
  Put16(f, 14, 1);       // Ethernet
  Put16(f, 16, 0x0800);  // IPv4
  f[18] = 6;
  f[19] = 4;
  Put16(f, 20, op);
  std::copy(sha.begin(), sha.end(), f.begin() + 22);
  std::copy(spa.begin(), spa.end(), f.begin() + 28);
  std::copy(tha.begin(), tha.end(), f.begin() + 32);
  std::copy(tpa.begin(), tpa.end(), f.begin() + 38);
  return f;
}

// Card -> 10.0.2.2 UDP datagram, UDP checksum 0 (none).
Bytes UdpFromCard(std::uint16_t src_port, std::uint16_t dst_port, const std::string& payload) {
  Bytes f(14 + 20 + 8 + payload.size());
  std::copy(kSlirpMac.begin(), kSlirpMac.end(), f.begin());
  std::copy(kCardMac.begin(), kCardMac.end(), f.begin() + 6);
  Put16(f, 12, 0x0800);
  f[14] = 0x45;
  Put16(f, 16, static_cast<std::uint16_t>(20 + 8 + payload.size()));
  f[22] = 64;  // TTL
  f[23] = 17;  // UDP
  std::copy(kCardIp.begin(), kCardIp.end(), f.begin() + 26);
  std::copy(kGatewayIp.begin(), kGatewayIp.end(), f.begin() + 30);
  Put16(f, 24, Ipv4HeaderChecksum(f, 14));
  Put16(f, 34, src_port);
  Put16(f, 36, dst_port);
  Put16(f, 38, static_cast<std::uint16_t>(8 + payload.size()));
  std::copy(payload.begin(), payload.end(), f.begin() + 42);
  return f;
}

// DHCPDISCOVER from the card (broadcast, no address yet).
Bytes DhcpDiscover() {
  constexpr std::size_t kBootp = 42;
  Bytes f(kBootp + 236 + 4 + 3 + 1);
  std::fill_n(f.begin(), 6, 0xff);
  std::copy(kCardMac.begin(), kCardMac.end(), f.begin() + 6);
  Put16(f, 12, 0x0800);
  f[14] = 0x45;
  Put16(f, 16, static_cast<std::uint16_t>(f.size() - 14));
  f[22] = 64;
  f[23] = 17;
  std::fill_n(f.begin() + 30, 4, 0xff);  // to 255.255.255.255 from 0.0.0.0
  Put16(f, 24, Ipv4HeaderChecksum(f, 14));
  Put16(f, 34, 68);
  Put16(f, 36, 67);
  Put16(f, 38, static_cast<std::uint16_t>(f.size() - 34));
  f[kBootp] = 1;  // BOOTREQUEST
  f[kBootp + 1] = 1;
  f[kBootp + 2] = 6;
  Put16(f, kBootp + 4, 0x1234);
  Put16(f, kBootp + 6, 0x5678);  // xid
  Put16(f, kBootp + 10, 0x8000);  // reply by broadcast
  std::copy(kCardMac.begin(), kCardMac.end(), f.begin() + kBootp + 28);
  const std::array<std::uint8_t, 8> options = {0x63, 0x82, 0x53, 0x63, 53, 1, 1, 255};  // DISCOVER
  std::copy(options.begin(), options.end(), f.begin() + kBootp + 236);
  return f;
}

bool IsUdpToPort(const Bytes& f, std::uint16_t port) {
  if (f.size() < 42 || Get16(f, 12) != 0x0800 || f[23] != 17) return false;
  const std::size_t udp = 14 + static_cast<std::size_t>(f[14] & 0x0f) * 4;
  return f.size() >= udp + 8 && Get16(f, udp + 2) == port;
}

bool IsArpRequestForCard(const Bytes& f) {
  return f.size() >= 42 && Get16(f, 12) == 0x0806 && Get16(f, 20) == 1 && Equal(f, 38, kCardIp);
}

// IPv4 to the card with the given protocol; returns the offset of the transport header.
std::optional<std::size_t> Ipv4ToCard(const Bytes& f, std::uint8_t protocol) {
  if (f.size() < 34 || Get16(f, 12) != 0x0800 || (f[14] >> 4) != 4 || f[23] != protocol) return {};
  if (!Equal(f, 30, kCardIp)) return {};
  const std::size_t transport = 14 + static_cast<std::size_t>(f[14] & 0x0f) * 4;
  if (f.size() < transport + 8) return {};
  return transport;
}

sockaddr_in Loopback(const char* address, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  inet_pton(AF_INET, address, &a.sin_addr);
  return a;
}

// A plain socket, closed at scope exit.
class Socket {
 public:
  explicit Socket(int type) : fd_(socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0)) {}
  ~Socket() {
    if (fd_ >= 0) close(fd_);
  }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  int fd() const { return fd_; }
  bool Bind(const char* address, std::uint16_t port) {
    const sockaddr_in a = Loopback(address, port);
    return bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) == 0;
  }
  std::uint16_t LocalPort() const {
    sockaddr_in a{};
    socklen_t len = sizeof(a);
    getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    return ntohs(a.sin_port);
  }

 private:
  int fd_;
};

class SlirpFramePortTest : public ::testing::Test {
 protected:
  SlirpPortConfig Config(std::vector<ForwardRule> forwards) {
    SlirpPortConfig config;
    config.mac = kCardMac;
    config.host_address = kTestHost;
    config.forwards = std::move(forwards);
    return config;
  }

  std::unique_ptr<SlirpFramePort> Make(const SlirpPortConfig& config) {
    std::string error;
    auto result = SlirpFramePort::Create(config, clock_, &error);
    EXPECT_TRUE(result.ok()) << error;
    return result.ok() ? std::move(result.value()) : nullptr;
  }

  std::optional<Bytes> ReceiveOne(SlirpFramePort& port) {
    std::array<std::uint8_t, kMaxFrameBytes> buffer{};
    const auto frame = port.Receive(buffer);
    if (!frame.ok()) return {};
    EXPECT_EQ(frame->port, PortId::kLeft);
    Bytes bytes(frame->length);
    std::copy_n(buffer.begin(), frame->length, bytes.begin());
    return bytes;
  }

  // Runs the event loop for at most kPumpLimit, answering slirp's ARP requests for the card, until
  // `wanted` accepts a frame (returned) or time runs out (nullopt).
  std::optional<Bytes> PumpUntil(SlirpFramePort& port, const std::function<bool(const Bytes&)>& wanted) {
    PollWaiter waiter(clock_);
    waiter.Register(port);
    const Micros give_up = clock_.NowMicros() + kPumpLimit;
    while (clock_.NowMicros() < give_up) {
      while (auto frame = ReceiveOne(port)) {
        if (IsArpRequestForCard(*frame)) {
          const base::MacAddress asker = {(*frame)[22], (*frame)[23], (*frame)[24],
                                    (*frame)[25], (*frame)[26], (*frame)[27]};
          const std::array<std::uint8_t, 4> asker_ip = {(*frame)[28], (*frame)[29], (*frame)[30],
                                                        (*frame)[31]};
          const Bytes reply = ArpFrame(2, asker, kCardMac, kCardIp, asker, asker_ip);
          EXPECT_TRUE(port.Transmit(PortId::kLeft, reply).ok());
          ++arp_requests_answered_;
          continue;
        }
        if (wanted(*frame)) return frame;
      }
      waiter.WaitUntil(std::min(give_up, clock_.NowMicros() + 20 * kMicrosPerMilli));
    }
    return {};
  }

  HostClock clock_;
  int arp_requests_answered_ = 0;
};

TEST_F(SlirpFramePortTest, AnswersArpForGatewayAtOnce) {
  auto port = Make(Config({}));
  ASSERT_NE(port, nullptr);
  EXPECT_EQ(port->Mac(), kCardMac);
  EXPECT_EQ(port->PortCount(), 1u);

  const Bytes request = ArpFrame(1, {0xff, 0xff, 0xff, 0xff, 0xff, 0xff}, kCardMac, kCardIp, {}, kGatewayIp);
  ASSERT_TRUE(port->Transmit(PortId::kLeft, request).ok());
  // slirp answers from inside slirp_input(): no pumping needed.
  auto reply = ReceiveOne(*port);
  ASSERT_TRUE(reply.has_value());
  const Bytes& f = *reply;
  ASSERT_GE(f.size(), 42u);
  EXPECT_TRUE(Equal(f, 0, kCardMac));    // Ethernet destination
  EXPECT_TRUE(Equal(f, 6, kSlirpMac));   // Ethernet source
  EXPECT_EQ(Get16(f, 12), 0x0806);
  EXPECT_EQ(Get16(f, 14), 1);
  EXPECT_EQ(Get16(f, 16), 0x0800);
  EXPECT_EQ(f[18], 6);
  EXPECT_EQ(f[19], 4);
  EXPECT_EQ(Get16(f, 20), 2);  // reply
  EXPECT_TRUE(Equal(f, 22, kSlirpMac));
  EXPECT_TRUE(Equal(f, 28, kGatewayIp));
  EXPECT_TRUE(Equal(f, 32, kCardMac));
  EXPECT_TRUE(Equal(f, 38, kCardIp));
  EXPECT_FALSE(ReceiveOne(*port).has_value());

  const PortCounters c = port->Counters(PortId::kLeft);
  EXPECT_EQ(c.tx_frames, 1u);
  EXPECT_EQ(c.tx_octets, 42u);
  EXPECT_EQ(c.rx_frames, 1u);
  EXPECT_EQ(c.rx_octets, f.size());
  EXPECT_EQ(c.rx_errors, 0u);
  EXPECT_EQ(c.tx_errors, 0u);
}

TEST_F(SlirpFramePortTest, HostTcpConnectBecomesSynToCard) {
  const std::uint16_t host_port = BasePort();
  auto port = Make(Config({{Transport::kTcp, 502, host_port, 0}}));
  ASSERT_NE(port, nullptr);
  ASSERT_EQ(port->ActiveForwards().size(), 1u);
  EXPECT_EQ(FormatForward(port->ActiveForwards()[0]),
            "TCP 127.0.0.3:" + std::to_string(host_port) + " -> 10.0.2.15:502");

  // Any 127.x.y.z source is shown to the card as 10.0.2.2 for TCP.
  Socket client(SOCK_STREAM);
  ASSERT_TRUE(client.Bind("127.0.0.5", 0)) << std::strerror(errno);
  const sockaddr_in target = Loopback(kTestHost, host_port);
  const int rc = connect(client.fd(), reinterpret_cast<const sockaddr*>(&target), sizeof(target));
  ASSERT_TRUE(rc == 0 || errno == EINPROGRESS) << std::strerror(errno);

  auto syn = PumpUntil(*port, [](const Bytes& f) { return Ipv4ToCard(f, 6).has_value(); });
  ASSERT_TRUE(syn.has_value()) << "no TCP frame reached the card";
  const Bytes& f = *syn;
  const std::size_t tcp = *Ipv4ToCard(f, 6);
  EXPECT_TRUE(Equal(f, 0, kCardMac));
  EXPECT_TRUE(Equal(f, 26, kGatewayIp));  // from 127.0.0.5 -> seen as 10.0.2.2
  EXPECT_EQ(Get16(f, tcp), client.LocalPort());
  EXPECT_EQ(Get16(f, tcp + 2), 502);      // destination port
  EXPECT_EQ(arp_requests_answered_, 1) << "slirp asks for the card's MAC before its first frame";
  const std::uint8_t flags = f[tcp + 13];
  EXPECT_EQ(flags & 0x02, 0x02);  // SYN
  EXPECT_EQ(flags & 0x10, 0x00);  // no ACK
}

TEST_F(SlirpFramePortTest, UdpForwardBothDirections) {
  const std::uint16_t forward_port = static_cast<std::uint16_t>(BasePort() + 1);
  const std::uint16_t scanner_port = static_cast<std::uint16_t>(BasePort() + 2);
  auto port = Make(Config({{Transport::kUdp, 2222, forward_port, 0}}));
  ASSERT_NE(port, nullptr);

  // The "scanner" binds its own port on 127.0.0.1, as a PLC simulator binds 127.0.0.1:2222.
  Socket scanner(SOCK_DGRAM);
  ASSERT_TRUE(scanner.Bind("127.0.0.1", scanner_port)) << std::strerror(errno);

  // O->T: host -> forward -> card.
  const std::string o_to_t = "O->T data \x01\x02\x03";
  const sockaddr_in forward = Loopback(kTestHost, forward_port);
  ASSERT_EQ(sendto(scanner.fd(), o_to_t.data(), o_to_t.size(), 0, reinterpret_cast<const sockaddr*>(&forward),
                   sizeof(forward)),
            static_cast<ssize_t>(o_to_t.size()));
  auto datagram = PumpUntil(*port, [](const Bytes& f) { return Ipv4ToCard(f, 17).has_value(); });
  ASSERT_TRUE(datagram.has_value()) << "no UDP frame reached the card";
  const Bytes& f = *datagram;
  const std::size_t udp = *Ipv4ToCard(f, 17);
  EXPECT_TRUE(Equal(f, 26, kGatewayIp));  // from 127.0.0.1 -> seen as 10.0.2.2
  EXPECT_EQ(Get16(f, udp), scanner_port);
  EXPECT_EQ(Get16(f, udp + 2), 2222);
  EXPECT_EQ(Get16(f, udp + 4), 8 + o_to_t.size());
  EXPECT_EQ(std::string(f.begin() + static_cast<std::ptrdiff_t>(udp + 8), f.end()).substr(0, o_to_t.size()),
            o_to_t);

  // T->O: card (from the forwarded port 2222) -> 10.0.2.2:scanner_port -> 127.0.0.1:scanner_port,
  // sent through the forward's socket, so it comes from 127.0.0.3:forward_port.
  const std::string t_to_o = "T->O data";
  ASSERT_TRUE(port->Transmit(PortId::kLeft, UdpFromCard(2222, scanner_port, t_to_o)).ok());
  pollfd pfd{scanner.fd(), POLLIN, 0};
  ASSERT_EQ(poll(&pfd, 1, 2000), 1);
  std::array<char, 256> buffer{};
  sockaddr_in from{};
  socklen_t from_len = sizeof(from);
  const ssize_t n =
      recvfrom(scanner.fd(), buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_len);
  ASSERT_EQ(n, static_cast<ssize_t>(t_to_o.size()));
  EXPECT_EQ(std::string(buffer.data(), static_cast<std::size_t>(n)), t_to_o);
  char from_text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &from.sin_addr, from_text, sizeof(from_text));
  EXPECT_STREQ(from_text, kTestHost);
  EXPECT_EQ(ntohs(from.sin_port), forward_port);

  // From a port that is not forwarded, slirp uses a fresh socket: the host sees 127.0.0.1:<ephemeral>.
  ASSERT_TRUE(port->Transmit(PortId::kLeft, UdpFromCard(50000, scanner_port, "other")).ok());
  ASSERT_EQ(poll(&pfd, 1, 2000), 1);
  from_len = sizeof(from);
  ASSERT_EQ(recvfrom(scanner.fd(), buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from),
                     &from_len),
            5);
  inet_ntop(AF_INET, &from.sin_addr, from_text, sizeof(from_text));
  EXPECT_STREQ(from_text, "127.0.0.1");
  EXPECT_NE(ntohs(from.sin_port), forward_port);

  // A datagram from another loopback address keeps its source address.
  Socket other(SOCK_DGRAM);
  ASSERT_TRUE(other.Bind("127.0.0.5", 0)) << std::strerror(errno);
  ASSERT_EQ(sendto(other.fd(), "x", 1, 0, reinterpret_cast<const sockaddr*>(&forward), sizeof(forward)), 1);
  auto from_other = PumpUntil(*port, [](const Bytes& g) { return Ipv4ToCard(g, 17).has_value(); });
  ASSERT_TRUE(from_other.has_value());
  EXPECT_TRUE(Equal(*from_other, 26, std::array<std::uint8_t, 4>{127, 0, 0, 5}));
  EXPECT_EQ(Get16(*from_other, *Ipv4ToCard(*from_other, 17)), other.LocalPort());
}

TEST_F(SlirpFramePortTest, DhcpServerOffersTheCardAddress) {
  auto port = Make(Config({}));
  ASSERT_NE(port, nullptr);
  ASSERT_TRUE(port->Transmit(PortId::kLeft, DhcpDiscover()).ok());
  auto offer = PumpUntil(*port, [](const Bytes& f) { return IsUdpToPort(f, 68); });
  ASSERT_TRUE(offer.has_value()) << "no DHCPOFFER";
  const Bytes& f = *offer;
  const std::size_t bootp = 14 + static_cast<std::size_t>(f[14] & 0x0f) * 4 + 8;
  ASSERT_GE(f.size(), bootp + 240);
  EXPECT_TRUE(Equal(f, 26, kGatewayIp));
  EXPECT_EQ(f[bootp], 2);                     // BOOTREPLY
  EXPECT_EQ(Get16(f, bootp + 4), 0x1234);     // xid
  EXPECT_TRUE(Equal(f, bootp + 16, kCardIp));  // yiaddr: the forwarded address

  SlirpPortConfig config = Config({});
  config.dhcp_server = false;
  auto silent = Make(config);
  ASSERT_NE(silent, nullptr);
  ASSERT_TRUE(silent->Transmit(PortId::kLeft, DhcpDiscover()).ok());
  PollSet set;
  Micros deadline = kNever;
  silent->PrepareWait(set, deadline);
  silent->AfterWait(set);
  EXPECT_FALSE(ReceiveOne(*silent).has_value());
}

TEST_F(SlirpFramePortTest, UnpluggedDropsBothWays) {
  auto port = Make(Config({}));
  ASSERT_NE(port, nullptr);
  const LinkState up = port->Link(PortId::kLeft);
  EXPECT_TRUE(up.up);
  EXPECT_EQ(up.speed, LinkSpeed::k100Mbps);
  EXPECT_TRUE(up.full_duplex);
  EXPECT_TRUE(port->Plugged(PortId::kLeft));

  const Bytes request = ArpFrame(1, {0xff, 0xff, 0xff, 0xff, 0xff, 0xff}, kCardMac, kCardIp, {}, kGatewayIp);
  ASSERT_TRUE(port->Transmit(PortId::kLeft, request).ok());  // reply waits in the ring
  ASSERT_TRUE(port->SetPlugged(PortId::kLeft, false).ok());
  EXPECT_FALSE(port->Plugged(PortId::kLeft));
  const LinkState down = port->Link(PortId::kLeft);
  EXPECT_FALSE(down.up);
  EXPECT_EQ(down.speed, LinkSpeed::kNone);
  EXPECT_FALSE(ReceiveOne(*port).has_value()) << "waiting frames are lost with the cable";
  EXPECT_EQ(port->Transmit(PortId::kLeft, request).code(), base::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(ReceiveOne(*port).has_value());

  ASSERT_TRUE(port->SetPlugged(PortId::kLeft, true).ok());
  EXPECT_TRUE(port->Link(PortId::kLeft).up);
  ASSERT_TRUE(port->Transmit(PortId::kLeft, request).ok());
  EXPECT_TRUE(ReceiveOne(*port).has_value());

  const PortCounters c = port->Counters(PortId::kLeft);
  EXPECT_EQ(c.tx_frames, 2u);
  EXPECT_EQ(c.tx_octets, 84u);
  EXPECT_EQ(c.tx_errors, 1u);
  EXPECT_EQ(c.rx_frames, 1u);
  EXPECT_EQ(c.rx_errors, 0u);

  EXPECT_EQ(port->SetPlugged(PortId::kRight, false).code(), base::StatusCode::kNotFound);
  EXPECT_EQ(port->Transmit(PortId::kRight, request).code(), base::StatusCode::kNotFound);
  EXPECT_FALSE(port->Link(PortId::kRight).up);
}

TEST_F(SlirpFramePortTest, BadLengthsAndFullRingAreCounted) {
  SlirpPortConfig config = Config({});
  config.rx_queue_frames = 2;
  auto port = Make(config);
  ASSERT_NE(port, nullptr);
  const Bytes request = ArpFrame(1, {0xff, 0xff, 0xff, 0xff, 0xff, 0xff}, kCardMac, kCardIp, {}, kGatewayIp);

  const std::array<std::uint8_t, kMaxFrameBytes + 1> big{};
  EXPECT_EQ(port->Transmit(PortId::kLeft, std::span(big).first(13)).code(), base::StatusCode::kOutOfRange);
  EXPECT_EQ(port->Transmit(PortId::kLeft, big).code(), base::StatusCode::kOutOfRange);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(port->Transmit(PortId::kLeft, request).ok());
  EXPECT_EQ(port->Counters(PortId::kLeft).rx_errors, 1u);  // third reply: ring full

  std::array<std::uint8_t, 20> small{};
  EXPECT_EQ(port->Receive(small).status().code(), base::StatusCode::kOutOfRange);
  EXPECT_TRUE(ReceiveOne(*port).has_value());
  EXPECT_EQ(port->Receive(small).status().code(), base::StatusCode::kUnavailable);

  const PortCounters c = port->Counters(PortId::kLeft);
  EXPECT_EQ(c.tx_errors, 2u);
  EXPECT_EQ(c.tx_frames, 3u);
  EXPECT_EQ(c.rx_errors, 2u);
  EXPECT_EQ(c.rx_frames, 1u);
}

TEST_F(SlirpFramePortTest, WaitDeadlines) {
  auto port = Make(Config({}));
  ASSERT_NE(port, nullptr);
  PollSet set;
  Micros deadline = kNever;
  port->PrepareWait(set, deadline);
  // slirp wants to be polled at least once a second.
  EXPECT_LE(deadline, clock_.NowMicros() + kMicrosPerSecond);
  port->AfterWait(set);

  const Bytes request = ArpFrame(1, {0xff, 0xff, 0xff, 0xff, 0xff, 0xff}, kCardMac, kCardIp, {}, kGatewayIp);
  ASSERT_TRUE(port->Transmit(PortId::kLeft, request).ok());
  set.Clear();
  deadline = kNever;
  port->PrepareWait(set, deadline);
  EXPECT_LE(deadline, clock_.NowMicros()) << "a waiting frame must not let the loop sleep";
  port->AfterWait(set);
  // AfterWait() without PrepareWait() is harmless.
  port->AfterWait(set);
}

TEST_F(SlirpFramePortTest, FallsBackWhenPreferredPortIsTaken) {
  const std::uint16_t tcp_taken = static_cast<std::uint16_t>(BasePort() + 3);
  const std::uint16_t tcp_fallback = static_cast<std::uint16_t>(BasePort() + 4);
  const std::uint16_t udp_taken = static_cast<std::uint16_t>(BasePort() + 5);
  const std::uint16_t udp_fallback = static_cast<std::uint16_t>(BasePort() + 6);
  Socket tcp_blocker(SOCK_STREAM);
  ASSERT_TRUE(tcp_blocker.Bind(kTestHost, tcp_taken)) << std::strerror(errno);
  ASSERT_EQ(listen(tcp_blocker.fd(), 1), 0);
  Socket udp_blocker(SOCK_DGRAM);
  ASSERT_TRUE(udp_blocker.Bind(kTestHost, udp_taken)) << std::strerror(errno);

  auto port = Make(Config({{Transport::kTcp, 502, tcp_taken, tcp_fallback},
                           {Transport::kUdp, 2222, udp_taken, udp_fallback}}));
  ASSERT_NE(port, nullptr);
  const auto& forwards = port->ActiveForwards();
  ASSERT_EQ(forwards.size(), 2u);
  EXPECT_EQ(forwards[0].transport, Transport::kTcp);
  EXPECT_EQ(forwards[0].host_address, kTestHost);
  EXPECT_EQ(forwards[0].host_port, tcp_fallback);
  EXPECT_EQ(forwards[0].guest_address, "10.0.2.15");
  EXPECT_EQ(forwards[0].guest_port, 502);
  EXPECT_TRUE(forwards[0].fallback);
  EXPECT_EQ(forwards[1].transport, Transport::kUdp);
  EXPECT_EQ(forwards[1].host_port, udp_fallback);
  EXPECT_EQ(forwards[1].guest_port, 2222);
  EXPECT_TRUE(forwards[1].fallback);

  // The fallback really is bound: a second port cannot take it.
  std::string error;
  auto second =
      SlirpFramePort::Create(Config({{Transport::kUdp, 2222, udp_taken, udp_fallback}}), clock_, &error);
  EXPECT_EQ(second.status().code(), base::StatusCode::kFailedPrecondition);
  EXPECT_EQ(error, "loopback port: UDP 127.0.0.3:" + std::to_string(udp_taken) +
                       " in use, fallback UDP 127.0.0.3:" + std::to_string(udp_fallback) + " in use");
}

TEST_F(SlirpFramePortTest, FailsWithoutFallback) {
  const std::uint16_t taken = static_cast<std::uint16_t>(BasePort() + 7);
  Socket blocker(SOCK_DGRAM);
  ASSERT_TRUE(blocker.Bind(kTestHost, taken)) << std::strerror(errno);
  std::string error;
  auto result = SlirpFramePort::Create(Config({{Transport::kUdp, 2222, taken, 0}}), clock_, &error);
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(error, "loopback port: UDP 127.0.0.3:" + std::to_string(taken) + " in use");
}

TEST_F(SlirpFramePortTest, RejectsBadConfig) {
  std::string error;
  SlirpPortConfig config = Config({});
  config.guest_address = "10.0.3.15";
  EXPECT_EQ(SlirpFramePort::Create(config, clock_, &error).status().code(),
            base::StatusCode::kInvalidArgument);
  EXPECT_NE(error.find("10.0.3.15"), std::string::npos) << error;

  config = Config({});
  config.host_address = "localhost";
  EXPECT_EQ(SlirpFramePort::Create(config, clock_, &error).status().code(),
            base::StatusCode::kInvalidArgument);
  EXPECT_NE(error.find("localhost"), std::string::npos) << error;

  config = Config({{Transport::kTcp, 0, 1234, 0}});
  EXPECT_EQ(SlirpFramePort::Create(config, clock_, &error).status().code(),
            base::StatusCode::kInvalidArgument);
}

TEST(SlirpForwardRules, Defaults) {
  const auto rules = DefaultForwardRules();
  ASSERT_EQ(rules.size(), 5u);
  EXPECT_EQ(rules[0].transport, Transport::kTcp);
  EXPECT_EQ(rules[0].guest_port, 502);
  EXPECT_EQ(rules[0].fallback_host_port, 5020);
  EXPECT_EQ(rules[3].transport, Transport::kUdp);
  EXPECT_EQ(rules[3].host_port, 2222);
  EXPECT_EQ(rules[4].guest_port, 80);
  EXPECT_EQ(rules[4].fallback_host_port, 8080);
  SlirpPortConfig config;
  EXPECT_EQ(config.host_address, "127.0.0.2");
  EXPECT_EQ(config.guest_address, "10.0.2.15");
}

}  // namespace
}  // namespace hal::host
