// The web server (web::HttpServer) bound to lwIP's raw TCP API: a listener on port 80, one PCB per
// client, bytes between the PCBs and the server. docs/web.md "Connections" has the rules.
//
// - Listens while c554 = 1 (web server enabled), whatever c500 says; c554 = 0 closes the port and resets
//   every connection (Configure).
// - At most web::kMaxHttpClients connections. One more is given the slot of the connection idle longest
//   between requests (closed with FIN; browsers keep idle connections and reopen them at will); when every
//   connection is busy it gets web::HttpServer::BusyResponse() (503, Retry-After: 1) and FIN. The slot
//   pool's refused counts these (counters().refused_busy); an evicted idle connection is not a refusal.
// - Received pbufs are copied into the server and freed at once; the window reopens as the server's
//   buffer allows (HttpServer::TakeReleasedInput), so a request larger than one window still arrives.
// - Answers: the head (status line, headers, JSON body) is copied into lwIP; an embedded asset's body is
//   referenced, not copied (it lives in flash for the program's life). At most TCP_SND_BUF bytes wait
//   for acknowledgement per connection (lwipopts.h sizes the heap and pbuf pools for 3 such clients and
//   the busy one). Handing an answer to TCP gives its response buffer back to the server.
// - Keepalive as the other services (a vanished browser frees its slot).
#pragma once

#include <cstdint>

#include "base/status.h"
#include "configurable_service.h"
#include "config/card_config.h"
#include "hal/clock.h"
#include "tcp_keepalive.h"
#include "stream_tcp_service.h"
#include "web/http_server.h"

namespace firmware {

struct WebServiceOptions {
  std::uint16_t port = 80;
  TcpKeepalive keepalive;
};

struct WebServiceCounters {
  std::uint32_t accepted = 0;
  std::uint32_t evicted = 0;         // idle connections closed to make room
  std::uint32_t refused_busy = 0;    // 503 and closed: every connection busy
  std::uint32_t closed_by_peer = 0;
  std::uint32_t closed_by_card = 0;  // Connection: close, an error answer, a timeout
  std::uint32_t lost = 0;            // lwIP dropped the connection (RST, keepalive, retransmissions)
  std::uint32_t write_errors = 0;    // tcp_write refused (no memory): retried later
};

class WebService final : public StreamTcpService<WebService, web::HttpServer, web::HttpClientId,
                                                 web::kMaxHttpClients, WebServiceCounters>,
                         public ConfigurableService {
 public:
  WebService(web::HttpServer& server, const hal::Clock& clock, const WebServiceOptions& options = {})
      : StreamTcpService(server, clock, options.port, options.keepalive) {}
  ~WebService() override;  // out of line: the skeleton's Stop() is instantiated once

  // Opens (c554 = 1) or closes (c554 = 0) the port.
  base::Status Configure(const config::CardConfig& config) override;

 private:
  friend TcpService;
  friend StreamTcpService;

  Slot* OpenConnection(tcp_pcb* pcb);
  err_t RefuseConnection(tcp_pcb* pcb);
  std::size_t ReleasedInput(Slot& client);
  void LoadOutput(Slot& client, hal::Micros now);
  u8_t WriteFlags(const Slot& client) const;
  std::size_t SendRoom(tcp_pcb* pcb) const;
};

}  // namespace firmware
