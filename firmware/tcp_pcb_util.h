// What every service bound to lwIP's raw TCP API does the same way (Modbus TCP, EtherNet/IP, HTTP):
// open and close a listener, wire an accepted request/response connection, detach a PCB being given
// up, and close with FIN or, without memory for the FIN, with RST.
#pragma once

#include <array>
#include <cstddef>
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

// The raw-API callbacks of a service that keeps one slot per connection (Modbus TCP, EtherNet/IP, HTTP):
// lwIP's `arg` is the slot, whose `service` and `pcb` members route each event to the service:
//   service->Receive(slot, p)  data, or p == nullptr for the peer's FIN;
//   service->Resume(slot)      an acknowledgement or lwIP's poll: output that waited may go now;
//   service->Lost(slot)        lwIP dropped the connection (RST, keepalive, retransmissions); the PCB is
//                              already freed and slot.pcb is null.
// Receive and Resume return ERR_ABRT when they aborted the PCB. A slot that no longer holds the PCB (it
// was closed meanwhile) is left alone. The service befriends TcpSlotCallbacks<Slot>.
template <typename Slot>
struct TcpSlotCallbacks {
  // tcp_recv_fn: "If the callback function returns ERR_OK or ERR_ABRT it must have freed the pbuf".
  static err_t OnRecv(void* arg, tcp_pcb* pcb, pbuf* p, err_t err) {
    auto* slot = static_cast<Slot*>(arg);
    if (slot == nullptr || slot->pcb != pcb) return DiscardTcpData(pcb, p);
    if (err != ERR_OK && p != nullptr) {
      pbuf_free(p);
      return ERR_OK;
    }
    return slot->service->Receive(*slot, p);
  }
  static err_t OnSent(void* arg, tcp_pcb* pcb, u16_t length) {
    static_cast<void>(length);
    return OnPoll(arg, pcb);
  }
  static err_t OnPoll(void* arg, tcp_pcb* pcb) {
    auto* slot = static_cast<Slot*>(arg);
    if (slot == nullptr || slot->pcb != pcb) return ERR_OK;
    return slot->service->Resume(*slot);
  }
  // tcp_err_fn: the PCB is already freed; only the slot's state is left.
  static void OnError(void* arg, err_t err) {
    static_cast<void>(err);
    auto* slot = static_cast<Slot*>(arg);
    if (slot == nullptr || slot->pcb == nullptr) return;
    slot->pcb = nullptr;
    slot->service->Lost(*slot);
  }
  static constexpr TcpCallbacks kCallbacks{&OnRecv, &OnSent, &OnError, &OnPoll};
};

// The slots of a service's table that hold a PCB (its connection pool's `used`).
template <typename Slot, std::size_t N>
std::size_t SlotsHoldingPcb(const std::array<Slot, N>& slots) {
  std::size_t count = 0;
  for (const Slot& slot : slots) count += slot.pcb != nullptr ? 1 : 0;
  return count;
}

// FIN after the data already queued; when lwIP has no memory for the FIN, RST instead and ERR_ABRT
// (a callback must then return ERR_ABRT). The PCB must be detached first.
err_t CloseOrAbortTcp(tcp_pcb* pcb);

}  // namespace firmware
