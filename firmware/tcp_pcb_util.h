// The steps on one lwIP TCP PCB that the card's TCP services (TcpService, tcp_service.h) are made of:
// open and close a listener, wire an accepted request/response connection, detach a PCB being given
// up, read a received chain, reopen the window, write, and close with FIN or, without memory for the FIN,
// with RST.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

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

// Hands the bytes of each pbuf of a chain to `take` (bool(std::span<const std::uint8_t>): taken whole?)
// in order; false as soon as one is not taken whole.
template <typename Take>
bool ForEachPbufSegment(const pbuf& chain, Take take) {
  for (const pbuf* q = &chain; q != nullptr; q = q->next) {
    if (!take(std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(q->payload), q->len))) return false;
  }
  return true;
}

// Reopens the receive window by `released` bytes (tcp_recved takes at most 0xFFFF at a time).
void ReopenTcpWindow(tcp_pcb* pcb, std::size_t released);

// Copies `bytes` into lwIP's send queue and sends what may go now. False when tcp_write refused them
// (no memory): nothing was queued, the caller keeps the bytes and tries again later.
bool WriteTcp(tcp_pcb* pcb, std::span<const std::uint8_t> bytes, u8_t flags = TCP_WRITE_FLAG_COPY);

// FIN after the data already queued; when lwIP has no memory for the FIN, RST instead and ERR_ABRT
// (a callback must then return ERR_ABRT). The PCB must be detached first.
err_t CloseOrAbortTcp(tcp_pcb* pcb);

}  // namespace firmware
