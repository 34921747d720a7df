// firmware::EipService on lwIP: TCP and UDP clients written on lwIP's raw API talk to a CipDevice on
// fakes (tests/unit/cip_fakes.h) through the lwIP binding, over two netifs wired back to back
// (lwip_tcp_pair.h). Exact bytes; the protocol rules themselves are the core's tests.
#include "eip_service.h"

#include <gtest/gtest.h>

#include "cip_fakes.h"
#include "cip_test_support.h"
#include "lwip/timeouts.h"
#include "lwip_tcp_pair.h"

namespace firmware {
namespace {

using cip::test::Concat;
using cip::test::Hex;
using test::Bytes;
using test::TcpTestClient;
using test::UdpTestPeer;

constexpr std::uint16_t kPort = 44818;

// An encapsulation header: command, length, session handle, status 0, sender context, options 0.
Bytes Header(std::uint16_t command, std::uint16_t length, std::uint32_t session,
             const char* context = "01 02 03 04 05 06 07 08") {
  Bytes header = {static_cast<std::uint8_t>(command),  static_cast<std::uint8_t>(command >> 8),
                  static_cast<std::uint8_t>(length),   static_cast<std::uint8_t>(length >> 8),
                  static_cast<std::uint8_t>(session),  static_cast<std::uint8_t>(session >> 8),
                  static_cast<std::uint8_t>(session >> 16), static_cast<std::uint8_t>(session >> 24),
                  0, 0, 0, 0};
  return Concat(Concat(header, Hex(context)), Hex("00 00 00 00"));
}

const Bytes kRegisterSession = Concat(Header(0x65, 4, 0), Hex("01 00 00 00"));
const Bytes kRegistered =
    Hex("65 00 04 00 | 44 33 22 11 | 00 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 00 | 01 00 00 00");
const Bytes kListServices = Header(0x04, 0, 0);
const Bytes kServicesReply = Concat(Header(0x04, 0x1A, 0),
                                    Hex("01 00 | 00 01 14 00 01 00 20 01 | 43 6F 6D 6D 75 6E 69 63 61 74 69 6F 6E 73 00 00"));

class EipServiceTest : public test::LwipPairTest {
 protected:
  void SetUp() override {
    StartNetifs();
    config_.protocol = drive_link::Protocol::kEtherNetIp;
    ASSERT_TRUE(service_.Configure(config_).ok());
    Pump();
  }
  void TearDown() override {
    CloseClients();
    service_.Stop();
  }
  void PollServices() override { service_.Poll(clock().NowMicros()); }

  // Lets `ms` of lwIP timers (retransmission, persist, refused data) run, pumping as they go.
  void RunTimers(int ms) {
    for (int t = 0; t < ms; t += 50) {
      clock().Advance(50 * hal::kMicrosPerMilli);
      sys_check_timeouts();
      Pump();
    }
  }

  drive_link::CardConfig config_;
  cip::test::FakeCard card_;
  EipService service_{card_.cip.encapsulation(), clock()};
};

TEST_F(EipServiceTest, RegisterSession_ExactReply) {
  TcpTestClient& client = Connect(kPort);
  ASSERT_TRUE(client.connected);
  Send(client, kRegisterSession);
  EXPECT_EQ(client.received, kRegistered);
  EXPECT_EQ(card_.cip.encapsulation().session_count(), 1u);
  EXPECT_EQ(service_.counters().accepted, 1u);
}

TEST_F(EipServiceTest, TwoMessagesInOneSegment_BothAnswered) {
  TcpTestClient& client = Connect(kPort);
  Send(client, Concat(kListServices, kListServices));
  EXPECT_EQ(client.received, Concat(kServicesReply, kServicesReply));
}

TEST_F(EipServiceTest, MessageSplitAcrossSegments_AnsweredOnceComplete) {
  TcpTestClient& client = Connect(kPort);
  Send(client, Bytes(kRegisterSession.begin(), kRegisterSession.begin() + 10));
  EXPECT_TRUE(client.received.empty());
  Send(client, Bytes(kRegisterSession.begin() + 10, kRegisterSession.end()));
  EXPECT_EQ(client.received, kRegistered);
}

TEST_F(EipServiceTest, ClientStopsReading_NothingLostWhenItReadsAgain) {
  TcpTestClient& client = Connect(kPort);
  client.reading = false;
  // 100 requests of 24 bytes fit the card's window; their 100 replies (50 bytes each) do not fit the
  // client's window plus the card's send buffer, so the card must hold input back.
  Bytes requests;
  for (int i = 0; i < 100; ++i) requests = Concat(requests, kListServices);
  Send(client, requests);
  RunTimers(2000);
  EXPECT_LT(client.received.size(), 100 * kServicesReply.size());
  client.reading = true;
  RunTimers(20000);
  ASSERT_EQ(client.received.size(), 100 * kServicesReply.size());
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(Bytes(client.received.begin() + i * static_cast<long>(kServicesReply.size()),
                    client.received.begin() + (i + 1) * static_cast<long>(kServicesReply.size())),
              kServicesReply)
        << i;
  }
}

TEST_F(EipServiceTest, UnRegisterSession_CardClosesTheConnection) {
  TcpTestClient& client = Connect(kPort);
  Send(client, kRegisterSession);
  Send(client, Header(0x66, 0, 0x11223344));
  EXPECT_TRUE(client.peer_closed);
  EXPECT_EQ(card_.cip.encapsulation().session_count(), 0u);
  EXPECT_EQ(service_.counters().closed_by_card, 1u);
}

TEST_F(EipServiceTest, PeerCloses_SessionEnds) {
  TcpTestClient& client = Connect(kPort);
  Send(client, kRegisterSession);
  ASSERT_EQ(tcp_close(client.pcb), ERR_OK);
  client.pcb = nullptr;
  Pump();
  EXPECT_EQ(card_.cip.encapsulation().session_count(), 0u);
  EXPECT_EQ(card_.cip.encapsulation().connection_count(), 0u);
  EXPECT_EQ(service_.counters().closed_by_peer, 1u);
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{0, cip::kMaxTcpConnections, 1, 0}));
  EXPECT_EQ(card_.cip.encapsulation().session_pool(), (base::PoolStats{0, cip::kMaxSessions, 1, 0}));
}

TEST_F(EipServiceTest, ConnectionBeyondTheLimit_ResetOthersStillServed) {
  std::vector<TcpTestClient*> open;
  for (std::size_t i = 0; i < cip::kMaxTcpConnections; ++i) {
    open.push_back(&Connect(kPort));
    ASSERT_TRUE(open.back()->connected) << i;
  }
  TcpTestClient& extra = Connect(kPort);
  EXPECT_TRUE(extra.reset);
  EXPECT_EQ(service_.counters().refused, 1u);
  constexpr std::size_t kMax = cip::kMaxTcpConnections;
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  // The binding refused it before the core was asked.
  EXPECT_EQ(card_.cip.encapsulation().connection_pool(), (base::PoolStats{kMax, kMax, kMax, 0}));
  Send(*open.front(), kListServices);
  EXPECT_EQ(open.front()->received, kServicesReply);
}

TEST_F(EipServiceTest, UnicastUdpListServices_AnsweredToTheSender) {
  UdpTestPeer& peer = OpenUdp(50000);
  SendTo(peer, test::kCardIp, kPort, kListServices);
  ASSERT_EQ(peer.received.size(), 1u);
  EXPECT_EQ(peer.received[0].bytes, kServicesReply);
  EXPECT_EQ(peer.received[0].from_port, kPort);
}

TEST_F(EipServiceTest, BroadcastListIdentity_SentWhenItsDelayIsDue) {
  UdpTestPeer& peer = OpenUdp(50001);
  // Maximum delay 500 ms (sender context bytes 0-1 = 0x01F4); the random draw 0x11223344 % 500001 µs.
  SendTo(peer, 0xC0A801FF, kPort, Header(0x63, 0, 0, "F4 01 00 00 00 00 00 00"));
  EXPECT_TRUE(peer.received.empty());
  const hal::Micros due = service_.NextDeadline();
  ASSERT_NE(due, hal::kNever);
  EXPECT_LE(due, clock().NowMicros() + 500 * hal::kMicrosPerMilli);
  clock().Set(due);
  Pump();
  ASSERT_EQ(peer.received.size(), 1u);
  const Bytes& reply = peer.received[0].bytes;
  EXPECT_EQ(Bytes(reply.begin(), reply.begin() + 2), Hex("63 00"));
  EXPECT_EQ(Bytes(reply.begin() + 12, reply.begin() + 20), Hex("F4 01 00 00 00 00 00 00"));
}

TEST_F(EipServiceTest, ModbusConfiguration_ClosesBothPorts) {
  TcpTestClient& before = Connect(kPort);
  ASSERT_TRUE(before.connected);
  config_.protocol = drive_link::Protocol::kModbusTcp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  Pump();
  EXPECT_FALSE(service_.listening());
  EXPECT_TRUE(before.reset);
  TcpTestClient& after = Connect(kPort);
  EXPECT_TRUE(after.reset);
  UdpTestPeer& peer = OpenUdp(50002);
  SendTo(peer, test::kCardIp, kPort, kListServices);
  EXPECT_TRUE(peer.received.empty());
  EXPECT_EQ(card_.cip.encapsulation().connection_count(), 0u);
}

TEST_F(EipServiceTest, EtherNetIpConfigurationAgain_OpensThePorts) {
  config_.protocol = drive_link::Protocol::kModbusTcp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  config_.protocol = drive_link::Protocol::kEtherNetIp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  EXPECT_TRUE(service_.listening());
  TcpTestClient& client = Connect(kPort);
  Send(client, kListServices);
  EXPECT_EQ(client.received, kServicesReply);
}

}  // namespace
}  // namespace firmware
