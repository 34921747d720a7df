// The lwIP raw-TCP skeleton every TCP front end of the card shares (Modbus TCP, HTTP, EtherNet/IP): a
// listener on one port, a fixed table of connection slots, accepting and refusing, FIN or RST, lwIP's
// callbacks routed to the slot, keepalive, the slot pool's statistics and the event loop's deadline.
// What differs, the protocol, is the class deriving from it (CRTP: no virtual call per segment):
//
//   class ModbusTcpService final
//       : public TcpService<ModbusTcpService, ModbusTcpConnection, modbus::Server::kMaxClients, ModbusTcpCounters>
//
// The skeleton calls these members of the protocol (it befriends the skeleton to keep them private):
//   Slot* OpenConnection(tcp_pcb*)      opens the core's connection for an accepted PCB and returns the
//                                       free slot with its Connection part set; nullptr: refuse it
//   err_t RefuseConnection(tcp_pcb*)    RefuseWithReset(pcb), or a protocol answer and FIN; returns
//                                       what the accept callback returns
//   bool TakeData(Slot&, const pbuf&)   copies received bytes out of the pbuf (the skeleton frees it);
//                                       false when they did not fit: the connection is reset
//   err_t Serve(Slot&)                  feeds the core, writes its answers, closes when the core says so
//   err_t Resume(Slot&)                 an acknowledgement or lwIP's poll: output that waited may go
//   void Release(Slot&)                 the connection is gone (closed, reset or lost): tell the core
//   bool MustServeNow(const Slot&)      work waits that the loop must come back for at once
//   hal::Micros CoreDeadline()          the core's own next deadline
// Serve and Resume return ERR_ABRT when they aborted the PCB (an lwIP callback must then return it).
// The protocol also implements Service::Poll, its Configure, and calls Stop() in its destructor (the
// skeleton's destructor runs after the protocol's members are gone).
//
// Counters must have the members accepted, closed_by_peer, closed_by_card and lost (and refused when
// the protocol refuses with RefuseWithReset).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/pool_stats.h"
#include "base/status.h"
#include "event_loop.h"
#include "lwip/tcp.h"
#include "tcp_keepalive.h"
#include "tcp_pcb_util.h"

namespace firmware {

// The raw-API callbacks of a TcpService's connection: lwIP's `arg` is the slot, whose `service` and `pcb`
// members route each event to the service:
//   service->Receive(slot, p)  data, or p == nullptr for the peer's FIN;
//   service->Resume(slot)      an acknowledgement or lwIP's poll: output that waited may go now;
//   service->Lost(slot)        lwIP dropped the connection (RST, keepalive, retransmissions); the PCB is
//                              already freed and slot.pcb is null.
// Receive and Resume return ERR_ABRT when they aborted the PCB. A slot that no longer holds the PCB (it
// was closed meanwhile) is left alone.
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

template <typename Protocol, typename Connection, std::size_t kSlots, typename Counters>
class TcpService : public Service {
 public:
  // One accepted connection: the protocol's state plus what routes lwIP's callbacks to it.
  struct Slot : Connection {
    TcpService* service = nullptr;
    tcp_pcb* pcb = nullptr;  // null: the slot is free
  };

  TcpService(std::uint16_t port, const TcpKeepalive& keepalive) : port_(port), keepalive_(keepalive) {}
  TcpService(const TcpService&) = delete;
  TcpService& operator=(const TcpService&) = delete;

  // Listens on the port (no-op when listening). kResourceExhausted: no PCB; kFailedPrecondition: the
  // port is taken.
  base::Status Start() {
    if (listener_ != nullptr) return base::OkStatus();
    const base::Result<tcp_pcb*> listener = OpenTcpListener(port_, this, &TcpService::OnAccept);
    if (!listener.ok()) return listener.status();
    listener_ = *listener;
    return base::OkStatus();
  }
  // Closes the port and resets every connection.
  void Stop() {
    for (Slot& slot : slots_) {
      if (slot.pcb != nullptr) Abort(slot);
    }
    CloseTcpListener(listener_);
  }
  bool listening() const { return listener_ != nullptr; }

  // Now when a connection has work the loop must come back for at once (an answer the drive completed
  // in another service's Poll, a connection to close), else the core's deadline.
  hal::Micros NextDeadline() const override {
    for (const Slot& slot : slots_) {
      if (slot.pcb != nullptr && protocol().MustServeNow(slot)) return 0;
    }
    return protocol().CoreDeadline();
  }

  const Counters& counters() const { return counters_; }
  // The connection slots (docs/robustness.md "Exhaustion"): slots holding a PCB; refused: the protocol's
  // refusals.
  base::PoolStats slot_pool() const { return slot_marks_.Stats(SlotsHoldingPcb(slots_), slots_.size()); }

 protected:
  std::array<Slot, kSlots>& slots() { return slots_; }

  // The first slot without a PCB, or nullptr.
  Slot* FreeSlot() {
    for (Slot& slot : slots_) {
      if (slot.pcb == nullptr) return &slot;
    }
    return nullptr;
  }
  // Every slot is taken: reset this connection, the others are not touched.
  err_t RefuseWithReset(tcp_pcb* pcb) {
    ++counters_.refused;
    NoteRefused();
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  void NoteRefused() { slot_marks_.NoteRefused(); }

  // FIN after the data already queued (RST and ERR_ABRT without memory for the FIN).
  err_t Close(Slot& slot) {
    tcp_pcb* pcb = Detach(slot);
    return CloseOrAbortTcp(pcb);
  }
  // The card gives the connection up (the core said so): counted, then closed with FIN.
  err_t CloseByCard(Slot& slot) {
    ++counters_.closed_by_card;
    return Close(slot);
  }
  // RST.
  void Abort(Slot& slot) { tcp_abort(Detach(slot)); }

  Counters counters_{};

 private:
  friend struct TcpSlotCallbacks<Slot>;

  Protocol& protocol() { return static_cast<Protocol&>(*this); }
  const Protocol& protocol() const { return static_cast<const Protocol&>(*this); }

  // tcp_accept_fn: "Only return ERR_ABRT if you have called tcp_abort from within the callback".
  static err_t OnAccept(void* arg, tcp_pcb* pcb, err_t err) {
    if (arg == nullptr || pcb == nullptr || err != ERR_OK) return ERR_VAL;
    return static_cast<TcpService*>(arg)->Accept(pcb);
  }

  err_t Accept(tcp_pcb* pcb) {
    Slot* slot = protocol().OpenConnection(pcb);
    if (slot == nullptr) return protocol().RefuseConnection(pcb);
    slot->service = this;
    slot->pcb = pcb;
    AttachTcpConnection(pcb, slot, TcpSlotCallbacks<Slot>::kCallbacks, keepalive_);
    ++counters_.accepted;
    slot_marks_.NoteTaken(SlotsHoldingPcb(slots_));
    return ERR_OK;
  }

  // A null pbuf: the remote host closed the connection; requests it left unanswered go with it.
  err_t Receive(Slot& slot, pbuf* p) {
    if (p == nullptr) {
      ++counters_.closed_by_peer;
      return Close(slot);
    }
    const bool taken = protocol().TakeData(slot, *p);
    pbuf_free(p);
    if (!taken) {
      // Cannot happen while the window fits the protocol's buffer (each protocol's static_asserts).
      Abort(slot);
      return ERR_ABRT;
    }
    return protocol().Serve(slot);
  }

  err_t Resume(Slot& slot) { return protocol().Resume(slot); }

  void Lost(Slot& slot) {
    ++counters_.lost;
    protocol().Release(slot);
  }

  // Takes the PCB out of the slot with every callback nulled, and closes the core's connection.
  tcp_pcb* Detach(Slot& slot) {
    tcp_pcb* pcb = slot.pcb;
    DetachTcpCallbacks(pcb);
    slot.pcb = nullptr;
    protocol().Release(slot);
    return pcb;
  }

  std::uint16_t port_;
  TcpKeepalive keepalive_;
  tcp_pcb* listener_ = nullptr;
  std::array<Slot, kSlots> slots_{};
  base::PoolWatermark slot_marks_;
};

}  // namespace firmware
