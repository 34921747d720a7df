// The EtherNet/IP encapsulation server (cip::EncapsulationServer) bound to lwIP's raw API: a TCP
// listener and a UDP PCB on port 44818, one lwIP PCB per TCP connection. docs/ethernetip.md "In the
// firmware" has the rules.
//
// - Open while c500 = 1 (EtherNet/IP); c500 = 0 (Modbus TCP) closes both ports and resets every
//   connection (Configure): the card speaks one protocol at a time (seed 000 §3.1 c500).
// - At most cip::kMaxTcpConnections (9) TCP connections; one more is accepted by TCP and reset at once.
// - Received bytes are copied into the connection's input buffer (TCP_WND = 536 bytes) and the pbuf is
//   freed at once, so a client that stops reading its replies holds no receive pbuf (the pool belongs to
//   every peer). The window is reopened only by bytes the core has consumed, so the buffer never
//   overflows; a message longer than the window arrives in several windows (the core's assembler keeps
//   it).
// - The core is fed only while its largest reply (cip::kMaxReplyMessage) fits into the send buffer.
//   A reply tcp_write still refuses (the heap or the segment pool is exhausted, lwipopts.h IPE_HEAP_ENIP)
//   is kept in the service's one held-reply buffer and written first when lwIP acknowledges data or
//   polls; meanwhile no connection is fed (the heap is shared, so the others could not write either).
//   Nothing is dropped: the clients' requests wait in their windows.
// - UDP: each datagram is handed over whole (a longer one than any request is dropped and counted);
//   replies go to the sender; delayed broadcast ListIdentity replies leave from Poll when due.
// - Dead peers: TCP keepalive (TcpKeepalive) and the core's inactivity timeout.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "cip/encapsulation_server.h"
#include "configurable_service.h"
#include "config/card_config.h"
#include "hal/clock.h"
#include "lwip/tcp.h"
#include "lwip/udp.h"
#include "lwipopts.h"
#include "tcp_keepalive.h"
#include "tcp_service.h"

namespace firmware {

struct EipOptions {
  std::uint16_t port = cip::kEncapsulationPort;  // TCP and UDP
  TcpKeepalive keepalive;
  // IP TOS of every packet of an accepted connection and of every UDP reply: the QoS object's DSCP
  // Explicit, shifted past the ECN bits. (A SYN-ACK leaves before the connection is accepted: TOS 0.)
  std::uint8_t tos = 0;
};

struct EipCounters {
  std::uint32_t accepted = 0;        // TCP connections handed to the core
  std::uint32_t refused = 0;         // reset at once: every connection slot taken
  std::uint32_t closed_by_peer = 0;  // FIN from the client
  std::uint32_t closed_by_card = 0;  // the core closed it (UnRegisterSession, inactivity)
  std::uint32_t lost = 0;            // lwIP dropped the connection (RST, keepalive, retransmissions)
  std::uint32_t write_stalls = 0;    // tcp_write refused a reply (no memory): kept and retried
  std::uint32_t udp_received = 0;
  std::uint32_t udp_sent = 0;
  std::uint32_t udp_dropped = 0;     // too long, or no memory for the reply
  std::uint32_t deferred_replies = 0;  // requests whose reply waited for drive accesses
  std::uint32_t deferred_retries = 0;  // their executions after the accesses completed
};

// The protocol's part of a connection slot (TcpService adds the PCB).
struct EipConnection {
  cip::TcpConnectionId id;
  // Received, not yet consumed by the core (at most one window).
  std::array<std::uint8_t, TCP_WND> input{};
  std::size_t input_size = 0;
  bool close_after_reply = false;
  bool pending = false;  // the core holds a message whose reply is deferred
};

class EipService final : public TcpService<EipService, EipConnection, cip::kMaxTcpConnections, EipCounters>,
                         public ConfigurableService {
 public:
  EipService(cip::EncapsulationServer& server, const hal::Clock& clock, const EipOptions& options = {})
      : TcpService(options.port, options.keepalive),
        server_(server),
        clock_(clock),
        udp_port_(options.port),
        tos_(options.tos) {}
  ~EipService() override;  // out of line: the skeleton's Stop() is instantiated once

  // Opens (c500 = 1) or closes (c500 = 0) the ports.
  base::Status Configure(const config::CardConfig& config) override;
  // Listens on TCP and UDP (no-op when open). kResourceExhausted: no PCB; kFailedPrecondition: a port
  // is taken. Nothing stays half open on failure.
  base::Status Start();
  // Closes both ports and resets every connection.
  void Stop();

  void Poll(hal::Micros now) override;

 private:
  friend TcpService;
  static void OnUdp(void* arg, udp_pcb* pcb, pbuf* p, const ip_addr_t* address, u16_t port);

  Slot* OpenConnection(tcp_pcb* pcb);
  err_t RefuseConnection(tcp_pcb* pcb) { return RefuseWithReset(pcb); }
  bool TakeData(Slot& connection, const pbuf& p);
  // Feeds buffered input to the core while replies fit, writes them, closes when the core says so.
  err_t Serve(Slot& connection);
  err_t Resume(Slot& connection) { return Serve(connection); }
  // The connection is gone: a reply it held goes with it.
  void Release(Slot& connection);
  // Input the core has not taken yet goes in on the next pass as soon as a reply fits. A deferred reply
  // is retried on the pass after its drive accesses completed.
  bool MustServeNow(const Slot& connection) const;
  hal::Micros CoreDeadline() const { return server_.NextDeadline(); }

  bool CanTakeReply(const Slot& connection) const;
  // Writes the held reply (whichever connection holds it); false while tcp_write still refuses it.
  bool WriteHeldReply();
  Slot* FindConnection(cip::TcpConnectionId id);
  void ReceiveDatagram(pbuf* p, const ip_addr_t* address, u16_t port);
  void SendDatagram(const cip::Ipv4Endpoint& to, std::span<const std::uint8_t> bytes);

  cip::EncapsulationServer& server_;
  const hal::Clock& clock_;
  std::uint16_t udp_port_;  // the same as the TCP listener's
  std::uint8_t tos_;
  udp_pcb* udp_ = nullptr;
  // A reply tcp_write refused (one for all connections: while it waits, no connection is fed).
  std::array<std::uint8_t, cip::kMaxReplyMessage> held_reply_{};
  std::size_t held_reply_size_ = 0;
  Slot* held_by_ = nullptr;
  std::array<std::uint8_t, cip::kMaxEncapsulationMessage> datagram_{};  // one received datagram
};

}  // namespace firmware
