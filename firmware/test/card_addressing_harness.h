// A CardAddressing on a CardNetif on a FakeFramePort, driven on lwIP's test clock from deadline to
// deadline like the event loop does (receive, lwIP timers, Poll), with every frame the card sends logged
// with its instant. Frame builders for what other hosts send (ARP, UDP over IPv4), written byte by byte
// here so that the tests do not check the card's encoders against themselves.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "card_addressing.h"
#include "fake_frame_port.h"
#include "lwip/timeouts.h"
#include "lwip_fixture.h"

namespace firmware::test {

using hal::Micros;
inline constexpr Micros kMs = hal::kMicrosPerMilli;
inline constexpr Micros kSec = hal::kMicrosPerSecond;

inline constexpr base::MacAddress kCardMac = {0x00, 0x80, 0xF4, 0x7D, 0x02, 0xC0};
inline constexpr base::MacAddress kOtherMac = {0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};

using Bytes = std::vector<std::uint8_t>;

inline void PutMac(Bytes& out, const base::MacAddress& mac) {
  out.insert(out.end(), mac.octets().begin(), mac.octets().end());
}
inline void Put16(Bytes& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}
inline void Put32(Bytes& out, std::uint32_t v) {
  Put16(out, static_cast<std::uint16_t>(v >> 16));
  Put16(out, static_cast<std::uint16_t>(v));
}
inline std::uint16_t Get16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] << 8 | b[at + 1]);
}
inline std::uint32_t Get32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(Get16(b, at)) << 16 | Get16(b, at + 2);
}

// Ethernet + ARP (RFC 826), 42 bytes.
inline Bytes ArpFrameBytes(std::uint16_t operation, const base::MacAddress& destination, const base::MacAddress& source,
                           const base::MacAddress& sender_mac, std::uint32_t sender_ip,
                           const base::MacAddress& target_mac, std::uint32_t target_ip) {
  Bytes f;
  PutMac(f, destination);
  PutMac(f, source);
  Put16(f, 0x0806);
  Put16(f, 1);       // Ethernet
  Put16(f, 0x0800);  // IPv4
  f.push_back(6);
  f.push_back(4);
  Put16(f, operation);
  PutMac(f, sender_mac);
  Put32(f, sender_ip);
  PutMac(f, target_mac);
  Put32(f, target_ip);
  return f;
}

// RFC 5227 §2.1.1 probe and §2.3 announcement of the card.
inline Bytes CardProbe(std::uint32_t address) {
  return ArpFrameBytes(1, base::kBroadcastMac, kCardMac, kCardMac, 0, base::kZeroMac, address);
}
inline Bytes CardAnnouncement(std::uint32_t address) {
  return ArpFrameBytes(1, base::kBroadcastMac, kCardMac, kCardMac, address, base::kZeroMac, address);
}

// The RFC 1071 sum over `bytes` added to `sum` (not yet folded or complemented).
inline std::uint32_t OnesSum(std::span<const std::uint8_t> bytes, std::uint32_t sum = 0) {
  for (std::size_t i = 0; i + 1 < bytes.size(); i += 2) sum += Get16(bytes, i);
  if (bytes.size() % 2 != 0) sum += static_cast<std::uint32_t>(bytes.back()) << 8;
  return sum;
}
inline std::uint16_t FoldComplement(std::uint32_t sum) {
  while (sum > 0xFFFF) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

// Ethernet + IPv4 (20-byte header without options, checksum set) around `payload`.
inline Bytes Ipv4FrameBytes(const base::MacAddress& destination, const base::MacAddress& source, std::uint32_t src_ip,
                            std::uint32_t dst_ip, std::uint8_t protocol, std::span<const std::uint8_t> payload) {
  Bytes ip;
  ip.push_back(0x45);
  ip.push_back(0);
  Put16(ip, static_cast<std::uint16_t>(20 + payload.size()));
  Put16(ip, 0x1234);  // identification
  Put16(ip, 0);       // no fragmentation
  ip.push_back(64);   // TTL
  ip.push_back(protocol);
  Put16(ip, 0);  // checksum, below
  Put32(ip, src_ip);
  Put32(ip, dst_ip);
  const std::uint16_t checksum = FoldComplement(OnesSum(ip));
  ip[10] = static_cast<std::uint8_t>(checksum >> 8);
  ip[11] = static_cast<std::uint8_t>(checksum);

  Bytes f;
  PutMac(f, destination);
  PutMac(f, source);
  Put16(f, 0x0800);
  f.insert(f.end(), ip.begin(), ip.end());
  f.insert(f.end(), payload.begin(), payload.end());
  return f;
}

// Ethernet + IPv4 + UDP (checksum over the pseudo-header set).
inline Bytes UdpFrameBytes(const base::MacAddress& destination, const base::MacAddress& source, std::uint32_t src_ip,
                           std::uint32_t dst_ip, std::uint16_t src_port, std::uint16_t dst_port,
                           std::span<const std::uint8_t> payload) {
  const auto udp_length = static_cast<std::uint16_t>(8 + payload.size());
  Bytes udp;
  Put16(udp, src_port);
  Put16(udp, dst_port);
  Put16(udp, udp_length);
  Put16(udp, 0);
  udp.insert(udp.end(), payload.begin(), payload.end());
  Bytes pseudo;
  Put32(pseudo, src_ip);
  Put32(pseudo, dst_ip);
  Put16(pseudo, 17);
  Put16(pseudo, udp_length);
  std::uint16_t checksum = FoldComplement(OnesSum(udp, OnesSum(pseudo)));
  if (checksum == 0) checksum = 0xFFFF;
  udp[6] = static_cast<std::uint8_t>(checksum >> 8);
  udp[7] = static_cast<std::uint8_t>(checksum);
  return Ipv4FrameBytes(destination, source, src_ip, dst_ip, 17, udp);
}

// A UDP datagram the card sent, taken apart (IPv4 header without options).
struct SentUdp {
  Bytes ethernet_destination;
  std::uint32_t src_ip = 0;
  std::uint32_t dst_ip = 0;
  std::uint16_t src_port = 0;
  std::uint16_t dst_port = 0;
  bool ip_checksum_ok = false;
  Bytes payload;
};
inline bool IsUdp(std::span<const std::uint8_t> f) {
  return f.size() >= 42 && Get16(f, 12) == 0x0800 && f[14] == 0x45 && f[23] == 17;
}
inline SentUdp ParseUdp(std::span<const std::uint8_t> f) {
  SentUdp u;
  u.ethernet_destination.assign(f.begin(), f.begin() + 6);
  u.src_ip = Get32(f, 26);
  u.dst_ip = Get32(f, 30);
  u.ip_checksum_ok = FoldComplement(OnesSum(f.subspan(14, 20))) == 0;
  u.src_port = Get16(f, 34);
  u.dst_port = Get16(f, 36);
  const std::size_t udp_length = Get16(f, 38);
  const std::size_t end = std::min(f.size(), 34 + udp_length);
  u.payload.assign(f.begin() + 42, f.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(end, 42)));
  return u;
}

inline config::CardConfig ManualConfig(base::Ipv4Address ip, base::Ipv4Address mask,
                                           base::Ipv4Address gateway = {}) {
  config::CardConfig config;
  config.ip_mode = config::IpMode::kManual;
  config.ip = ip;
  config.netmask = mask;
  config.gateway = gateway;
  return config;
}

inline config::CardConfig ModeConfig(config::IpMode mode, const std::string& name = "") {
  config::CardConfig config;
  config.ip_mode = mode;
  std::copy_n(name.begin(), std::min<std::size_t>(name.size(), 16), config.device_name.begin());
  return config;
}

class AddressingHarness : public ::testing::Test {
 protected:
  struct TimedFrame {
    Micros at;
    hal::PortId port;
    Bytes bytes;
  };

  AddressingHarness() {
    hal::test::EnsureLwipInitialised();
    netif_.Start(Ipv4Config{}, nullptr);
    netif_.SetObserver(&addressing_);
    Collect();  // whatever Start sent (nothing without an address)
  }
  ~AddressingHarness() override { netif_.SetObserver(nullptr); }

  static hal::test::FakeClock& Clock() { return hal::test::LwipTestClock(); }
  static Micros Now() { return Clock().NowMicros(); }

  // One pass of the event loop at the clock's instant.
  void Step() {
    netif_.SyncLinkState();
    netif_.PumpReceive(32);
    sys_check_timeouts();
    addressing_.Poll(Now());
    Collect();
  }

  // Passes from deadline to deadline (the addressing's and lwIP's timers) until `end`.
  void RunUntil(Micros end) {
    Step();
    for (int i = 0; i < 100000 && Now() < end; ++i) {
      const Micros lwip_due = Now() + static_cast<Micros>(std::min<u32_t>(sys_timeouts_sleeptime(), 1000)) * kMs;
      Micros next = std::min({addressing_.NextDeadline(), lwip_due, end});
      if (next <= Now()) next = Now() + 1;  // a deadline at "now" was served by the last pass
      Clock().Set(next);
      Step();
    }
  }
  void RunFor(Micros duration) { RunUntil(Now() + duration); }

  // Injects a frame on `port` and runs one pass at the current instant.
  void Receive(const Bytes& frame, hal::PortId port = hal::PortId::kLeft) {
    port_.Inject(frame, port);
    Step();
  }

  // The frames logged since `from` (an index into sent_) that are ARP.
  std::vector<TimedFrame> ArpSince(std::size_t from = 0) const {
    std::vector<TimedFrame> arp;
    for (std::size_t i = from; i < sent_.size(); ++i) {
      if (sent_[i].bytes.size() >= 14 && Get16(sent_[i].bytes, 12) == 0x0806) arp.push_back(sent_[i]);
    }
    return arp;
  }
  std::vector<TimedFrame> UdpSince(std::size_t from = 0) const {
    std::vector<TimedFrame> udp;
    for (std::size_t i = from; i < sent_.size(); ++i) {
      if (IsUdp(sent_[i].bytes)) udp.push_back(sent_[i]);
    }
    return udp;
  }

  // The address in lwIP, host order.
  std::uint32_t LwipAddress() { return lwip_ntohl(ip4_addr_get_u32(netif_ip4_addr(&netif_.lwip_netif()))); }
  std::uint32_t LwipMask() { return lwip_ntohl(ip4_addr_get_u32(netif_ip4_netmask(&netif_.lwip_netif()))); }
  std::uint32_t LwipGateway() { return lwip_ntohl(ip4_addr_get_u32(netif_ip4_gw(&netif_.lwip_netif()))); }

  hal::test::FakeFramePort port_{kCardMac, 1};
  CardNetif netif_{port_};
  hal::test::CountingRandom random_;
  CardAddressing addressing_{netif_, Clock(), random_};
  std::vector<TimedFrame> sent_;

 private:
  void Collect() {
    for (auto& frame : port_.sent()) sent_.push_back(TimedFrame{Now(), frame.port, std::move(frame.bytes)});
    port_.sent().clear();
  }
};

}  // namespace firmware::test
