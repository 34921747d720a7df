// TCP/IP Interface and Ethernet Link objects (manual §4.11, §4.12, §3.2.2) through a CipDevice on fakes:
// every attribute with exact bytes, every settable attribute's checks and what reaches the store.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "cip/ethernet_link_object.h"
#include "cip/tcpip_interface_object.h"
#include "cip_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::FakeCard;
using test::Hex;

// Set_Attribute_Single of TCP/IP instance 1 attribute `attribute` with `value` (hex).
Bytes SetTcpIp(std::uint8_t attribute, std::string_view value) {
  return test::Concat({0x10, 0x03, 0x20, 0xF5, 0x24, 0x01, 0x30, attribute}, Hex(value));
}
Bytes GetTcpIp(std::uint8_t attribute) { return {0x0E, 0x03, 0x20, 0xF5, 0x24, 0x01, 0x30, attribute}; }

const Bytes kOk = Hex("90 00 00 00");

class CipTcpIpTest : public ::testing::Test {
 protected:
  CipTcpIpTest() {
    EXPECT_TRUE(card_.tcpip.stored.host_name.Assign("VFMB1-4007PL"));
  }
  FakeCard card_;
};

TEST_F(CipTcpIpTest, StatusAndCapability) {
  EXPECT_EQ(card_.Ask(GetTcpIp(1)), Hex("8E 00 00 00 01 00 00 00"));
  card_.tcpip.conflict_detected = true;
  EXPECT_EQ(card_.Ask(GetTcpIp(1)), Hex("8E 00 00 00 41 00 00 00"));
  card_.tcpip.valid = false;
  card_.tcpip.conflict_detected = false;
  EXPECT_EQ(card_.Ask(GetTcpIp(1)), Hex("8E 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(2)), Hex("8E 00 00 00 9D 00 00 00"));
}

TEST_F(CipTcpIpTest, GetEveryAttribute) {
  card_.tcpip.stored.startup = StartupConfiguration::kDhcp;
  card_.tcpip.last_conflict.acd_activity = 2;
  card_.tcpip.last_conflict.remote_mac = {0x02, 0x00, 0x00, 0x00, 0x00, 0x09};
  card_.tcpip.last_conflict.arp_pdu[0] = 0x00;
  card_.tcpip.last_conflict.arp_pdu[1] = 0x01;
  EXPECT_EQ(card_.Ask(GetTcpIp(3)), Hex("8E 00 00 00 02 00 00 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(4)), Hex("8E 00 00 00 02 00 20 F6 24 01"));
  EXPECT_EQ(card_.Ask(GetTcpIp(5)), Hex("8E 00 00 00 0F 02 00 0A | 00 FF FF FF | 02 02 00 0A | 00 00 00 00 |"
                                        "00 00 00 00 | 00 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(6)), Hex("8E 00 00 00 0C 00 56 46 4D 42 31 2D 34 30 30 37 50 4C"));
  EXPECT_EQ(card_.Ask(GetTcpIp(7)), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(8)), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(GetTcpIp(9)), Hex("8E 00 00 00 00 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(10)), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(GetTcpIp(11)), Hex("8E 00 00 00 02 | 02 00 00 00 00 09 | 00 01 00 00 00 00 00 00 00 00 00 00 00 00"
                                         "00 00 00 00 00 00 00 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(GetTcpIp(12)), Hex("8E 00 14 00"));
  (void)card_.tcpip.active.domain_name.Assign("abc");
  EXPECT_EQ(card_.Ask(GetTcpIp(5)), Hex("8E 00 00 00 0F 02 00 0A 00 FF FF FF 02 02 00 0A 00 00 00 00 00 00 00 00"
                                        "| 03 00 61 62 63 00"));
}

TEST_F(CipTcpIpTest, GetAttributesAllKeepsAPlaceForAttribute7) {
  EXPECT_EQ(card_.Ask(Hex("01 02 20 F5 24 01")),
            Hex("81 00 00 00 | 01 00 00 00 | 9D 00 00 00 | 00 00 00 00 | 02 00 20 F6 24 01"
                "| 0F 02 00 0A 00 FF FF FF 02 02 00 0A 00 00 00 00 00 00 00 00 00 00"
                "| 0C 00 56 46 4D 42 31 2D 34 30 30 37 50 4C | 00 00 00 00 00 00 | 01 | 00 00 00 00 00 00 00 00 | 01"
                "| 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"));
}

TEST_F(CipTcpIpTest, ClassAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 F5 24 00 30 04")), Hex("8E 00 00 00 04 00 08 00 09 00 0A 00 0B 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 F5 24 00 30 05")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 F5 24 00 30 07")), Hex("8E 00 00 00 0B 00"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 F5 24 00")),
            Hex("81 00 00 00 01 00 01 00 01 00 04 00 08 00 09 00 0A 00 0B 00 00 00 07 00 0B 00"));
}

TEST_F(CipTcpIpTest, ConfigurationControlIsTheIpMode) {
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "02 00 00 00")), kOk);
  EXPECT_EQ(card_.tcpip.stored.startup, StartupConfiguration::kDhcp);
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "01 00 00 00")), kOk);
  EXPECT_EQ(card_.tcpip.stored.startup, StartupConfiguration::kBootp);
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "12 00 00 00")), Hex("90 00 09 00"));  // DNS
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "03 00 00 00")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "00 00 00")), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(3, "00 00 00 00 00")), Hex("90 00 15 00"));
  EXPECT_EQ(card_.tcpip.stores, 2);
}

// 192.168.0.10/24, gateway 192.168.0.1, no name servers.
const std::string_view kStaticConfiguration = "0A 00 A8 C0 | 00 FF FF FF | 01 00 A8 C0 | 00 00 00 00 | 00 00 00 00";

TEST_F(CipTcpIpTest, InterfaceConfigurationIsStoredForTheNextStart) {
  EXPECT_EQ(card_.Ask(SetTcpIp(5, std::string(kStaticConfiguration) + "00 00")), kOk);
  EXPECT_EQ(card_.tcpip.stored.static_configuration.ip_address, 0xC0A8000AU);
  EXPECT_EQ(card_.tcpip.stored.static_configuration.network_mask, 0xFFFFFF00U);
  EXPECT_EQ(card_.tcpip.stored.static_configuration.gateway, 0xC0A80001U);
  // The address in use does not change before a reset.
  EXPECT_EQ(card_.Ask(GetTcpIp(5)).at(4), 0x0F);
  EXPECT_EQ(card_.Ask(SetTcpIp(5, std::string(kStaticConfiguration) + "03 00 61 62 63 00")), kOk);
  EXPECT_EQ(card_.tcpip.stored.static_configuration.domain_name.size(), 3U);
  // All zeros: no address configured.
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "00000000 00000000 00000000 00000000 00000000 0000")), kOk);
}

TEST_F(CipTcpIpTest, InterfaceConfigurationChecks) {
  const std::string base(kStaticConfiguration);
  EXPECT_EQ(card_.Ask(SetTcpIp(5, base + "00")), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, base + "00 00 00")), Hex("90 00 15 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, base + "03 00 61 62 63")), Hex("90 00 13 00"));  // pad missing
  Bytes long_domain = test::Concat(Hex(base + "31 00"), Bytes(49, 'a'));
  long_domain.push_back(0);
  EXPECT_EQ(card_.Ask(test::Concat(SetTcpIp(5, ""), long_domain)), Hex("90 00 09 00"));
  // Mask with a hole, gateway on another subnet, broadcast host, loopback, multicast name server.
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "0A00A8C0 00FF00FF 0100A8C0 00000000 00000000 0000")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "0A00A8C0 00FFFFFF 0101A8C0 00000000 00000000 0000")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "FF00A8C0 00FFFFFF 0100A8C0 00000000 00000000 0000")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "0100007F 000000FF 00000000 00000000 00000000 0000")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(5, "0A00A8C0 00FFFFFF 0100A8C0 010000E0 00000000 0000")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.tcpip.stores, 0);
  // While the card is to use BOOTP or DHCP, a static configuration is refused outright.
  card_.tcpip.stored.startup = StartupConfiguration::kDhcp;
  EXPECT_EQ(card_.Ask(SetTcpIp(5, base + "00 00")), Hex("90 00 0C 00"));
}

TEST_F(CipTcpIpTest, StoreFailures) {
  card_.tcpip.store_result = base::InvalidArgument();
  EXPECT_EQ(card_.Ask(SetTcpIp(8, "05")), Hex("90 00 09 00"));
  card_.tcpip.store_result = base::Unavailable();
  EXPECT_EQ(card_.Ask(SetTcpIp(8, "05")), Hex("90 00 19 00"));
  EXPECT_EQ(card_.tcpip.stored.ttl, 1);
}

TEST_F(CipTcpIpTest, HostNameIsTheDeviceName) {
  EXPECT_EQ(card_.Ask(SetTcpIp(6, "05 00 56 46 53 31 35 00")), kOk);  // "VFS15" + pad
  EXPECT_TRUE(card_.tcpip.stored.host_name == [] {
    FixedString<kMaxHostName> name;
    (void)name.Assign("VFS15");
    return name;
  }());
  EXPECT_EQ(card_.Ask(SetTcpIp(6, "00 00")), kOk);
  EXPECT_TRUE(card_.tcpip.stored.host_name.empty());
  EXPECT_EQ(card_.Ask(SetTcpIp(6, "11 00 61 61 61 61 61 61 61 61 61 61 61 61 61 61 61 61 61 00")),
            Hex("90 00 09 00"));  // 17 characters: c081-c096 hold 16
  EXPECT_EQ(card_.Ask(SetTcpIp(6, "02 00 61 20")), Hex("90 00 09 00"));  // a space
  EXPECT_EQ(card_.Ask(SetTcpIp(6, "03 00 61 62 63")), Hex("90 00 13 00"));
}

TEST_F(CipTcpIpTest, TtlMulticastAcd) {
  EXPECT_EQ(card_.Ask(SetTcpIp(8, "20")), kOk);
  EXPECT_EQ(card_.tcpip.stored.ttl, 0x20);
  EXPECT_EQ(card_.Ask(SetTcpIp(8, "00")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "01 00 20 00 00 01 C0 EF")), kOk);  // 32 from 239.192.1.0
  EXPECT_EQ(card_.tcpip.stored.multicast, (MulticastConfiguration{1, 32, 0xEFC00100}));
  EXPECT_EQ(card_.Ask(GetTcpIp(9)), Hex("8E 00 00 00 01 00 20 00 00 01 C0 EF"));
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "00 00 01 00 00 00 00 00")), Hex("90 00 09 00"));  // default with a count
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "02 00 01 00 00 01 C0 EF")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "01 01 01 00 00 01 C0 EF")), Hex("90 00 09 00"));  // reserved byte
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "01 00 01 00 05 00 00 E0")), Hex("90 00 09 00"));  // 224.0.0.5
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "01 00 01 00 00 00 A8 C0")), Hex("90 00 09 00"));  // unicast
  EXPECT_EQ(card_.Ask(SetTcpIp(9, "01 00 01 00 00 01 C0")), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(10, "00")), kOk);
  EXPECT_FALSE(card_.tcpip.stored.select_acd);
  EXPECT_EQ(card_.Ask(SetTcpIp(10, "02")), Hex("90 00 09 00"));
}

TEST_F(CipTcpIpTest, LastConflictCanOnlyBeCleared) {
  card_.tcpip.last_conflict.acd_activity = 1;
  EXPECT_EQ(card_.Ask(test::Concat(SetTcpIp(11, ""), Bytes(35, 0))), kOk);
  EXPECT_EQ(card_.tcpip.clears, 1);
  Bytes not_zero(35, 0);
  not_zero[3] = 1;
  EXPECT_EQ(card_.Ask(test::Concat(SetTcpIp(11, ""), not_zero)), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(test::Concat(SetTcpIp(11, ""), Bytes(34, 0))), Hex("90 00 13 00"));
  EXPECT_EQ(card_.tcpip.clears, 1);
}

TEST_F(CipTcpIpTest, ReadOnlyAttributes) {
  EXPECT_EQ(card_.Ask(SetTcpIp(1, "00 00 00 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(2, "00 00 00 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(4, "02 00 20 F6 24 01")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(SetTcpIp(7, "00 00 00 00 00 00")), Hex("90 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 F5 24 00 30 01 01 00")), Hex("90 00 08 00"));  // class level
}

TEST(CipTcpIpRules, InterfaceConfiguration) {
  InterfaceConfiguration c;
  c.ip_address = 0x0A000001;
  c.network_mask = 0xFF000000;
  EXPECT_TRUE(IsValidInterfaceConfiguration(c));
  c.network_mask = 0xFFFFFFFE;  // /31: no room for hosts
  EXPECT_FALSE(IsValidInterfaceConfiguration(c));
  c.network_mask = 0xFFFFFF00;
  c.ip_address = 0x0A000000;  // the network address itself
  EXPECT_FALSE(IsValidInterfaceConfiguration(c));
  c.ip_address = 0x0A000002;
  c.gateway = 0x0A000002;  // gateway = own address
  EXPECT_FALSE(IsValidInterfaceConfiguration(c));
  c.gateway = 0x0A000001;
  EXPECT_TRUE(IsValidInterfaceConfiguration(c));
  c.ip_address = 0;  // zero address with a mask is not "unconfigured"
  EXPECT_FALSE(IsValidInterfaceConfiguration(c));
}

// ---- Ethernet Link -------------------------------------------------------------------------------

Bytes GetLink(std::uint8_t instance, std::uint8_t attribute) {
  return {0x0E, 0x03, 0x20, 0xF6, 0x24, instance, 0x30, attribute};
}

class CipEthernetLinkTest : public ::testing::Test {
 protected:
  CipEthernetLinkTest() {
    card_.links.state[0] = LinkState{true, true, 100, NegotiationStatus::kNegotiated, false};
    InterfaceCounters& c = card_.links.counters[1];
    c = InterfaceCounters{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    card_.links.media[1] = MediaCounters{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  }
  FakeCard card_;
};

const std::string_view kCounterBytes =
    "01000000 02000000 03000000 04000000 05000000 06000000 07000000 08000000 09000000 0A000000 0B000000";
const std::string_view kMediaBytes =
    "01000000 02000000 03000000 04000000 05000000 06000000 07000000 08000000 09000000 0A000000 0B000000 0C000000";

TEST_F(CipEthernetLinkTest, SpeedFlagsAndAddress) {
  EXPECT_EQ(card_.Ask(GetLink(1, 1)), Hex("8E 00 00 00 64 00 00 00"));
  EXPECT_EQ(card_.Ask(GetLink(1, 2)), Hex("8E 00 00 00 2F 00 00 00"));
  EXPECT_EQ(card_.Ask(GetLink(2, 1)), Hex("8E 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(GetLink(2, 2)), Hex("8E 00 00 00 20 00 00 00"));
  card_.links.state[1] = LinkState{true, false, 10, NegotiationStatus::kForced, true};
  EXPECT_EQ(card_.Ask(GetLink(2, 2)), Hex("8E 00 00 00 71 00 00 00"));
  EXPECT_EQ(card_.Ask(GetLink(1, 3)), Hex("8E 00 00 00 00 80 F4 7D 02 C0"));
  EXPECT_EQ(card_.Ask(GetLink(2, 3)), Hex("8E 00 00 00 00 80 F4 7D 02 C0"));
}

TEST_F(CipEthernetLinkTest, CountersTypeAndLabels) {
  EXPECT_EQ(card_.Ask(GetLink(2, 4)), test::Concat(Hex("8E 00 00 00"), Hex(kCounterBytes)));
  EXPECT_EQ(card_.Ask(GetLink(2, 5)), test::Concat(Hex("8E 00 00 00"), Hex(kMediaBytes)));
  EXPECT_EQ(card_.Ask(GetLink(1, 6)), Hex("8E 00 00 00 01 00 00 00"));
  EXPECT_EQ(card_.Ask(GetLink(1, 7)), Hex("8E 00 00 00 02"));
  EXPECT_EQ(card_.Ask(GetLink(1, 10)), Hex("8E 00 00 00 04 4C 65 66 74"));
  EXPECT_EQ(card_.Ask(GetLink(2, 10)), Hex("8E 00 00 00 05 52 69 67 68 74"));
  EXPECT_EQ(card_.Ask(GetLink(1, 8)), Hex("8E 00 00 00 01"));  // interface state: enabled
  EXPECT_EQ(card_.Ask(GetLink(2, 9)), Hex("8E 00 00 00 01"));  // admin state: enabled
  EXPECT_EQ(card_.Ask(GetLink(1, 11)), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(GetLink(3, 1)), Hex("8E 00 16 00"));
}

TEST_F(CipEthernetLinkTest, GetAttributesAll) {
  EXPECT_EQ(card_.Ask(Hex("01 02 20 F6 24 02")),
            test::Concat(test::Concat(Hex("81 00 00 00 00 00 00 00 20 00 00 00 00 80 F4 7D 02 C0"), Hex(kCounterBytes)),
                         test::Concat(Hex(kMediaBytes), Hex("01 00 00 00 | 02 | 01 | 01 | 05 52 69 67 68 74"))));
  // Class level: revision, max instance, count, empty optional attribute and service lists, 7, 10.
  EXPECT_EQ(card_.Ask(Hex("01 02 20 F6 24 00")), Hex("81 00 00 00 03 00 02 00 02 00 00 00 00 00 07 00 0A 00"));
}

TEST_F(CipEthernetLinkTest, InterfaceControlIsTheRateSetting) {
  const Bytes set = Hex("10 03 20 F6 24 02 30 06");
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 0A 00"))), kOk);
  EXPECT_EQ(card_.links.setting, LinkSetting::k10Half);
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("02 00 64 00"))), kOk);
  EXPECT_EQ(card_.links.setting, LinkSetting::k100Full);
  EXPECT_EQ(card_.Ask(GetLink(1, 6)), Hex("8E 00 00 00 02 00 64 00"));  // one setting for both ports
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("02 00 0A 00"))), kOk);
  EXPECT_EQ(card_.links.setting, LinkSetting::k10Full);
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 64 00"))), kOk);
  EXPECT_EQ(card_.links.setting, LinkSetting::k100Half);
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("01 00 00 00"))), kOk);
  EXPECT_EQ(card_.links.setting, LinkSetting::kAuto);
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("01 00 64 00"))), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 0B 00"))), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("04 00 0A 00"))), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 0A"))), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 0A 00 00"))), Hex("90 00 15 00"));
  card_.links.store_result = base::Unavailable();
  EXPECT_EQ(card_.Ask(test::Concat(set, Hex("00 00 0A 00"))), Hex("90 00 19 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 F6 24 01 30 01 64 00 00 00")), Hex("90 00 0E 00"));
}

TEST_F(CipEthernetLinkTest, GetAndClear) {
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 F6 24 02 30 04")), test::Concat(Hex("CC 00 00 00"), Hex(kCounterBytes)));
  EXPECT_EQ(card_.Ask(GetLink(2, 4)), test::Concat(Hex("8E 00 00 00"), Bytes(44, 0)));
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 F6 24 02 30 05")), test::Concat(Hex("CC 00 00 00"), Hex(kMediaBytes)));
  EXPECT_EQ(card_.Ask(GetLink(2, 5)), test::Concat(Hex("8E 00 00 00"), Bytes(48, 0)));
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 F6 24 01 30 01")), Hex("CC 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("4C 02 20 F6 24 01")), Hex("CC 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 F6 24 01 30 04 00")), Hex("CC 00 15 00"));
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 F6 24 00 30 04")), Hex("CC 00 08 00"));
}

}  // namespace
}  // namespace cip
