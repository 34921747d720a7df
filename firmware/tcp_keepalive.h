// TCP keepalive on one lwIP connection: how a service finds a peer that vanished without FIN or RST
// (a PLC power-cycled, a cable pulled between two switches). Used by every service that holds a slot
// per connection (Modbus TCP, EtherNet/IP). lwipopts.h enables per-PCB timing (LWIP_TCP_KEEPALIVE);
// the defaults here are its TCP_KEEP*_DEFAULT: first probe after 60 s idle, 6 probes 10 s apart, the
// connection is dropped (RST, the error callback with ERR_ABRT) about 2 minutes after the peer's last
// segment. Tests shorten them (ipe002z-host --tcp-keepalive).
#pragma once

#include <cstdint>

#include "lwip/ip.h"
#include "lwip/tcp.h"

namespace firmware {

struct TcpKeepalive {
  std::uint32_t idle_ms = 60000;      // no segment from the peer for this long: the first probe
  std::uint32_t interval_ms = 10000;  // then a probe every interval
  std::uint8_t count = 6;             // this many unanswered probes: the connection is dropped
};

static_assert(TcpKeepalive{}.idle_ms == TCP_KEEPIDLE_DEFAULT, "defaults must match lwipopts.h");
static_assert(TcpKeepalive{}.interval_ms == TCP_KEEPINTVL_DEFAULT, "defaults must match lwipopts.h");
static_assert(TcpKeepalive{}.count == TCP_KEEPCNT_DEFAULT, "defaults must match lwipopts.h");

// Turns keepalive on for `pcb` (an active connection, e.g. from the accept callback) with `k`'s timing.
// lwIP checks the times in its slow timer, every 500 ms.
inline void ApplyKeepalive(tcp_pcb* pcb, const TcpKeepalive& k) {
  ip_set_option(pcb, SOF_KEEPALIVE);
  pcb->keep_idle = k.idle_ms;
  pcb->keep_intvl = k.interval_ms;
  pcb->keep_cnt = k.count;
}

}  // namespace firmware
