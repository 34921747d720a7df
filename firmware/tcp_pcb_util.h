// What every service bound to lwIP's raw TCP API does the same way (Modbus TCP, EtherNet/IP, HTTP):
// open and close a listener, wire an accepted request/response connection, detach a PCB being given
// up, and close with FIN or, without memory for the FIN, with RST.
#pragma once

#include <cstdint>

#include "base/status.h"
#include "lwip/tcp.h"
#include "tcp_keepalive.h"

namespace firmware {

// lwIP's poll callback runs every interval x 500 ms: a stalled write is retried within a second.
inline constexpr u8_t kTcpPollInterval = 2;

struct TcpCallbacks {
  tcp_recv_fn recv = nullptr;
  tcp_sent_fn sent = nullptr;
  tcp_err_fn err = nullptr;
  tcp_poll_fn poll = nullptr;
};

// Listens on `port` (any address) and hands `arg` to `accept`, with SOF_REUSEADDR (connections of an
// earlier listener on the port may be in TIME_WAIT). kResourceExhausted: no PCB; kFailedPrecondition:
// the port is taken. Nothing is left allocated on failure.
base::Result<tcp_pcb*> OpenTcpListener(std::uint16_t port, void* arg, tcp_accept_fn accept);
// Closes a listener (always freed) and sets it to null; no-op on null.
void CloseTcpListener(tcp_pcb*& listener);

// Wires an accepted connection: `arg` and the callbacks, the poll every kTcpPollInterval, Nagle off
// (request/response: an answer must not wait for the acknowledgement of the previous one) and
// keepalive.
void AttachTcpConnection(tcp_pcb* pcb, void* arg, const TcpCallbacks& callbacks, const TcpKeepalive& keepalive);

// Nulls every callback of a PCB being closed or aborted (tcpecho_raw's rule): lwIP must not call into
// a slot that is about to be reused.
void DetachTcpCallbacks(tcp_pcb* pcb);

// A recv callback for a PCB that is no longer ours: what lwIP's tcp_recv_null does (take and free the
// data; a null pbuf needs nothing). Returns ERR_OK.
err_t DiscardTcpData(tcp_pcb* pcb, pbuf* p);

// FIN after the data already queued; when lwIP has no memory for the FIN, RST instead and ERR_ABRT
// (a callback must then return ERR_ABRT). The PCB must be detached first.
err_t CloseOrAbortTcp(tcp_pcb* pcb);

}  // namespace firmware
