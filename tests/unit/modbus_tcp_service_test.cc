// firmware::ModbusTcpService on lwIP: a Modbus client written on lwIP's raw TCP API, inside the same
// lwIP instance, talks to the card over two netifs whose frame ports are wired back to back (a peer
// at 192.168.1.30 and the card at 192.168.1.12). The client's PCB is bound to the peer's netif
// (tcp_bind_netif); the card's PCBs route through the card's netif, the first in lwIP's list.
#include "modbus_tcp_service.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "card_netif.h"
#include "fake_frame_port.h"
#include "lwip/tcp.h"
#include "lwip_fixture.h"
#include "modbus_fakes.h"

namespace firmware {
namespace {

using modbus::test::Bytes;

constexpr hal::MacAddress kPeerMac = {0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
constexpr hal::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
constexpr std::uint32_t kCardIp = 0xC0A8010C;  // 192.168.1.12
constexpr std::uint32_t kPeerIp = 0xC0A8011E;  // 192.168.1.30

const Bytes kReadVersion = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
const Bytes kVersionAnswer = {0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0xFB, 0x03, 0x02, 0x01, 0x06};

// A Modbus TCP client on lwIP's raw API.
struct TestClient {
  tcp_pcb* pcb = nullptr;
  bool connected = false;
  bool reset = false;       // the err callback ran (RST or abort): the PCB is gone
  bool peer_closed = false;  // FIN from the card
  Bytes received;

  static err_t OnConnected(void* arg, tcp_pcb*, err_t) {
    static_cast<TestClient*>(arg)->connected = true;
    return ERR_OK;
  }
  static err_t OnRecv(void* arg, tcp_pcb* pcb, pbuf* p, err_t) {
    auto* self = static_cast<TestClient*>(arg);
    if (p == nullptr) {
      self->peer_closed = true;
      return ERR_OK;
    }
    for (const pbuf* q = p; q != nullptr; q = q->next) {
      const auto* bytes = static_cast<const std::uint8_t*>(q->payload);
      self->received.insert(self->received.end(), bytes, bytes + q->len);
    }
    tcp_recved(pcb, p->tot_len);
    pbuf_free(p);
    return ERR_OK;
  }
  static void OnError(void* arg, err_t) {
    auto* self = static_cast<TestClient*>(arg);
    self->reset = true;
    self->pcb = nullptr;
  }
};

ip4_addr_t Ip(std::uint32_t host_order) {
  ip4_addr_t address;
  ip4_addr_set_u32(&address, lwip_htonl(host_order));
  return address;
}

class ModbusTcpServiceTest : public ::testing::Test {
 protected:
  ModbusTcpServiceTest() { hal::test::EnsureLwipInitialised(); }

  void SetUp() override {
    peer_netif_.Start(Ipv4Config{kPeerIp, 0xFFFFFF00, 0}, "peer");
    card_netif_.Start(Ipv4Config{kCardIp, 0xFFFFFF00, 0}, "card");
    ASSERT_TRUE(service_.Configure(config_).ok());
    Pump();
  }

  void TearDown() override {
    for (auto& client : clients_) {
      if (client->pcb != nullptr) {
        tcp_arg(client->pcb, nullptr);
        tcp_err(client->pcb, nullptr);
        tcp_abort(client->pcb);
      }
    }
    service_.Stop();
  }

  // The service polls, then frames are carried between the two ports, until nothing moves.
  void Pump() {
    for (int round = 0; round < 200; ++round) {
      service_.Poll(clock().NowMicros());
      std::size_t moved = Carry(card_port_, peer_port_) + Carry(peer_port_, card_port_);
      moved += peer_netif_.PumpReceive(64) + card_netif_.PumpReceive(64);
      if (moved == 0) return;
    }
    FAIL() << "traffic did not settle";
  }

  static std::size_t Carry(hal::test::FakeFramePort& from, hal::test::FakeFramePort& to) {
    const std::size_t count = from.sent().size();
    for (auto& frame : from.sent()) to.Inject(std::move(frame.bytes));
    from.sent().clear();
    return count;
  }

  TestClient& Connect() {
    clients_.push_back(std::make_unique<TestClient>());
    TestClient& client = *clients_.back();
    client.pcb = tcp_new_ip_type(IPADDR_TYPE_V4);
    EXPECT_NE(client.pcb, nullptr);
    tcp_bind_netif(client.pcb, &peer_netif_.lwip_netif());
    tcp_arg(client.pcb, &client);
    tcp_recv(client.pcb, &TestClient::OnRecv);
    tcp_err(client.pcb, &TestClient::OnError);
    tcp_nagle_disable(client.pcb);
    const ip4_addr_t card = Ip(kCardIp);
    EXPECT_EQ(tcp_connect(client.pcb, &card, 502, &TestClient::OnConnected), ERR_OK);
    Pump();
    return client;
  }

  void Send(TestClient& client, const Bytes& bytes) {
    ASSERT_NE(client.pcb, nullptr);
    ASSERT_EQ(tcp_write(client.pcb, bytes.data(), static_cast<u16_t>(bytes.size()), TCP_WRITE_FLAG_COPY), ERR_OK);
    ASSERT_EQ(tcp_output(client.pcb), ERR_OK);
    Pump();
  }

  static hal::test::FakeClock& clock() { return hal::test::LwipTestClock(); }

  hal::test::FakeFramePort peer_port_{kPeerMac};
  hal::test::FakeFramePort card_port_{kCardMac};
  CardNetif peer_netif_{peer_port_};
  CardNetif card_netif_{card_port_};
  drive_link::CardConfig config_;
  modbus::test::ServerHarness h_{[] {
    modbus::ServerOptions options;
    options.idle_timeout = 10 * hal::kMicrosPerSecond;
    return options;
  }()};
  ModbusTcpService service_{h_.server, clock()};
  std::vector<std::unique_ptr<TestClient>> clients_;
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

TEST_F(ModbusTcpServiceTest, NinthClient_ResetOthersStillServed) {
  std::vector<TestClient*> eight;
  for (std::size_t i = 0; i < modbus::Server::kMaxClients; ++i) {
    eight.push_back(&Connect());
    ASSERT_TRUE(eight.back()->connected) << i;
  }
  TestClient& ninth = Connect();
  EXPECT_TRUE(ninth.reset);
  EXPECT_EQ(service_.counters().refused, 1u);
  EXPECT_EQ(h_.server.open_connections(), modbus::Server::kMaxClients);
  for (TestClient* client : eight) {
    EXPECT_FALSE(client->reset);
    Send(*client, kReadVersion);
    EXPECT_EQ(client->received, kVersionAnswer);
  }
}

TEST_F(ModbusTcpServiceTest, ClientCloses_SlotFreed) {
  TestClient& client = Connect();
  Send(client, kReadVersion);
  ASSERT_EQ(tcp_close(client.pcb), ERR_OK);
  client.pcb = nullptr;
  Pump();
  EXPECT_EQ(h_.server.open_connections(), 0u);
  EXPECT_EQ(service_.counters().closed_by_peer, 1u);
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
  drive_link::CardConfig ethernet_ip = config_;
  ethernet_ip.protocol = drive_link::Protocol::kEtherNetIp;
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
