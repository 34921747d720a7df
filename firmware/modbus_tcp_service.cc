#include "modbus_tcp_service.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "ipv4_lwip.h"
#include "lwip/ip.h"
#include "lwipopts.h"
#include "tcp_pcb_util.h"

namespace firmware {
namespace {

// Everything TCP may deliver fits into the server: the window is never larger than its buffer.
static_assert(modbus::kReceiveBufferBytes >= TCP_WND, "the Modbus receive buffer must hold a whole TCP window");
// lwIP reopens a window only in steps of TCP_WND / 2 (silly window avoidance): a full buffer that ends in
// a partial ADU must free that much by answering the whole ADUs before it, or the window never reopens.
static_assert(modbus::kReceiveBufferBytes - (modbus::kMaxAduBytes - 1) >= TCP_WND / 2,
              "a partial ADU must leave half a window of answerable requests in the buffer");
static_assert(modbus::kMaxAduBytes == IPE_MODBUS_ADU_BYTES, "lwipopts.h sizes the heap for this ADU");
static_assert(ModbusTcpService::kMaxUnacknowledgedBytes == IPE_MODBUS_UNACKED_BYTES,
              "lwipopts.h sizes the heap for this many unacknowledged bytes");
static_assert(modbus::Server::kMaxClients == IPE_MAX_MODBUS_CLIENTS, "lwipopts.h sizes pools for these clients");

base::Ipv4Address PeerAddress(const tcp_pcb* pcb) {
  return FromLwip(ip_2_ip4(&pcb->remote_ip));
}

}  // namespace

base::Status ModbusTcpService::Configure(const drive_link::CardConfig& config) {
  server_.Configure(config);
  if (config.protocol == drive_link::Protocol::kModbusTcp) return Start();
  Stop();
  return base::OkStatus();
}

base::Status ModbusTcpService::Start() {
  if (listener_ != nullptr) return base::OkStatus();
  const base::Result<tcp_pcb*> listener = OpenTcpListener(options_.port, this, &ModbusTcpService::OnAccept);
  if (!listener.ok()) return listener.status();
  listener_ = *listener;
  return base::OkStatus();
}

void ModbusTcpService::Stop() {
  for (Client& client : clients_) {
    if (client.pcb != nullptr) Abort(client);
  }
  CloseTcpListener(listener_);
}

void ModbusTcpService::Poll(hal::Micros now) {
  server_.Poll(now);
  for (Client& client : clients_) {
    if (client.pcb != nullptr) static_cast<void>(Flush(client));
  }
}

hal::Micros ModbusTcpService::NextDeadline() const {
  // Answers completed by the drive (in another service's Poll) go out on the next pass, at once.
  for (const Client& client : clients_) {
    if (client.pcb == nullptr) continue;
    if (server_.MustClose(client.id)) return 0;
    if (!client.stalled && !server_.PendingOutput(client.id).empty()) return 0;
  }
  return server_.NextDeadline();
}

// tcp_accept_fn: "Only return ERR_ABRT if you have called tcp_abort from within the callback".
err_t ModbusTcpService::OnAccept(void* arg, tcp_pcb* pcb, err_t err) {
  if (arg == nullptr || pcb == nullptr || err != ERR_OK) return ERR_VAL;
  return static_cast<ModbusTcpService*>(arg)->Accept(pcb);
}

err_t ModbusTcpService::Accept(tcp_pcb* pcb) {
  const base::Result<modbus::ConnectionId> id = server_.Open(PeerAddress(pcb), clock_.NowMicros());
  if (!id.ok()) {
    // Every slot is taken: reset this one, the others are not touched.
    ++counters_.refused;
    slot_marks_.NoteRefused();
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  Client& client = clients_[*id];
  client = Client{this, pcb, *id, false};
  AttachTcpConnection(pcb, &client, TcpSlotCallbacks<Client>::kCallbacks, options_.keepalive);
  ++counters_.accepted;
  slot_marks_.NoteTaken(SlotsHoldingPcb(clients_));
  return ERR_OK;
}

// A null pbuf: the remote host closed the connection.
err_t ModbusTcpService::Receive(Client& client, pbuf* p) {
  if (p == nullptr) {
    // The client is done. Requests it left unanswered are dropped with the connection.
    ++counters_.closed_by_peer;
    return Close(client);
  }
  const hal::Micros now = clock_.NowMicros();
  bool all_taken = true;
  for (const pbuf* q = p; q != nullptr && all_taken; q = q->next) {
    const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(q->payload), q->len);
    all_taken = server_.Receive(client.id, bytes, now) == bytes.size();
  }
  pbuf_free(p);
  if (!all_taken) {
    // Cannot happen while the window fits the server's buffer (static_assert above).
    Abort(client);
    return ERR_ABRT;
  }
  return Flush(client);
}

err_t ModbusTcpService::Resume(Client& client) {
  client.stalled = false;
  return Flush(client);
}

void ModbusTcpService::Lost(Client& client) {
  ++counters_.lost;
  server_.Close(client.id);
}

err_t ModbusTcpService::Flush(Client& client) {
  const hal::Micros now = clock_.NowMicros();
  bool progress = true;
  while (progress) {
    progress = false;
    // Reopen the window by what the server is done with.
    for (std::size_t released = server_.TakeReleasedInput(client.id); released > 0;) {
      const auto chunk = static_cast<u16_t>(std::min<std::size_t>(released, 0xFFFF));
      tcp_recved(client.pcb, chunk);
      released -= chunk;
    }
    const std::span<const std::uint8_t> answers = server_.PendingOutput(client.id);
    if (answers.empty()) break;
    const std::size_t in_flight = TCP_SND_BUF - tcp_sndbuf(client.pcb);
    std::size_t room = in_flight >= kMaxUnacknowledgedBytes ? 0 : kMaxUnacknowledgedBytes - in_flight;
    if (tcp_sndqueuelen(client.pcb) >= kMaxQueuedSegments) room = 0;
    const std::size_t count = std::min({answers.size(), room, static_cast<std::size_t>(tcp_sndbuf(client.pcb))});
    if (count == 0) {
      client.stalled = true;
      break;
    }
    if (tcp_write(client.pcb, answers.data(), static_cast<u16_t>(count), TCP_WRITE_FLAG_COPY) != ERR_OK) {
      ++counters_.write_errors;
      client.stalled = true;
      break;
    }
    tcp_output(client.pcb);
    // Taking answers out may let the server serve the next request at once.
    server_.ConsumeOutput(client.id, count, now);
    progress = true;
  }
  if (server_.MustClose(client.id)) {
    ++counters_.closed_by_card;
    return Close(client);
  }
  return ERR_OK;
}

err_t ModbusTcpService::Close(Client& client) {
  tcp_pcb* pcb = client.pcb;
  DetachTcpCallbacks(pcb);
  client.pcb = nullptr;
  server_.Close(client.id);
  return CloseOrAbortTcp(pcb);
}

void ModbusTcpService::Abort(Client& client) {
  tcp_pcb* pcb = client.pcb;
  DetachTcpCallbacks(pcb);
  client.pcb = nullptr;
  server_.Close(client.id);
  tcp_abort(pcb);
}

}  // namespace firmware
