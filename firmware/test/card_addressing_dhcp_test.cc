// CardAddressing with c504 = 2 (lwIP's DHCP client with our state and our options hook) on a fake port:
// the options the card adds (61 client identifier = type 0 + device name, 12 host name in DISCOVER), a
// whole DISCOVER/OFFER/REQUEST/ACK exchange with lwIP's ARP check, ACD claiming the lease, and the lease
// given back after ACD yields it.
#include <gtest/gtest.h>

#include <map>
#include <optional>

#include "card_addressing_harness.h"
#include "lwip/prot/dhcp.h"
#include "lwip_hooks.h"

namespace firmware::test {
namespace {

constexpr base::MacAddress kServerMac = {0x02, 0x00, 0x00, 0x00, 0x00, 0x43};
constexpr std::uint32_t kServerIp = 0xC0A80101;  // 192.168.1.1
constexpr std::uint32_t kOffered = 0xC0A8013C;   // 192.168.1.60
const std::string kName = "VFS15-LINE3";

// DHCP message types (RFC 2132 §9.6).
constexpr std::uint8_t kDiscover = 1;
constexpr std::uint8_t kOffer = 2;
constexpr std::uint8_t kRequest = 3;
constexpr std::uint8_t kAck = 5;
constexpr std::uint8_t kRelease = 7;

// The options of a BOOTP/DHCP payload after the cookie, code -> every instance's data, in order.
std::multimap<std::uint8_t, Bytes> Options(const Bytes& payload) {
  std::multimap<std::uint8_t, Bytes> options;
  if (payload.size() < 240 || Get32(payload, 236) != 0x63825363) {
    ADD_FAILURE() << "no magic cookie";
    return options;
  }
  std::size_t at = 240;
  while (at < payload.size()) {
    const std::uint8_t code = payload[at];
    if (code == 0) {
      ++at;
      continue;
    }
    if (code == 255) return options;
    if (at + 1 >= payload.size() || at + 2 + payload[at + 1] > payload.size()) {
      ADD_FAILURE() << "option " << int{code} << " runs past the payload";
      return options;
    }
    options.emplace(code, Bytes(payload.begin() + static_cast<std::ptrdiff_t>(at + 2),
                                payload.begin() + static_cast<std::ptrdiff_t>(at + 2 + payload[at + 1])));
    at += 2 + payload[at + 1];
  }
  ADD_FAILURE() << "no end option";
  return options;
}

std::optional<Bytes> Option(const Bytes& payload, std::uint8_t code) {
  const auto options = Options(payload);
  const auto it = options.find(code);
  if (it == options.end()) return std::nullopt;
  return it->second;
}

Bytes NameBytes(const std::string& name) { return Bytes(name.begin(), name.end()); }
Bytes ClientId(const std::string& name) {
  Bytes id(name.size() + 1, 0x00);  // type 0, then the name
  std::copy(name.begin(), name.end(), id.begin() + 1);
  return id;
}

// A DHCP reply from the server (broadcast, as for a client without the broadcast flag it could unicast).
Bytes ServerReply(std::uint8_t type, std::uint32_t xid, std::uint32_t yiaddr) {
  Bytes m = {2, 1, 6, 0};
  Put32(m, xid);
  Put16(m, 0);
  Put16(m, 0);
  Put32(m, 0);
  Put32(m, yiaddr);
  Put32(m, kServerIp);
  Put32(m, 0);
  PutMac(m, kCardMac);
  m.resize(236, 0);
  Put32(m, 0x63825363);
  const Bytes options = {53, 1, type, 54, 4, 192, 168, 1, 1, 51, 4, 0, 0, 0x0E, 0x10,  // lease 3600 s
                         1, 4, 255, 255, 255, 0, 3, 4, 192, 168, 1, 1, 255};
  m.insert(m.end(), options.begin(), options.end());
  m.resize(300, 0);
  return UdpFrameBytes(base::kBroadcastMac, kServerMac, kServerIp, 0xFFFFFFFF, 67, 68, m);
}

// The server's ARP reply to the card (for the leased address the card asked from).
Bytes ServerArpReply() { return ArpFrameBytes(2, kCardMac, kServerMac, kServerMac, kServerIp, kCardMac, kOffered); }

class DhcpAddressingTest : public AddressingHarness {
 protected:
  // The DHCP messages the card sent since `from`, as UDP payloads.
  std::vector<Bytes> DhcpSince(std::size_t from = 0) const {
    std::vector<Bytes> messages;
    for (const auto& frame : UdpSince(from)) {
      const SentUdp udp = ParseUdp(frame.bytes);
      if (udp.src_port == 68 && udp.dst_port == 67) messages.push_back(udp.payload);
    }
    return messages;
  }
  static std::uint8_t Type(const Bytes& message) {
    const auto type = Option(message, 53);
    return type.has_value() && type->size() == 1 ? (*type)[0] : 0;
  }

  // Configures DHCP with kName and runs one pass: DHCP starts from Poll. Returns the DISCOVER.
  Bytes ConfigureDhcp(const std::string& name = kName) {
    EXPECT_TRUE(addressing_.Configure(ModeConfig(config::IpMode::kDhcp, name)).ok());
    Step();
    const auto messages = DhcpSince();
    EXPECT_EQ(messages.size(), 1u);
    return messages.empty() ? Bytes{} : messages[0];
  }

  // DISCOVER, OFFER, REQUEST, ACK, lwIP's ARP check: returns the instant the lease was bound.
  Micros Lease() {
    const Bytes discover = ConfigureDhcp();
    const std::uint32_t xid = Get32(discover, 4);
    std::size_t mark = sent_.size();
    Receive(ServerReply(kOffer, xid, kOffered));
    const auto request = DhcpSince(mark);
    EXPECT_EQ(request.size(), 1u);
    mark = sent_.size();
    Receive(ServerReply(kAck, xid, kOffered));
    for (int i = 0; i < 40 && LwipAddress() == 0; ++i) RunFor(100 * kMs);
    EXPECT_EQ(LwipAddress(), kOffered);
    return Now();
  }
};

TEST_F(DhcpAddressingTest, Discover_ClientIdIsType0PlusDeviceName_HostNameOption12) {
  const Bytes discover = ConfigureDhcp();
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
  EXPECT_EQ(addressing_.mode(), config::IpMode::kDhcp);
  const auto frames = UdpSince();
  ASSERT_EQ(frames.size(), 1u);
  const SentUdp udp = ParseUdp(frames[0].bytes);
  EXPECT_EQ(udp.ethernet_destination, Bytes(6, 0xFF));
  EXPECT_EQ(udp.src_ip, 0u);
  EXPECT_EQ(udp.dst_ip, 0xFFFFFFFFu);
  EXPECT_TRUE(udp.ip_checksum_ok);
  ASSERT_GE(discover.size(), 240u);
  EXPECT_EQ(discover[0], 1);
  EXPECT_EQ(Bytes(discover.begin() + 28, discover.begin() + 34), Bytes(kCardMac.octets().begin(), kCardMac.octets().end()));
  EXPECT_EQ(Type(discover), kDiscover);
  const auto options = Options(discover);
  ASSERT_EQ(options.count(12), 1u);
  EXPECT_EQ(options.find(12)->second, NameBytes(kName));
  ASSERT_EQ(options.count(61), 1u);
  EXPECT_EQ(options.find(61)->second, ClientId(kName));
}

TEST_F(DhcpAddressingTest, SixteenCharacterName_BothOptionsFit) {
  const std::string name = "ABCDEFGHIJKLMNOP";
  const Bytes discover = ConfigureDhcp(name);
  EXPECT_EQ(Option(discover, 12), NameBytes(name));
  EXPECT_EQ(Option(discover, 61), ClientId(name));
}

TEST_F(DhcpAddressingTest, NoDeviceName_NeitherOption) {
  const Bytes discover = ConfigureDhcp("");
  EXPECT_EQ(Type(discover), kDiscover);
  EXPECT_FALSE(Option(discover, 12).has_value());
  EXPECT_FALSE(Option(discover, 61).has_value());
}

TEST_F(DhcpAddressingTest, FullExchange_ArpCheckedLeaseInstalledThenClaimedByAcd) {
  const Bytes discover = ConfigureDhcp();
  const std::uint32_t xid = Get32(discover, 4);

  std::size_t mark = sent_.size();
  Receive(ServerReply(kOffer, xid, kOffered));
  auto messages = DhcpSince(mark);
  ASSERT_EQ(messages.size(), 1u);
  const Bytes& request = messages[0];
  EXPECT_EQ(Type(request), kRequest);
  EXPECT_EQ(Get32(request, 4), xid);
  EXPECT_EQ(Option(request, 50), (Bytes{192, 168, 1, 60}));  // requested address
  EXPECT_EQ(Option(request, 54), (Bytes{192, 168, 1, 1}));   // server identifier
  EXPECT_EQ(Options(request).count(12), 1u);                  // lwIP's own, not a second from the hook
  EXPECT_EQ(Option(request, 12), NameBytes(kName));
  EXPECT_EQ(Option(request, 61), ClientId(kName));
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);

  mark = sent_.size();
  Receive(ServerReply(kAck, xid, kOffered));
  // lwIP's DHCP_DOES_ARP_CHECK: an ARP request for the offered address from 0.0.0.0 (a probe) first;
  // the address is not used before the check has run out.
  auto arp = ArpSince(mark);
  ASSERT_EQ(arp.size(), 1u);
  EXPECT_EQ(arp[0].bytes, CardProbe(kOffered));
  EXPECT_EQ(LwipAddress(), 0u);
  const Micros ack_at = Now();
  for (int i = 0; i < 40 && LwipAddress() == 0; ++i) RunFor(100 * kMs);
  ASSERT_EQ(LwipAddress(), kOffered);
  EXPECT_LE(Now() - ack_at, 2 * kSec);
  EXPECT_EQ(LwipMask(), 0xFFFFFF00u);
  EXPECT_EQ(LwipGateway(), kServerIp);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kInUse);
  EXPECT_FALSE(addressing_.acquiring());

  // ACD claims the leased address without probing again: two announcements 2 s apart.
  mark = sent_.size();
  const AddressingCounters before = addressing_.counters();
  RunFor(2500 * kMs);
  std::size_t announcements = 0;
  for (const auto& f : ArpSince(mark)) {
    EXPECT_NE(f.bytes, CardProbe(kOffered));
    announcements += f.bytes == CardAnnouncement(kOffered) ? 1 : 0;
  }
  EXPECT_GE(announcements, 1u);
  EXPECT_EQ(addressing_.counters().acd_frames_sent, 2u);
  EXPECT_LE(before.acd_frames_sent, 1u);
}

TEST_F(DhcpAddressingTest, AcdYieldsLease_ReleasedAndDiscoverAgainAfterTenSeconds) {
  Lease();
  RunFor(5 * kSec);
  const Bytes conflict = ArpFrameBytes(1, base::kBroadcastMac, kOtherMac, kOtherMac, kOffered, base::kZeroMac, kOffered);
  Receive(conflict);  // defended
  EXPECT_EQ(LwipAddress(), kOffered);
  RunFor(1 * kSec);
  std::size_t mark = sent_.size();
  Receive(conflict);  // yielded: the lease goes back
  const Micros yielded_at = Now();
  EXPECT_EQ(LwipAddress(), 0u);
  EXPECT_EQ(addressing_.counters().dhcp_restarts, 1u);
  EXPECT_TRUE(addressing_.duplicate_detected());
  // The address left lwIP before lwIP read the frame: no ARP reply to the other host. The DHCPRELEASE
  // (unicast to the server) waits for the server's MAC: lwIP asks for it.
  auto arp = ArpSince(mark);
  ASSERT_EQ(arp.size(), 1u);
  EXPECT_EQ(arp[0].bytes, ArpFrameBytes(1, base::kBroadcastMac, kCardMac, kCardMac, kOffered, base::kZeroMac, kServerIp));
  EXPECT_TRUE(DhcpSince(mark).empty());
  Receive(ServerArpReply());
  auto messages = DhcpSince(mark);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(Type(messages[0]), kRelease);
  EXPECT_EQ(Option(messages[0], 61), ClientId(kName));
  EXPECT_EQ(Get32(messages[0], 12), kOffered);  // ciaddr

  mark = sent_.size();
  RunUntil(yielded_at + 9900 * kMs);
  EXPECT_TRUE(DhcpSince(mark).empty());  // RFC 2131 §3.1: wait 10 s before starting again
  RunUntil(yielded_at + 10 * kSec + 100 * kMs);
  messages = DhcpSince(mark);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(Type(messages[0]), kDiscover);
  EXPECT_EQ(addressing_.phase(), AddressPhase::kAcquiring);
}

TEST_F(DhcpAddressingTest, SwitchToManual_LeaseReleased) {
  Lease();
  addressing_.SetAcdEnabled(false);
  const std::size_t mark = sent_.size();
  ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
  EXPECT_EQ(LwipAddress(), 0xC0A8010Cu);
  Receive(ServerArpReply());  // the server's MAC, for the DHCPRELEASE lwIP holds
  const auto messages = DhcpSince(mark);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(Type(messages[0]), kRelease);
  RunFor(20 * kSec);
  EXPECT_EQ(DhcpSince(mark).size(), 1u);  // DHCP stays stopped
  EXPECT_EQ(LwipAddress(), 0xC0A8010Cu);
}

// The options hook itself, as lwIP calls it: a message whose options so far are `head` (`length` bytes
// of it used), a netif with host name `name`, the type lwIP says the message has.
struct HookResult {
  Bytes options;
  u16_t length = 0;
};
HookResult RunHook(const std::string& name, const Bytes& head, std::size_t length, u8_t given_type) {
  netif nif{};
  nif.hostname = name.c_str();
  dhcp_msg msg{};
  std::copy(head.begin(), head.end(), msg.options);
  auto used = static_cast<u16_t>(length);
  ipe_dhcp_append_options(&nif, given_type, &msg, &used);
  return {Bytes(msg.options, msg.options + used), used};
}

// lwIP 2.1.3's dhcp_rebind passes DHCP_DISCOVER as the type of its DHCPREQUEST (after adding the host name
// itself): the message's own option 53 is what counts.
TEST(DhcpOptionsHookTest, TypeFromTheMessage_NoSecondHostNameInARebindingRequest) {
  const Bytes head = {53, 1, kRequest, 12, 6, 'D', 'R', 'I', 'V', 'E', '7'};
  Bytes expected = head;
  const Bytes client_id = {61, 7, 0, 'D', 'R', 'I', 'V', 'E', '7'};
  expected.insert(expected.end(), client_id.begin(), client_id.end());
  EXPECT_EQ(RunHook("DRIVE7", head, head.size(), DHCP_DISCOVER).options, expected);
}

TEST(DhcpOptionsHookTest, DiscoverGetsHostNameAndClientId_RequestOnlyClientId) {
  EXPECT_EQ(RunHook("AB", {53, 1, kDiscover}, 3, DHCP_DISCOVER).options,
            (Bytes{53, 1, 1, 12, 2, 'A', 'B', 61, 3, 0, 'A', 'B'}));
  EXPECT_EQ(RunHook("AB", {53, 1, kRequest}, 3, DHCP_REQUEST).options, (Bytes{53, 1, 3, 61, 3, 0, 'A', 'B'}));
  EXPECT_EQ(RunHook("", {53, 1, kDiscover}, 3, DHCP_DISCOVER).options, (Bytes{53, 1, 1}));
}

TEST(DhcpOptionsHookTest, NoRoomForOptionAndEnd_LeftOut) {
  const std::string name = "ABCDEFGHIJKLMNOP";
  // 19 bytes of option 61 plus the end option need 20: one byte short.
  EXPECT_EQ(RunHook(name, {53, 1, kRequest}, DHCP_OPTIONS_LEN - 19, DHCP_REQUEST).length, DHCP_OPTIONS_LEN - 19);
  const HookResult fits = RunHook(name, {53, 1, kRequest}, DHCP_OPTIONS_LEN - 20, DHCP_REQUEST);
  EXPECT_EQ(fits.length, DHCP_OPTIONS_LEN - 1);
  EXPECT_EQ(fits.options[DHCP_OPTIONS_LEN - 20], 61);
}

}  // namespace
}  // namespace firmware::test
