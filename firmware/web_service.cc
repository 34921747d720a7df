#include "web_service.h"

#include <algorithm>
#include <span>

#include "lwipopts.h"
#include "tcp_pcb_util.h"

namespace firmware {
namespace {

static_assert(web::kMaxHttpClients == IPE_MAX_HTTP_CLIENTS, "lwipopts.h sizes pools for these clients");
static_assert(web::kHttpReceiveBufferBytes >= TCP_WND, "a whole window must fit the receive buffer");
// lwIP announces a reopened window only in steps of TCP_WND / 2: the buffer's room beyond the largest
// request must cover one step, or the last bytes of a request at the limits could never be sent.
static_assert(web::kHttpReceiveSlack >= TCP_WND / 2, "the receive buffer needs half a window beyond a request");

}  // namespace

base::Status WebService::Configure(const config::CardConfig& config) {
  if (config.web_server) return Start();
  Stop();
  return base::OkStatus();
}

base::Status WebService::Start() {
  if (listener_ != nullptr) return base::OkStatus();
  const base::Result<tcp_pcb*> listener = OpenTcpListener(options_.port, this, &WebService::OnAccept);
  if (!listener.ok()) return listener.status();
  listener_ = *listener;
  return base::OkStatus();
}

void WebService::Stop() {
  for (Client& client : clients_) {
    if (client.pcb != nullptr) Abort(client);
  }
  CloseTcpListener(listener_);
}

void WebService::Poll(hal::Micros now) {
  server_.Poll(now);
  for (Client& client : clients_) {
    if (client.pcb != nullptr) static_cast<void>(Flush(client));
  }
}

hal::Micros WebService::NextDeadline() const {
  for (const Client& client : clients_) {
    if (client.pcb == nullptr) continue;
    if (server_.MustClose(client.id)) return 0;
    if (!client.stalled && !server_.PendingOutput(client.id).empty()) return 0;
  }
  return server_.NextDeadline();
}

err_t WebService::OnAccept(void* arg, tcp_pcb* pcb, err_t err) {
  if (arg == nullptr || pcb == nullptr || err != ERR_OK) return ERR_VAL;
  return static_cast<WebService*>(arg)->Accept(pcb);
}

err_t WebService::Accept(tcp_pcb* pcb) {
  const hal::Micros now = clock_.NowMicros();
  base::Result<web::HttpClientId> id = server_.Open(now);
  if (!id.ok()) {
    const std::optional<web::HttpClientId> idle = server_.IdleClientToEvict();
    if (!idle) return RefuseBusy(pcb);
    for (Client& other : clients_) {
      if (other.pcb != nullptr && other.id == *idle) {
        ++counters_.evicted;
        static_cast<void>(Close(other));
        break;
      }
    }
    id = server_.Open(now);
    if (!id.ok()) return RefuseBusy(pcb);
  }
  Client& client = clients_[*id];
  client = Client{this, pcb, *id, false};
  AttachTcpConnection(pcb, &client, TcpSlotCallbacks<Client>::kCallbacks, options_.keepalive);
  ++counters_.accepted;
  slot_marks_.NoteTaken(SlotsHoldingPcb(clients_));
  return ERR_OK;
}

// Every slot is busy with a request: a 503 from flash, then FIN. lwIP's defaults (tcp_recv_null) take
// whatever the client still sends.
err_t WebService::RefuseBusy(tcp_pcb* pcb) {
  ++counters_.refused_busy;
  slot_marks_.NoteRefused();
  const std::span<const std::uint8_t> busy = web::HttpServer::BusyResponse();
  tcp_arg(pcb, nullptr);
  if (tcp_write(pcb, busy.data(), static_cast<u16_t>(busy.size()), 0) != ERR_OK) {
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  tcp_output(pcb);
  return CloseOrAbortTcp(pcb);
}

err_t WebService::Receive(Client& client, pbuf* p) {
  if (p == nullptr) {
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
    // Cannot happen: the window never offers more than the buffer's free space (TakeReleasedInput).
    Abort(client);
    return ERR_ABRT;
  }
  return Flush(client);
}

err_t WebService::Resume(Client& client) {
  client.stalled = false;
  return Flush(client);
}

void WebService::Lost(Client& client) {
  ++counters_.lost;
  server_.Close(client.id);
}

err_t WebService::Flush(Client& client) {
  const hal::Micros now = clock_.NowMicros();
  bool progress = true;
  while (progress) {
    progress = false;
    for (std::size_t released = server_.TakeReleasedInput(client.id, TCP_WND); released > 0;) {
      const auto chunk = static_cast<u16_t>(std::min<std::size_t>(released, 0xFFFF));
      tcp_recved(client.pcb, chunk);
      released -= chunk;
    }
    // A streamed body's next chunk, no larger than TCP takes now: copied at once, the buffer is free again.
    server_.LoadStreamChunk(client.id, tcp_sndbuf(client.pcb), now);
    const std::span<const std::uint8_t> output = server_.PendingOutput(client.id);
    if (output.empty()) break;
    const std::size_t count = std::min<std::size_t>(output.size(), tcp_sndbuf(client.pcb));
    if (count == 0 || tcp_sndqueuelen(client.pcb) >= TCP_SND_QUEUELEN) {
      client.stalled = true;
      break;
    }
    // The head lives in the server's response buffer, reused for the next answer: copied. A body from
    // flash is referenced (lwIP keeps a ROM pbuf pointing at it).
    const u8_t flags = server_.PendingOutputIsStatic(client.id) ? 0 : TCP_WRITE_FLAG_COPY;
    if (tcp_write(client.pcb, output.data(), static_cast<u16_t>(count), flags) != ERR_OK) {
      ++counters_.write_errors;
      client.stalled = true;
      break;
    }
    tcp_output(client.pcb);
    server_.ConsumeOutput(client.id, count, now);
    progress = true;
  }
  if (server_.MustClose(client.id)) {
    ++counters_.closed_by_card;
    return Close(client);
  }
  return ERR_OK;
}

err_t WebService::Close(Client& client) {
  tcp_pcb* pcb = client.pcb;
  DetachTcpCallbacks(pcb);
  client.pcb = nullptr;
  server_.Close(client.id);
  return CloseOrAbortTcp(pcb);
}

void WebService::Abort(Client& client) {
  tcp_pcb* pcb = client.pcb;
  DetachTcpCallbacks(pcb);
  client.pcb = nullptr;
  server_.Close(client.id);
  tcp_abort(pcb);
}

}  // namespace firmware
