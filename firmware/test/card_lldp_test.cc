// CardLldp on a CardNetif, CardAddressing and lwIP with a fake port: the card's LLDPDU carries the device
// name of the configuration and, once ACD has installed it, the address in use; a neighbour's LLDPDU is
// taken from the frame path with its port (lwIP never gets it) and lands in the agent's table; a port
// whose link goes down loses its neighbours and sends nothing.
#include <gtest/gtest.h>

#include "card_addressing_harness.h"
#include "card_lldp.h"
#include "net/lldp_frame.h"

namespace firmware::test {
namespace {

constexpr base::Ipv4Address kAddress(192, 168, 1, 12);

// What lldpd sends, written byte by byte: chassis by MAC, port by interface name "eth0", TTL 120, system
// name "peer", management address 192.168.1.1.
Bytes NeighbourLldpdu() {
  Bytes f;
  PutMac(f, {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E});
  PutMac(f, kOtherMac);
  Put16(f, 0x88CC);
  const Bytes tlvs = {0x02, 0x07, 0x04, 0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE,  // chassis: MAC
                      0x04, 0x05, 0x05, 'e', 't', 'h', '0',                   // port: interface name
                      0x06, 0x02, 0x00, 0x78,                                 // TTL 120
                      0x0A, 0x04, 'p', 'e', 'e', 'r',                         // system name
                      0x10, 0x0C, 0x05, 0x01, 192, 168, 1, 1, 0x02, 0, 0, 0, 2, 0x00,
                      0x00, 0x00};
  f.insert(f.end(), tlvs.begin(), tlvs.end());
  return f;
}

class CardLldpTest : public AddressingHarness {
 protected:
  CardLldpTest() { netif_.SetPortFrameHandler(&lldp_); }
  ~CardLldpTest() override { netif_.SetPortFrameHandler(nullptr); }

  // The LLDP frames the service sends when polled at `at` (after the loop's other work at that instant).
  std::vector<hal::test::FakeFramePort::Sent> LldpPollAt(Micros at) {
    Clock().Set(at);
    Step();
    lldp_.Poll(Now());
    std::vector<hal::test::FakeFramePort::Sent> lldp;
    for (auto& frame : port_.sent()) {
      if (frame.bytes.size() >= 14 && Get16(frame.bytes, 12) == 0x88CC) lldp.push_back(frame);
    }
    port_.sent().clear();
    return lldp;
  }

  CardLldp lldp_{netif_, addressing_, Clock(), "IPE002Z test"};
};

TEST_F(CardLldpTest, AdvertisesTheDeviceNameThenTheAddressOnceInUse) {
  config::CardConfig config = ModeConfig(config::IpMode::kManual, "drive-7");
  config.ip = kAddress;
  config.netmask = {255, 255, 255, 0};
  const Micros start = Now();
  ASSERT_TRUE(lldp_.Configure(config).ok());
  EXPECT_TRUE(LldpPollAt(start).empty());  // link seen now: the first frame waits a second

  const auto first = LldpPollAt(start + 1 * kSec);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].port, hal::PortId::kLeft);
  const base::Result<net::LldpNeighbourInfo> sent = net::ParseLldpFrame(first[0].bytes);
  ASSERT_TRUE(sent.ok());
  EXPECT_EQ(std::string(sent->system_name.view().begin(), sent->system_name.view().end()), "drive-7");
  EXPECT_TRUE(sent->management.IsUnspecified());  // no address yet

  ASSERT_TRUE(addressing_.Configure(config).ok());
  RunUntil(start + 2100 * kMs);  // ACD: probe wait <= 200 ms, 4 probes 200 ms apart, announce wait 200 ms
  ASSERT_EQ(LwipAddress(), kAddress.HostOrder());
  const auto change = LldpPollAt(start + 2100 * kMs);
  ASSERT_EQ(change.size(), 1u);
  EXPECT_EQ(net::ParseLldpFrame(change[0].bytes)->management, kAddress);
  EXPECT_EQ(lldp_.NextDeadline(), start + 32100 * kMs);
  EXPECT_EQ(lldp_.agent().counters().frames_out, 2u);
}

TEST_F(CardLldpTest, ANeighbourIsTakenWithItsPort_NotGivenToLwip_ForgottenAtLinkDown) {
  lldp_.Poll(Now());
  const std::uint64_t rx = netif_.counters().rx_frames;
  Receive(NeighbourLldpdu(), hal::PortId::kLeft);
  ASSERT_EQ(lldp_.agent().neighbours().size(), 1u);
  const net::LldpNeighbour& n = lldp_.agent().neighbours()[0];
  EXPECT_EQ(n.port, 0);
  EXPECT_EQ(n.info.management, base::Ipv4Address(192, 168, 1, 1));
  EXPECT_EQ(n.expires, Now() + 120 * kSec);
  EXPECT_EQ(netif_.counters().rx_frames, rx);
  hal::TextLine line;
  DescribeLldpId(n.info.chassis, true, line);
  line.Text(" ");
  DescribeLldpId(n.info.port, false, line);
  EXPECT_EQ(line.view(), "02:aa:bb:cc:dd:ee eth0");

  port_.SetLink(hal::PortId::kLeft, false);
  EXPECT_TRUE(LldpPollAt(Now() + 2 * kSec).empty());
  EXPECT_TRUE(lldp_.agent().neighbours().empty());
}

TEST(CardLldpText, BytesOutsidePrintableAsciiAreUnderscores) {
  const Bytes text = {'a', ' ', 'b', 0x00, 0xC3, 0xA9, '~'};
  hal::TextLine line;
  DescribeLldpText(text, line);
  EXPECT_EQ(line.view(), "a_b___~");
}

}  // namespace
}  // namespace firmware::test
