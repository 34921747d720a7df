// The whole core as the lwIP binding will drive it: bytes of a TCP stream or a UDP datagram in, exact
// bytes out, through encapsulation, Common Packet Format, message router and the objects.
#include "cip/cip_device.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "cip_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

class CipDeviceTest : public ::testing::Test {
 protected:
  CipDeviceTest() { id_ = card_.cip.encapsulation().OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(0x0A000202), 51000}, 0).value(); }

  Bytes Exchange(const Bytes& request) {
    const TcpStep step = card_.cip.encapsulation().OnTcpData(id_, request, 0);
    EXPECT_EQ(step.consumed, request.size());
    return Of(step.reply);
  }

  test::FakeCard card_;
  TcpConnectionId id_;
};

TEST_F(CipDeviceTest, GetVendorIdOverASession) {
  EXPECT_EQ(Exchange(Hex("65 00 04 00 00 00 00 00 00 00 00 00 C0 FF EE 00 00 00 00 00 00 00 00 00 01 00 00 00")),
            Hex("65 00 04 00 44 33 22 11 00 00 00 00 C0 FF EE 00 00 00 00 00 00 00 00 00 01 00 00 00"));
  EXPECT_EQ(Exchange(Hex("6F 00 18 00 44 33 22 11 00 00 00 00 C0 FF EE 00 00 00 00 00 00 00 00 00"
                         "| 00 00 00 00 | 05 00 | 02 00 | 00 00 00 00 | B2 00 08 00 | 0E 03 20 01 24 01 30 01")),
            Hex("6F 00 16 00 44 33 22 11 00 00 00 00 C0 FF EE 00 00 00 00 00 00 00 00 00"
                "| 00 00 00 00 | 00 00 | 02 00 | 00 00 00 00 | B2 00 06 00 | 8E 00 00 00 79 01"));
}

TEST_F(CipDeviceTest, UnconnectedSendWithAMultipleServicePacketInside) {
  (void)Exchange(Hex("65 00 04 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 01 00 00 00"));
  // Unconnected_Send (route 01 00) carrying MSP { Identity attr 1, Identity attr 9 }.
  const Bytes msp = Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00 | 0E 03 20 01 24 01 30 01 | 0E 03 20 01 24 01 30 09");
  Bytes ucs = Hex("52 02 20 06 24 01 0A F0 1C 00");
  ucs.insert(ucs.end(), msp.begin(), msp.end());
  const Bytes route = Hex("01 00 01 00");
  ucs.insert(ucs.end(), route.begin(), route.end());
  Bytes request = Hex("6F 00 00 00 44 33 22 11 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
                      "00 00 00 00 00 00 02 00 00 00 00 00 B2 00 00 00");
  request[2] = static_cast<std::uint8_t>(16 + ucs.size());
  request[38] = static_cast<std::uint8_t>(ucs.size());
  request.insert(request.end(), ucs.begin(), ucs.end());
  EXPECT_EQ(Exchange(request),
            Hex("6F 00 24 00 44 33 22 11 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
                "| 00 00 00 00 00 00 02 00 00 00 00 00 B2 00 14 00"
                "| 8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 79 01 8E 00 14 00"));
}

TEST_F(CipDeviceTest, BroadcastListIdentityFromTheRealObjects) {
  card_.device.model = DriveModel::kVfS15;
  card_.random.Push(0);  // no delay
  const Bytes request = Hex("63 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00");
  const UdpDecision decision =
      card_.cip.encapsulation().OnUdpDatagram(request, UdpSource{Ipv4Endpoint{base::Ipv4Address(0x0A000202), 2222}, true}, 5);
  ASSERT_EQ(decision.action, UdpDecision::Action::kSendLater);
  EXPECT_EQ(decision.send_at, 5U);
  DueDatagram due;
  ASSERT_TRUE(card_.cip.encapsulation().TakeDueDatagram(5, due));
  EXPECT_EQ(Of(due.bytes), Hex("63 00 2E 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
                               "| 01 00 0C 00 28 00 01 00 00 02 AF 12 0A 00 02 0F 00 00 00 00 00 00 00 00"
                               "| 79 01 02 00 01 7D 01 08 30 00 C0 02 7D F4 06 56 46 2D 53 31 35 FF"));
}

}  // namespace
}  // namespace cip
