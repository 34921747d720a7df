// A TcpService (tcp_service.h) over a protocol core that keeps each connection's byte stream itself
// (modbus::Server, web::HttpServer): received bytes go into the core at once, the window reopens by what
// the core has released, and its pending output is written while the protocol's send room allows. The
// core has Receive, TakeReleasedInput, PendingOutput, ConsumeOutput, MustClose, Close, Poll and
// NextDeadline for a connection id that is also its slot's index.
//
// Besides OpenConnection and RefuseConnection (TcpService), the protocol deriving from it writes:
//   std::size_t SendRoom(tcp_pcb*)        how many bytes TCP may take now (0: wait for an acknowledgement)
// and may replace (by declaring its own) the defaults:
//   std::size_t ReleasedInput(Slot&)      bytes the core is done with: core.TakeReleasedInput(id)
//   void LoadOutput(Slot&, Micros now)    before the output is read: nothing
//   u8_t WriteFlags(const Slot&)          tcp_write's flags: TCP_WRITE_FLAG_COPY
// Counters also need write_errors (tcp_write refused: retried on the next acknowledgement or poll).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/clock.h"
#include "tcp_pcb_util.h"
#include "tcp_service.h"

namespace firmware {

template <typename Id>
struct StreamTcpConnection {
  Id id = 0;
  // The last attempt to hand output to TCP could not write everything: wait for an acknowledgement
  // (sent callback) or lwIP's poll instead of asking the loop to come back at once.
  bool stalled = false;
};

template <typename Protocol, typename Core, typename Id, std::size_t kSlots, typename Counters>
class StreamTcpService : public TcpService<Protocol, StreamTcpConnection<Id>, kSlots, Counters> {
  using Base = TcpService<Protocol, StreamTcpConnection<Id>, kSlots, Counters>;

 public:
  using typename Base::Slot;

  // The core's timers, then every connection: output completed meanwhile (a drive access answered in
  // another service's Poll) goes out.
  void Poll(hal::Micros now) override {
    core_.Poll(now);
    for (Slot& slot : this->slots()) {
      if (slot.pcb != nullptr) static_cast<void>(Serve(slot));
    }
  }

 protected:
  StreamTcpService(Core& core, const hal::Clock& clock, std::uint16_t port, const TcpKeepalive& keepalive)
      : Base(port, keepalive), core_(core), clock_(clock) {}

  // The slot of a connection the core opened as `id`.
  Slot* SlotFor(Id id) {
    Slot& slot = this->slots()[id];
    slot.id = id;
    slot.stalled = false;
    return &slot;
  }

  std::size_t ReleasedInput(Slot& slot) { return core_.TakeReleasedInput(slot.id); }
  void LoadOutput(Slot&, hal::Micros) {}
  u8_t WriteFlags(const Slot&) const { return TCP_WRITE_FLAG_COPY; }

  Core& core_;
  const hal::Clock& clock_;

 private:
  friend Base;

  Protocol& protocol() { return static_cast<Protocol&>(*this); }

  // Always taken whole while the window fits the core's buffer (each protocol's static_asserts).
  bool TakeData(Slot& slot, const pbuf& p) {
    const hal::Micros now = clock_.NowMicros();
    return ForEachPbufSegment(
        p, [&](std::span<const std::uint8_t> bytes) { return core_.Receive(slot.id, bytes, now) == bytes.size(); });
  }

  // Reopens the window, hands output to TCP, closes the connection when the core says so.
  err_t Serve(Slot& slot) {
    const hal::Micros now = clock_.NowMicros();
    while (true) {
      ReopenTcpWindow(slot.pcb, protocol().ReleasedInput(slot));
      protocol().LoadOutput(slot, now);
      const std::span<const std::uint8_t> output = core_.PendingOutput(slot.id);
      if (output.empty()) break;
      const std::size_t count = std::min(output.size(), protocol().SendRoom(slot.pcb));
      if (count == 0) {
        slot.stalled = true;
        break;
      }
      if (!WriteTcp(slot.pcb, output.first(count), protocol().WriteFlags(slot))) {
        ++this->counters_.write_errors;
        slot.stalled = true;
        break;
      }
      // Taking output out may let the core serve the next request at once.
      core_.ConsumeOutput(slot.id, count, now);
    }
    if (core_.MustClose(slot.id)) return this->CloseByCard(slot);
    return ERR_OK;
  }

  err_t Resume(Slot& slot) {
    slot.stalled = false;
    return Serve(slot);
  }

  void Release(Slot& slot) { core_.Close(slot.id); }

  // Output waiting that TCP may take, or a connection to close: the loop comes back at once.
  bool MustServeNow(const Slot& slot) const {
    return core_.MustClose(slot.id) || (!slot.stalled && !core_.PendingOutput(slot.id).empty());
  }

  hal::Micros CoreDeadline() const { return core_.NextDeadline(); }
};

}  // namespace firmware
