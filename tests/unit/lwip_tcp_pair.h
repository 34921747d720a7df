// Two netifs in the one lwIP instance of the unit tests, their fake frame ports wired back to back: a
// peer at 192.168.1.30 and the card at 192.168.1.12. Clients written on lwIP's raw API (TcpTestClient,
// UdpTestPeer) are bound to the peer's netif; the card's PCBs route through the card's netif, the first
// in lwIP's list. Tests of the services bound to lwIP (Modbus TCP, EtherNet/IP) derive from
// LwipPairTest and say in PollServices() what runs on each pass.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "card_netif.h"
#include "fake_frame_port.h"
#include "lwip/tcp.h"
#include "lwip/udp.h"
#include "lwip_fixture.h"

namespace firmware::test {

using Bytes = std::vector<std::uint8_t>;

inline constexpr hal::MacAddress kPeerMac = {0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
inline constexpr hal::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
inline constexpr std::uint32_t kCardIp = 0xC0A8010C;  // 192.168.1.12
inline constexpr std::uint32_t kPeerIp = 0xC0A8011E;  // 192.168.1.30

inline ip4_addr_t Ip(std::uint32_t host_order) {
  ip4_addr_t address;
  ip4_addr_set_u32(&address, lwip_htonl(host_order));
  return address;
}

// A TCP client on lwIP's raw API. With `reading` false it stops taking data (a peer that does not read:
// lwIP's window for the card closes).
struct TcpTestClient {
  tcp_pcb* pcb = nullptr;
  bool connected = false;
  bool reset = false;        // the err callback ran (RST or abort): the PCB is gone
  bool peer_closed = false;  // FIN from the card
  bool reading = true;
  Bytes received;

  static err_t OnConnected(void* arg, tcp_pcb*, err_t) {
    static_cast<TcpTestClient*>(arg)->connected = true;
    return ERR_OK;
  }
  static err_t OnRecv(void* arg, tcp_pcb* pcb, pbuf* p, err_t) {
    auto* self = static_cast<TcpTestClient*>(arg);
    if (p == nullptr) {
      self->peer_closed = true;
      return ERR_OK;
    }
    if (!self->reading) return ERR_MEM;  // lwIP keeps the data and offers it again later
    for (const pbuf* q = p; q != nullptr; q = q->next) {
      const auto* bytes = static_cast<const std::uint8_t*>(q->payload);
      self->received.insert(self->received.end(), bytes, bytes + q->len);
    }
    tcp_recved(pcb, p->tot_len);
    pbuf_free(p);
    return ERR_OK;
  }
  static void OnError(void* arg, err_t) {
    auto* self = static_cast<TcpTestClient*>(arg);
    self->reset = true;
    self->pcb = nullptr;
  }
};

// A UDP socket on the peer's netif that keeps what it receives.
struct UdpTestPeer {
  struct Datagram {
    Bytes bytes;
    std::uint16_t from_port = 0;
  };
  udp_pcb* pcb = nullptr;
  std::vector<Datagram> received;

  static void OnRecv(void* arg, udp_pcb*, pbuf* p, const ip_addr_t*, u16_t port) {
    auto* self = static_cast<UdpTestPeer*>(arg);
    Bytes bytes(p->tot_len);
    pbuf_copy_partial(p, bytes.data(), p->tot_len, 0);
    self->received.push_back({std::move(bytes), port});
    pbuf_free(p);
  }
};

class LwipPairTest : public ::testing::Test {
 protected:
  LwipPairTest() { hal::test::EnsureLwipInitialised(); }

  void StartNetifs() {
    peer_netif_.Start(Ipv4Config{kPeerIp, 0xFFFFFF00, 0}, "peer");
    card_netif_.Start(Ipv4Config{kCardIp, 0xFFFFFF00, 0}, "card");
  }

  // Aborts every client PCB still open (the card's side is the test's to stop).
  void CloseClients() {
    for (auto& client : clients_) {
      if (client->pcb != nullptr) {
        tcp_arg(client->pcb, nullptr);
        tcp_err(client->pcb, nullptr);
        tcp_abort(client->pcb);
      }
    }
    for (auto& peer : udp_peers_) udp_remove(peer->pcb);
  }

  // What runs on the card on each pass (the service's Poll).
  virtual void PollServices() = 0;

  // Passes run and frames are carried between the two ports until nothing moves.
  void Pump() {
    for (int round = 0; round < 200; ++round) {
      PollServices();
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

  TcpTestClient& Connect(std::uint16_t port) {
    clients_.push_back(std::make_unique<TcpTestClient>());
    TcpTestClient& client = *clients_.back();
    client.pcb = tcp_new_ip_type(IPADDR_TYPE_V4);
    EXPECT_NE(client.pcb, nullptr);
    tcp_bind_netif(client.pcb, &peer_netif_.lwip_netif());
    tcp_arg(client.pcb, &client);
    tcp_recv(client.pcb, &TcpTestClient::OnRecv);
    tcp_err(client.pcb, &TcpTestClient::OnError);
    tcp_nagle_disable(client.pcb);
    const ip4_addr_t card = Ip(kCardIp);
    EXPECT_EQ(tcp_connect(client.pcb, &card, port, &TcpTestClient::OnConnected), ERR_OK);
    Pump();
    return client;
  }

  void Send(TcpTestClient& client, const Bytes& bytes) {
    ASSERT_NE(client.pcb, nullptr);
    ASSERT_EQ(tcp_write(client.pcb, bytes.data(), static_cast<u16_t>(bytes.size()), TCP_WRITE_FLAG_COPY), ERR_OK);
    ASSERT_EQ(tcp_output(client.pcb), ERR_OK);
    Pump();
  }

  UdpTestPeer& OpenUdp(std::uint16_t local_port) {
    udp_peers_.push_back(std::make_unique<UdpTestPeer>());
    UdpTestPeer& peer = *udp_peers_.back();
    peer.pcb = udp_new_ip_type(IPADDR_TYPE_V4);
    EXPECT_NE(peer.pcb, nullptr);
    const ip4_addr_t any = Ip(kPeerIp);
    EXPECT_EQ(udp_bind(peer.pcb, &any, local_port), ERR_OK);
    udp_bind_netif(peer.pcb, &peer_netif_.lwip_netif());
    udp_recv(peer.pcb, &UdpTestPeer::OnRecv, &peer);
    return peer;
  }

  void SendTo(UdpTestPeer& peer, std::uint32_t to, std::uint16_t port, const Bytes& bytes) {
    pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(bytes.size()), PBUF_RAM);
    ASSERT_NE(p, nullptr);
    pbuf_take(p, bytes.data(), static_cast<u16_t>(bytes.size()));
    const ip4_addr_t address = Ip(to);
    ip_addr_t destination;
    ip_addr_copy_from_ip4(destination, address);
    EXPECT_EQ(udp_sendto(peer.pcb, p, &destination, port), ERR_OK);
    pbuf_free(p);
    Pump();
  }

  static hal::test::FakeClock& clock() { return hal::test::LwipTestClock(); }

  hal::test::FakeFramePort peer_port_{kPeerMac};
  hal::test::FakeFramePort card_port_{kCardMac};
  CardNetif peer_netif_{peer_port_};
  CardNetif card_netif_{card_port_};
  std::vector<std::unique_ptr<TcpTestClient>> clients_;
  std::vector<std::unique_ptr<UdpTestPeer>> udp_peers_;
};

}  // namespace firmware::test
