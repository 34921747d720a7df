// firmware::EipService on lwIP: TCP and UDP clients written on lwIP's raw API talk to a CipDevice on
// fakes (cip/test/cip_fakes.h) through the lwIP binding, over two netifs wired back to back
// (lwip_tcp_pair.h). Exact bytes; the protocol rules themselves are the core's tests.
#include "eip_service.h"

#include <gtest/gtest.h>

#include "cip_fakes.h"
#include "cip_test_support.h"
#include "lwip/pbuf.h"
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
    config_.protocol = config::Protocol::kEtherNetIp;
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

  // Writes whole copies of `request`, at most `count`, as far as the client's send buffer takes them;
  // returns how many.
  std::size_t WriteWhatFits(TcpTestClient& client, const Bytes& request, std::size_t count) {
    std::size_t written = 0;
    while (written < count && tcp_sndbuf(client.pcb) >= request.size() &&
           tcp_sndqueuelen(client.pcb) + 1 < TCP_SND_QUEUELEN &&
           tcp_write(client.pcb, request.data(), static_cast<u16_t>(request.size()), TCP_WRITE_FLAG_COPY) == ERR_OK) {
      ++written;
    }
    EXPECT_EQ(tcp_output(client.pcb), ERR_OK);
    Pump();
    return written;
  }

  config::CardConfig config_;
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
  // 24-byte requests, as many as the client's send buffer takes, until TCP stops taking them: the card's
  // replies (50 bytes each) are not acknowledged, so its send buffer fills (no more room for a largest
  // reply), then it holds input back and its window (TCP_WND) closes.
  constexpr std::size_t kRequests = 100;
  std::size_t sent = 0;
  for (int round = 0; round < 50 && sent < kRequests; ++round) {
    const std::size_t written = WriteWhatFits(client, kListServices, kRequests - sent);
    if (written == 0) break;
    sent += written;
  }
  RunTimers(2000);
  EXPECT_TRUE(client.received.empty());
  // More requests than replies the card can have unacknowledged while it still has room for a largest one.
  EXPECT_GT(sent * kServicesReply.size(), static_cast<std::size_t>(TCP_SND_BUF) - cip::kMaxReplyMessage);
  EXPECT_LT(sent, kRequests);  // TCP stopped the client
  client.reading = true;
  for (int round = 0; round < 200 && sent < kRequests; ++round) {
    sent += WriteWhatFits(client, kListServices, kRequests - sent);
    RunTimers(250);
  }
  ASSERT_EQ(sent, kRequests);
  RunTimers(20000);
  ASSERT_EQ(client.received.size(), kRequests * kServicesReply.size());
  for (std::size_t i = 0; i < kRequests; ++i) {
    EXPECT_EQ(Bytes(client.received.begin() + static_cast<long>(i * kServicesReply.size()),
                    client.received.begin() + static_cast<long>((i + 1) * kServicesReply.size())),
              kServicesReply)
        << i;
  }
}

TEST_F(EipServiceTest, HeapExhausted_ReplyHeldAndNoConnectionFedUntilItIsWritten) {
  TcpTestClient& first = Connect(kPort);
  TcpTestClient& second = Connect(kPort);
  // Both requests are on their way (in the clients' send queues and on the wire) before lwIP's heap runs
  // out, so the card receives them with no heap left for its replies.
  for (TcpTestClient* client : {&first, &second}) {
    ASSERT_EQ(tcp_write(client->pcb, kListServices.data(), static_cast<u16_t>(kListServices.size()),
                        TCP_WRITE_FLAG_COPY),
              ERR_OK);
    ASSERT_EQ(tcp_output(client->pcb), ERR_OK);
  }
  std::vector<pbuf*> hog;
  for (u16_t size = 1024; size >= 16; size = static_cast<u16_t>(size / 2)) {
    while (pbuf* p = pbuf_alloc(PBUF_RAW, size, PBUF_RAM)) hog.push_back(p);
  }
  Pump();
  // The first reply could not be written: it is held, and no connection is fed meanwhile.
  EXPECT_EQ(service_.counters().write_stalls, 1u);
  EXPECT_TRUE(first.received.empty());
  EXPECT_TRUE(second.received.empty());
  for (pbuf* p : hog) pbuf_free(p);
  RunTimers(1000);
  EXPECT_EQ(first.received, kServicesReply);
  EXPECT_EQ(second.received, kServicesReply);
  EXPECT_EQ(service_.counters().write_stalls, 1u);
}

TEST_F(EipServiceTest, LargestMessageArrivesThroughTheWindow_OneByteMoreIs0x0002) {
  TcpTestClient& client = Connect(kPort);
  // SendRRData with 600 bytes of data (kMaxEncapsulationData) and no session: 624 bytes, more than one
  // window (TCP_WND 536), so the card's window must reopen before the message is whole. The core takes it
  // and answers 0x0064 (invalid session handle), header only.
  static_assert(cip::kMaxEncapsulationMessage > TCP_WND);
  Bytes largest = Header(0x6F, cip::kMaxEncapsulationData, 0);
  largest.resize(cip::kMaxEncapsulationMessage, 0x00);
  Send(client, largest);
  EXPECT_EQ(client.received,
            Hex("6F 00 00 00 | 00 00 00 00 | 64 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 00"));
  // One byte more: the message cannot be buffered; its body is counted off and it is answered 0x0002
  // (insufficient memory), and the connection stays usable.
  client.received.clear();
  Bytes beyond = Header(0x6F, cip::kMaxEncapsulationData + 1, 0);
  beyond.resize(cip::kMaxEncapsulationMessage + 1, 0x00);
  Send(client, beyond);
  EXPECT_EQ(client.received,
            Hex("6F 00 00 00 | 00 00 00 00 | 02 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 00"));
  client.received.clear();
  Send(client, kListServices);
  EXPECT_EQ(client.received, kServicesReply);
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
  // Every connection slot taken, each connection served. The unit tests' lwIP gives the clients' PCBs from
  // the card's own pool (lwipopts.h: 9 connections + 3 HTTP + 3 spare PCBs for the card alone), so all but
  // one are frozen: their connections stay open on the card and the test speaks to them in raw frames.
  std::vector<test::FrozenTcpClient> frozen;
  TcpTestClient* live = nullptr;
  for (std::size_t i = 0; i < cip::kMaxTcpConnections; ++i) {
    TcpTestClient& client = Connect(kPort);
    ASSERT_TRUE(client.connected) << i;
    Send(client, kListServices);
    ASSERT_EQ(client.received, kServicesReply) << i;
    if (i + 1 < cip::kMaxTcpConnections) {
      frozen.push_back(Freeze(client));
    } else {
      live = &client;
    }
  }
  TcpTestClient& extra = Connect(kPort);
  EXPECT_TRUE(extra.reset);
  EXPECT_EQ(service_.counters().refused, 1u);
  constexpr std::size_t kMax = cip::kMaxTcpConnections;
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  // The binding refused it before the core was asked.
  EXPECT_EQ(card_.cip.encapsulation().connection_pool(), (base::PoolStats{kMax, kMax, kMax, 0}));
  for (std::size_t i = 0; i < frozen.size(); ++i) EXPECT_EQ(ExchangeFrozen(frozen[i], kListServices), kServicesReply) << i;
  Send(*live, kListServices);
  EXPECT_EQ(live->received, Concat(kServicesReply, kServicesReply));
  EXPECT_EQ(service_.counters().lost, 0u);
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
  config_.protocol = config::Protocol::kModbusTcp;
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
  config_.protocol = config::Protocol::kModbusTcp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  config_.protocol = config::Protocol::kEtherNetIp;
  ASSERT_TRUE(service_.Configure(config_).ok());
  EXPECT_TRUE(service_.listening());
  TcpTestClient& client = Connect(kPort);
  Send(client, kListServices);
  EXPECT_EQ(client.received, kServicesReply);
}

}  // namespace
}  // namespace firmware
