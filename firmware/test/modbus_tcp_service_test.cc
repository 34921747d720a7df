// firmware::ModbusTcpService on lwIP: a Modbus client written on lwIP's raw TCP API talks to the card
// over two netifs wired back to back (lwip_tcp_pair.h).
#include "modbus_tcp_service.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "lwip_tcp_pair.h"
#include "modbus_fakes.h"

namespace firmware {
namespace {

using modbus::test::Bytes;
using TestClient = test::TcpTestClient;

const Bytes kReadVersion = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
const Bytes kVersionAnswer = {0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0xFB, 0x03, 0x02, 0x01, 0x06};

class ModbusTcpServiceTest : public test::LwipPairTest {
 protected:
  void SetUp() override {
    StartNetifs();
    ASSERT_TRUE(service_.Configure(config_).ok());
    Pump();
  }
  void TearDown() override {
    CloseClients();
    service_.Stop();
  }
  void PollServices() override { service_.Poll(clock().NowMicros()); }

  TestClient& Connect() { return LwipPairTest::Connect(502); }

  config::CardConfig config_;
  modbus::test::ServerHarness h_{[] {
    modbus::ServerOptions options;
    options.idle_timeout = 10 * hal::kMicrosPerSecond;
    return options;
  }()};
  ModbusTcpService service_{h_.server, clock()};
};

TEST_F(ModbusTcpServiceTest, ReadBoardRegister_ExactAnswer) {
  TestClient& client = Connect();
  ASSERT_TRUE(client.connected);
  Send(client, kReadVersion);
  EXPECT_EQ(client.received, kVersionAnswer);
  EXPECT_EQ(service_.counters().accepted, 1u);
}

TEST_F(ModbusTcpServiceTest, DriveRead_AnsweredOnThePassAfterTheCompletion) {
  h_.drive.registers = {{0x0009, 100}};
  TestClient& client = Connect();
  Send(client, {0x00, 0x07, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x09, 0x00, 0x01});
  EXPECT_TRUE(client.received.empty());
  h_.drive.Poll();
  EXPECT_EQ(service_.NextDeadline(), 0u);  // an answer is waiting: the loop must come back at once
  Pump();
  EXPECT_EQ(client.received, (Bytes{0x00, 0x07, 0x00, 0x00, 0x00, 0x05, 0x01, 0x03, 0x02, 0x00, 0x64}));
  EXPECT_NE(service_.NextDeadline(), 0u);
}

TEST_F(ModbusTcpServiceTest, TwoRequestsInOneSegment_BothAnswered) {
  TestClient& client = Connect();
  Bytes two = kReadVersion;
  two.insert(two.end(), kReadVersion.begin(), kReadVersion.end());
  Send(client, two);
  Bytes expected = kVersionAnswer;
  expected.insert(expected.end(), kVersionAnswer.begin(), kVersionAnswer.end());
  EXPECT_EQ(client.received, expected);
}

TEST_F(ModbusTcpServiceTest, TwentyPipelinedRequests_AllAnsweredInOrder) {
  TestClient& client = Connect();
  Bytes requests;
  Bytes expected;
  for (std::uint8_t i = 0; i < 20; ++i) {
    Bytes request = kReadVersion;
    request[1] = i;
    requests.insert(requests.end(), request.begin(), request.end());
    Bytes answer = kVersionAnswer;
    answer[1] = i;
    expected.insert(expected.end(), answer.begin(), answer.end());
  }
  Send(client, requests);
  EXPECT_EQ(client.received, expected);
}

TEST_F(ModbusTcpServiceTest, ThreeLargestAdus_MoreThanAWindow_AllAnsweredInOrder) {
  TestClient& client = Connect();
  // Three 260-byte ADUs (MBAP length 254, the largest; unit 1, function 0: exception 01) = 780 bytes: more
  // than the card's window and receive buffer (TCP_WND = kReceiveBufferBytes = 536). The window holds two
  // and part of the third; answering the two frees more than half a window, so lwIP reopens it.
  static_assert(3 * modbus::kMaxAduBytes > TCP_WND);
  Bytes requests;
  Bytes expected;
  for (std::uint8_t i = 1; i <= 3; ++i) {
    Bytes adu = {0x00, i, 0x00, 0x00, 0x00, 254, 0x01, 0x00};
    adu.resize(modbus::kMaxAduBytes, 0x00);
    requests.insert(requests.end(), adu.begin(), adu.end());
    const Bytes answer = {0x00, i, 0x00, 0x00, 0x00, 0x03, 0x01, 0x80, 0x01};
    expected.insert(expected.end(), answer.begin(), answer.end());
  }
  Send(client, requests);
  EXPECT_EQ(client.received, expected);
}

TEST_F(ModbusTcpServiceTest, NinthClient_ResetOthersStillServed) {
  // Eight clients, each served. The unit tests' lwIP gives the clients' PCBs from the card's own pool
  // (lwipopts.h: 8 Modbus + 3 HTTP + 3 spare PCBs for the card alone), so seven of them are frozen: their
  // connections stay open on the card and the test speaks to them in raw frames.
  std::vector<test::FrozenTcpClient> frozen;
  TestClient* live = nullptr;
  for (std::size_t i = 0; i < modbus::Server::kMaxClients; ++i) {
    TestClient& client = Connect();
    ASSERT_TRUE(client.connected) << i;
    Send(client, kReadVersion);
    ASSERT_EQ(client.received, kVersionAnswer) << i;
    if (i + 1 < modbus::Server::kMaxClients) {
      frozen.push_back(Freeze(client));
    } else {
      live = &client;
    }
  }
  TestClient& ninth = Connect();
  EXPECT_TRUE(ninth.reset);
  EXPECT_EQ(service_.counters().refused, 1u);
  EXPECT_EQ(h_.server.open_connections(), modbus::Server::kMaxClients);
  constexpr std::size_t kMax = modbus::Server::kMaxClients;
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  // The service asks the server first: the server's table is what refused the ninth.
  EXPECT_EQ(h_.server.client_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  for (std::size_t i = 0; i < frozen.size(); ++i) EXPECT_EQ(ExchangeFrozen(frozen[i], kReadVersion), kVersionAnswer) << i;
  EXPECT_FALSE(live->reset);
  Send(*live, kReadVersion);
  Bytes twice = kVersionAnswer;
  twice.insert(twice.end(), kVersionAnswer.begin(), kVersionAnswer.end());
  EXPECT_EQ(live->received, twice);
  EXPECT_EQ(service_.counters().lost, 0u);
  EXPECT_EQ(service_.counters().closed_by_peer, 0u);
}

TEST_F(ModbusTcpServiceTest, ClientCloses_SlotFreed) {
  TestClient& client = Connect();
  Send(client, kReadVersion);
  ASSERT_EQ(tcp_close(client.pcb), ERR_OK);
  client.pcb = nullptr;
  Pump();
  EXPECT_EQ(h_.server.open_connections(), 0u);
  EXPECT_EQ(service_.counters().closed_by_peer, 1u);
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{0, modbus::Server::kMaxClients, 1, 0}));
  EXPECT_EQ(h_.server.client_pool(), (base::PoolStats{0, modbus::Server::kMaxClients, 1, 0}));
}

TEST_F(ModbusTcpServiceTest, BadHeader_EarlierAnswerThenFin) {
  TestClient& client = Connect();
  Bytes stream = kReadVersion;
  const Bytes bad = {0x00, 0x02, 0x00, 0x07, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
  stream.insert(stream.end(), bad.begin(), bad.end());
  Send(client, stream);
  EXPECT_EQ(client.received, kVersionAnswer);
  EXPECT_TRUE(client.peer_closed);
  EXPECT_FALSE(client.reset);
  EXPECT_EQ(service_.counters().closed_by_card, 1u);
  EXPECT_EQ(h_.server.open_connections(), 0u);
}

TEST_F(ModbusTcpServiceTest, IdleClient_ClosedWithFin) {
  TestClient& client = Connect();
  Send(client, kReadVersion);
  clock().Advance(10 * hal::kMicrosPerSecond);
  Pump();
  EXPECT_TRUE(client.peer_closed);
  EXPECT_EQ(h_.server.counters().idle_closes, 1u);
  EXPECT_EQ(h_.server.open_connections(), 0u);
}

TEST_F(ModbusTcpServiceTest, EtherNetIpSelected_PortClosedAndClientsReset) {
  TestClient& client = Connect();
  config::CardConfig ethernet_ip = config_;
  ethernet_ip.protocol = config::Protocol::kEtherNetIp;
  ASSERT_TRUE(service_.Configure(ethernet_ip).ok());
  Pump();
  EXPECT_FALSE(service_.listening());
  EXPECT_TRUE(client.reset);
  EXPECT_EQ(h_.server.open_connections(), 0u);
  // Nobody listens: lwIP answers the SYN with RST.
  TestClient& refused = Connect();
  EXPECT_FALSE(refused.connected);
  EXPECT_TRUE(refused.reset);
  // Back to Modbus TCP.
  ASSERT_TRUE(service_.Configure(config_).ok());
  TestClient& again = Connect();
  ASSERT_TRUE(again.connected);
  Send(again, kReadVersion);
  EXPECT_EQ(again.received, kVersionAnswer);
}

TEST_F(ModbusTcpServiceTest, StartTwice_OneListener) {
  EXPECT_TRUE(service_.Start().ok());
  EXPECT_TRUE(service_.listening());
  TestClient& client = Connect();
  EXPECT_TRUE(client.connected);
}

}  // namespace
}  // namespace firmware
