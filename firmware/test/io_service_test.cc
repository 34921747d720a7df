// IoService: the connection manager's class 1 I/O bound to lwIP UDP 2222, between two lwIP stacks on
// fake frame ports: O->T datagrams reach the manager, productions leave when due (point-to-point to the
// originator, multicast with the TTL of TCP/IP attribute 8), c500 opens and closes the port.
#include "io_service.h"

#include <gtest/gtest.h>

#include "cip_connection_fakes.h"
#include "lwip_tcp_pair.h"

namespace firmware {
namespace {

using cip::test::Bytes;
using cip::test::ConnectionCard;
using cip::test::Hex;
using cip::test::IoDatagramBytes;
using cip::test::OpenParams;
using test::UdpTestPeer;

class FixedTtl final : public MulticastTtlSource {
 public:
  std::uint8_t MulticastTtl() const override { return ttl; }
  std::uint8_t ttl = 5;
};

constexpr std::uint16_t kPeerPort = 40001;

class IoServiceTest : public test::LwipPairTest {
 protected:
  void SetUp() override {
    StartNetifs();
    config_.protocol = config::Protocol::kEtherNetIp;
    ASSERT_TRUE(service_.Configure(config_).ok());
    Pump();
  }
  void TearDown() override {
    CloseClients();
    service_.Stop();
  }
  void PollServices() override { service_.Poll(clock().NowMicros()); }

  // A Forward_Open from the peer's address, as the encapsulation layer would hand it over. Its T->O
  // socket address item names kPeerPort: both lwIP stacks share one PCB table, where the card's PCB
  // holds port 2222 on every address.
  Bytes Open(const OpenParams& params = {}) {
    Bytes reply(cip::kMaxEncapsulationData);
    cip::RequestContext context;
    context.now = clock().NowMicros();
    context.session_handle = cip::test::kSession;
    context.peer = cip::Ipv4Endpoint{base::Ipv4Address(test::kPeerIp), 50000};
    context.request_t_to_o = cip::SocketAddress{cip::SocketAddress::kAfInet, kPeerPort, test::kPeerIp};
    reply.resize(card_.card.cip.router().HandleUnconnected(cip::test::ForwardOpenRequestBytes(params), context, reply));
    return reply;
  }

  config::CardConfig config_;
  ConnectionCard card_;
  FixedTtl ttl_;
  IoService service_{card_.cm, clock(), ttl_};
};

TEST_F(IoServiceTest, ProductionsCarryTheDscpOfTheirPriority) {
  UdpTestPeer& peer = OpenUdp(kPeerPort);
  ASSERT_EQ(Open().at(2), 0x00);  // T->O priority scheduled
  Pump();
  ASSERT_EQ(peer.received.size(), 1U);
  EXPECT_EQ(peer.received[0].tos, 0x00);  // no QoS values given: unmarked

  cip::QosSettings qos;
  service_.set_qos(&qos);
  clock().Advance(10000);
  Pump();
  ASSERT_EQ(peer.received.size(), 2U);
  EXPECT_EQ(peer.received[1].tos, 47 << 2);  // DSCP Scheduled, default 47

  qos.values[static_cast<std::size_t>(cip::QosAttribute::kDscpScheduled) - 1] = 20;
  OpenParams urgent = cip::test::InputOnly151(2);
  urgent.t_to_o.priority = cip::ConnectionPriority::kUrgent;
  ASSERT_EQ(Open(urgent).at(2), 0x00);
  Pump();
  ASSERT_EQ(peer.received.size(), 3U);
  EXPECT_EQ(peer.received[2].tos, 55 << 2);  // DSCP Urgent
  clock().Advance(10000);
  Pump();
  ASSERT_GE(peer.received.size(), 4U);
  EXPECT_EQ(peer.received[3].tos, 20 << 2);  // the scheduled connection with the new value
}

TEST_F(IoServiceTest, OutputDatagramsReachTheManagerAndProductionsTheOriginator) {
  UdpTestPeer& peer = OpenUdp(kPeerPort);
  const Bytes reply = Open();
  ASSERT_EQ(reply.at(2), 0x00);
  const std::uint32_t o_to_t = ConnectionCard::OtoTId(reply);

  // The first production is due at once: T->O ID 0x20000001 (the originator's), encapsulation sequence
  // 1, CIP sequence 1, the 6 bytes of 150 as FakeIo produces them (150 + i).
  Pump();
  ASSERT_EQ(peer.received.size(), 1U);
  EXPECT_EQ(peer.received[0].from_port, cip::kIoPort);
  EXPECT_EQ(peer.received[0].bytes, Hex("02 00 | 02 80 08 00 01 00 00 20 01 00 00 00 | B1 00 08 00 01 00 96 97 98 99 9A 9B"));
  EXPECT_EQ(service_.counters().sent, 1U);

  // Nothing before the next slot; the next one 10 ms later.
  clock().Advance(9999);
  Pump();
  EXPECT_EQ(peer.received.size(), 1U);
  clock().Advance(1);
  Pump();
  ASSERT_EQ(peer.received.size(), 2U);
  EXPECT_EQ(peer.received[1].bytes, Hex("02 00 | 02 80 08 00 01 00 00 20 02 00 00 00 | B1 00 08 00 02 00 96 97 98 99 9A 9B"));

  SendTo(peer, test::kCardIp, cip::kIoPort, IoDatagramBytes(o_to_t, 1, 1, true, Hex("11 22 33 44 55 66 77 88")));
  ASSERT_EQ(card_.io.consumed.size(), 1U);
  EXPECT_EQ(card_.io.consumed[0].point, 100U);
  EXPECT_EQ(card_.io.consumed[0].data, Hex("11 22 33 44 55 66 77 88"));
  EXPECT_TRUE(card_.io.consumed[0].run);
  EXPECT_EQ(service_.counters().received, 1U);
}

TEST_F(IoServiceTest, OverlongDatagramIsDroppedHere) {
  UdpTestPeer& peer = OpenUdp(40000);
  SendTo(peer, test::kCardIp, cip::kIoPort, Bytes(cip::kMaxIoDatagram + 1, 0x00));
  EXPECT_EQ(service_.counters().received, 1U);
  EXPECT_EQ(service_.counters().too_long, 1U);
  EXPECT_EQ(card_.cm.dropped_datagrams(), 0U);
  // kMaxIoDatagram (56) bytes go to the manager, which drops what it cannot use (no such connection).
  SendTo(peer, test::kCardIp, cip::kIoPort, Bytes(cip::kMaxIoDatagram, 0x00));
  EXPECT_EQ(service_.counters().too_long, 1U);
  EXPECT_EQ(card_.cm.dropped_datagrams(), 1U);
  // So does a short one.
  SendTo(peer, test::kCardIp, cip::kIoPort, Hex("02 00"));
  EXPECT_EQ(card_.cm.dropped_datagrams(), 2U);
}

TEST_F(IoServiceTest, MulticastProductionsCarryTheConfiguredTtl) {
  OpenParams params;
  params.t_to_o.type = cip::ConnectionType::kMulticast;
  ASSERT_EQ(Open(params).at(2), 0x00);
  card_port_.sent().clear();
  service_.Poll(clock().NowMicros());
  ASSERT_EQ(card_port_.sent().size(), 1U);
  const Bytes& frame = card_port_.sent()[0].bytes;
  // Ethernet: 01:00:5E + the group's low 23 bits (239.192.1.32); IPv4 TTL (byte 8 of the header) 5;
  // destination 239.192.1.32; UDP destination port 2222.
  ASSERT_GE(frame.size(), 42U);
  EXPECT_EQ(Bytes(frame.begin(), frame.begin() + 6), Hex("01 00 5E 40 01 20"));
  EXPECT_EQ(frame[14 + 8], 5);
  EXPECT_EQ(Bytes(frame.begin() + 30, frame.begin() + 34), Hex("EF C0 01 20"));
  EXPECT_EQ(Bytes(frame.begin() + 36, frame.begin() + 38), Hex("08 AE"));
}

TEST_F(IoServiceTest, ModbusConfigurationClosesThePort) {
  UdpTestPeer& peer = OpenUdp(kPeerPort);
  const Bytes reply = Open();
  const std::uint32_t o_to_t = ConnectionCard::OtoTId(reply);
  config_.protocol = config::Protocol::kModbusTcp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  EXPECT_FALSE(service_.running());
  Pump();
  EXPECT_TRUE(peer.received.empty());  // the due production is taken, not sent
  SendTo(peer, test::kCardIp, cip::kIoPort, IoDatagramBytes(o_to_t, 1, 1, true, Hex("11 22 33 44 55 66 77 88")));
  EXPECT_TRUE(card_.io.consumed.empty());
  EXPECT_EQ(service_.counters().received, 0U);

  config_.protocol = config::Protocol::kEtherNetIp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  EXPECT_TRUE(service_.running());
}

}  // namespace
}  // namespace firmware
