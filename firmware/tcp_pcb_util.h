// Small helpers shared by the services bound to lwIP's raw TCP API.
#pragma once

#include "lwip/tcp.h"

namespace firmware {

// Nulls every callback of a PCB being closed or aborted (tcpecho_raw's rule): lwIP must not call into
// a slot that is about to be reused.
inline void DetachTcpCallbacks(tcp_pcb* pcb) {
  tcp_arg(pcb, nullptr);
  tcp_recv(pcb, nullptr);
  tcp_sent(pcb, nullptr);
  tcp_err(pcb, nullptr);
  tcp_poll(pcb, nullptr, 0);
}

}  // namespace firmware
