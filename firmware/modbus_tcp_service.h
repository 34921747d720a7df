// The Modbus TCP server (modbus::Server) bound to lwIP's raw TCP API: a listener on port 502, one
// lwIP PCB per client, bytes between the PCBs and the server. docs/modbus.md "TCP" has the rules.
//
// - Listens while c500 = 0 (Modbus TCP); c500 = 1 (EtherNet/IP) closes the port and resets every
//   connection (Configure). A closed port answers a connection attempt with RST (lwIP).
// - At most modbus::Server::kMaxClients (8) clients. The 9th is accepted by TCP (lwipopts.h keeps PCBs
//   for that) and reset at once from the accept callback; the others do not notice.
// - Received pbufs are copied into the server at once and freed; the receive window is reopened by the
//   bytes the server has finished with (the server's buffer is as large as the window, so nothing is
//   ever refused back to lwIP and no receive pbuf stays with this service).
// - Answers are written with tcp_write (copied) while at most kMaxUnacknowledgedBytes (two largest
//   answers) in kMaxQueuedSegments segments wait for the peer's acknowledgement: what lwipopts.h sizes
//   the heap and the segment pool for. The rest waits in the server, which stops serving that client
//   while its answer buffer is full (backpressure).
// - Dead peers: TCP keepalive on every connection (ModbusTcpOptions::keepalive, by default lwipopts.h's
//   60 s idle, 6 probes 10 s apart; dropped: counters().lost), and the server's idle rule (no request
//   for two minutes). A connection the server gives up (framing error, idle) is closed with FIN after
//   its last answers.
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "configurable_service.h"
#include "config/card_config.h"
#include "hal/clock.h"
#include "modbus/server.h"
#include "tcp_keepalive.h"
#include "stream_tcp_service.h"

namespace firmware {

struct ModbusTcpOptions {
  std::uint16_t port = 502;
  TcpKeepalive keepalive;  // on every connection (a vanished peer frees its slot)
};

struct ModbusTcpCounters {
  std::uint32_t accepted = 0;        // connections handed to the server
  std::uint32_t refused = 0;         // reset at once: every slot taken
  std::uint32_t closed_by_peer = 0;  // FIN from the client
  std::uint32_t closed_by_card = 0;  // the server gave the connection up (framing error, idle)
  std::uint32_t lost = 0;            // lwIP dropped the connection (RST, keepalive, retransmissions)
  std::uint32_t write_errors = 0;    // tcp_write refused (no memory): retried later
};

class ModbusTcpService final : public StreamTcpService<ModbusTcpService, modbus::Server, modbus::ConnectionId,
                                                       modbus::Server::kMaxClients, ModbusTcpCounters>,
                               public ConfigurableService {
 public:
  // In flight per connection: two largest Modbus answers, in at most two segments (lwipopts.h sizes
  // the heap, IPE_HEAP_MODBUS, and MEMP_NUM_TCP_SEG for that). Answers a pipelining client
  // is owed meanwhile wait in the server and leave together in the next segment.
  static constexpr std::size_t kMaxUnacknowledgedBytes = 2 * modbus::kMaxAduBytes;
  static constexpr std::size_t kMaxQueuedSegments = 2;

  ModbusTcpService(modbus::Server& server, const hal::Clock& clock, const ModbusTcpOptions& options = {})
      : StreamTcpService(server, clock, options.port, options.keepalive) {}
  ~ModbusTcpService() override;  // out of line: the skeleton's Stop() is instantiated once

  // Hands the configuration to the server and opens (c500 = 0) or closes (c500 = 1) the port.
  base::Status Configure(const config::CardConfig& config) override;

 private:
  friend TcpService;
  friend StreamTcpService;

  Slot* OpenConnection(tcp_pcb* pcb);
  err_t RefuseConnection(tcp_pcb* pcb) { return RefuseWithReset(pcb); }
  std::size_t SendRoom(tcp_pcb* pcb) const;
};

}  // namespace firmware
