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
#include "lwip/ip.h"
#include "lwip/priv/tcp_priv.h"
#include "lwip/prot/ip4.h"
#include "lwip/tcp.h"
#include "lwip/udp.h"
#include "lwip_fixture.h"

namespace firmware::test {

using Bytes = std::vector<std::uint8_t>;

inline constexpr base::MacAddress kPeerMac = {0x02, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE};
inline constexpr base::MacAddress kCardMac = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
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
    std::uint8_t tos = 0;  // of the IP header it came in
  };
  udp_pcb* pcb = nullptr;
  std::vector<Datagram> received;

  static void OnRecv(void* arg, udp_pcb*, pbuf* p, const ip_addr_t*, u16_t port) {
    auto* self = static_cast<UdpTestPeer*>(arg);
    Bytes bytes(p->tot_len);
    pbuf_copy_partial(p, bytes.data(), p->tot_len, 0);
    self->received.push_back({std::move(bytes), port, IPH_TOS(ip4_current_header())});
    pbuf_free(p);
  }
};

// A client connection whose lwIP PCB was released without a word to the card (tcp_abandon, no RST): the
// card's side stays established and the test speaks to it in raw frames, with the sequence numbers the
// PCB had (LwipPairTest::Freeze / ExchangeFrozen). The unit tests' single lwIP instance takes the clients'
// PCBs from the pool that lwipopts.h sizes for the card alone; freezing lets a test hold every slot of a
// service, plus one more client, without a second pool.
struct FrozenTcpClient {
  std::uint16_t client_port = 0;
  std::uint16_t card_port = 0;
  std::uint32_t next_sent = 0;      // the next sequence number the client sends
  std::uint32_t next_expected = 0;  // the next sequence number expected from the card
};

class LwipPairTest : public ::testing::Test {
 protected:
  LwipPairTest() { hal::test::EnsureLwipInitialised(); }

  void StartNetifs() {
    peer_netif_.Start(Ipv4Config{base::Ipv4Address(kPeerIp), base::Ipv4Address(0xFFFFFF00), {}}, "peer");
    card_netif_.Start(Ipv4Config{base::Ipv4Address(kCardIp), base::Ipv4Address(0xFFFFFF00), {}}, "card");
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

  // Freezes a connected client that has nothing of its own unacknowledged: acknowledges what it received,
  // then releases its PCB without telling the card.
  FrozenTcpClient Freeze(TcpTestClient& client) {
    tcp_pcb* pcb = client.pcb;
    EXPECT_NE(pcb, nullptr);
    if (pcb == nullptr) return {};
    tcp_ack_now(pcb);
    EXPECT_EQ(tcp_output(pcb), ERR_OK);
    Pump();
    EXPECT_EQ(pcb->unsent, nullptr);
    EXPECT_EQ(pcb->unacked, nullptr);
    const FrozenTcpClient frozen{pcb->local_port, pcb->remote_port, pcb->snd_nxt, pcb->rcv_nxt};
    tcp_arg(pcb, nullptr);
    tcp_err(pcb, nullptr);
    tcp_recv(pcb, nullptr);
    tcp_abandon(pcb, 0);
    client.pcb = nullptr;
    return frozen;
  }

  // Sends `payload` on a frozen connection and returns every byte the card answers with (acknowledged, so
  // nothing is left to retransmit). Other traffic is carried as Pump() carries it.
  Bytes ExchangeFrozen(FrozenTcpClient& frozen, const Bytes& payload) {
    card_port_.Inject(FrozenSegment(frozen, kTcpPush | kTcpAck, payload));
    frozen.next_sent += static_cast<std::uint32_t>(payload.size());
    Bytes received;
    PumpFrozen(frozen, received);
    card_port_.Inject(FrozenSegment(frozen, kTcpAck, {}));
    PumpFrozen(frozen, received);
    return received;
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

 private:
  static constexpr std::uint8_t kTcpFin = 0x01;
  static constexpr std::uint8_t kTcpPush = 0x08;
  static constexpr std::uint8_t kTcpAck = 0x10;
  static constexpr std::size_t kEthernetHeader = 14;

  static std::uint16_t Checksum(std::uint32_t sum, const std::uint8_t* bytes, std::size_t size) {
    for (std::size_t i = 0; i + 1 < size; i += 2) sum += static_cast<std::uint32_t>(bytes[i] << 8 | bytes[i + 1]);
    if (size % 2 != 0) sum += static_cast<std::uint32_t>(bytes[size - 1] << 8);
    while (sum > 0xFFFF) sum = (sum & 0xFFFF) + (sum >> 16);
    return static_cast<std::uint16_t>(~sum & 0xFFFF);
  }
  static void Put16(Bytes& out, std::size_t at, std::uint32_t value) {
    out[at] = static_cast<std::uint8_t>(value >> 8);
    out[at + 1] = static_cast<std::uint8_t>(value);
  }
  static void Put32(Bytes& out, std::size_t at, std::uint32_t value) {
    Put16(out, at, value >> 16);
    Put16(out, at + 2, value & 0xFFFF);
  }
  static std::uint32_t Get32(const Bytes& in, std::size_t at) {
    return static_cast<std::uint32_t>(in[at] << 24 | in[at + 1] << 16 | in[at + 2] << 8 | in[at + 3]);
  }

  // An Ethernet/IPv4/TCP frame from the peer to the card on a frozen connection.
  Bytes FrozenSegment(const FrozenTcpClient& frozen, std::uint8_t flags, const Bytes& payload) {
    const std::size_t tcp_length = 20 + payload.size();
    Bytes frame(kEthernetHeader + 20 + tcp_length, 0);
    const netif& card = card_netif_.lwip_netif();
    const netif& peer = peer_netif_.lwip_netif();
    std::copy(card.hwaddr, card.hwaddr + 6, frame.begin());
    std::copy(peer.hwaddr, peer.hwaddr + 6, frame.begin() + 6);
    Put16(frame, 12, 0x0800);
    const std::size_t ip = kEthernetHeader;
    frame[ip] = 0x45;
    Put16(frame, ip + 2, static_cast<std::uint32_t>(20 + tcp_length));
    frame[ip + 8] = 64;
    frame[ip + 9] = 6;
    Put32(frame, ip + 12, kPeerIp);
    Put32(frame, ip + 16, kCardIp);
    Put16(frame, ip + 10, Checksum(0, frame.data() + ip, 20));
    const std::size_t tcp = ip + 20;
    Put16(frame, tcp, frozen.client_port);
    Put16(frame, tcp + 2, frozen.card_port);
    Put32(frame, tcp + 4, frozen.next_sent);
    Put32(frame, tcp + 8, frozen.next_expected);
    frame[tcp + 12] = 5 << 4;
    frame[tcp + 13] = flags;
    Put16(frame, tcp + 14, TCP_WND);
    std::copy(payload.begin(), payload.end(), frame.begin() + static_cast<long>(tcp + 20));
    const std::uint32_t pseudo = (kPeerIp >> 16) + (kPeerIp & 0xFFFF) + (kCardIp >> 16) + (kCardIp & 0xFFFF) + 6 +
                                 static_cast<std::uint32_t>(tcp_length);
    Put16(frame, tcp + 16, Checksum(pseudo, frame.data() + tcp, tcp_length));
    return frame;
  }

  // Pump(), except that the card's segments of the frozen connection are kept (their data appended to
  // `received`) instead of reaching the peer's lwIP, which would answer them with RST.
  void PumpFrozen(FrozenTcpClient& frozen, Bytes& received) {
    for (int round = 0; round < 200; ++round) {
      PollServices();
      std::size_t moved = card_netif_.PumpReceive(64);
      for (auto& sent : card_port_.sent()) {
        ++moved;
        const Bytes& f = sent.bytes;
        const std::size_t ip = kEthernetHeader;
        const bool frozen_segment = f.size() >= ip + 40 && f[12] == 0x08 && f[13] == 0x00 && f[ip + 9] == 6 &&
                                    (f[ip + 20 + 2] << 8 | f[ip + 20 + 3]) == frozen.client_port &&
                                    (f[ip + 20] << 8 | f[ip + 21]) == frozen.card_port;
        if (!frozen_segment) {
          peer_port_.Inject(std::move(sent.bytes));
          continue;
        }
        const std::size_t ip_length = static_cast<std::size_t>(f[ip + 2] << 8 | f[ip + 3]);
        const std::size_t tcp = ip + static_cast<std::size_t>((f[ip] & 0x0F) * 4);
        const std::size_t data = tcp + static_cast<std::size_t>((f[tcp + 12] >> 4) * 4);
        const std::size_t end = ip + ip_length;
        if (Get32(f, tcp + 4) != frozen.next_expected || end < data) continue;  // a retransmission
        received.insert(received.end(), f.begin() + static_cast<long>(data), f.begin() + static_cast<long>(end));
        frozen.next_expected += static_cast<std::uint32_t>(end - data) + ((f[tcp + 13] & kTcpFin) != 0 ? 1 : 0);
      }
      card_port_.sent().clear();
      moved += Carry(peer_port_, card_port_) + peer_netif_.PumpReceive(64);
      if (moved == 0) return;
    }
    FAIL() << "traffic did not settle";
  }

 protected:

  hal::test::FakeFramePort peer_port_{kPeerMac};
  hal::test::FakeFramePort card_port_{kCardMac};
  CardNetif peer_netif_{peer_port_};
  CardNetif card_netif_{card_port_};
  std::vector<std::unique_ptr<TcpTestClient>> clients_;
  std::vector<std::unique_ptr<UdpTestPeer>> udp_peers_;
};

}  // namespace firmware::test
