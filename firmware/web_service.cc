#include "web_service.h"

#include <optional>

#include "lwipopts.h"

namespace firmware {
namespace {

static_assert(web::kMaxHttpClients == IPE_MAX_HTTP_CLIENTS, "lwipopts.h sizes pools for these clients");
static_assert(web::kHttpReceiveBufferBytes >= TCP_WND, "a whole window must fit the receive buffer");
// lwIP announces a reopened window only in steps of TCP_WND / 2: the buffer's room beyond the largest
// request must cover one step, or the last bytes of a request at the limits could never be sent.
static_assert(web::kHttpReceiveSlack >= TCP_WND / 2, "the receive buffer needs half a window beyond a request");

}  // namespace

WebService::~WebService() { Stop(); }

base::Status WebService::Configure(const config::CardConfig& config) {
  if (config.web_server) return Start();
  Stop();
  return base::OkStatus();
}

// Every slot taken: the connection idle longest between requests makes room (closed with FIN).
WebService::Slot* WebService::OpenConnection(tcp_pcb*) {
  const hal::Micros now = clock_.NowMicros();
  base::Result<web::HttpClientId> id = core_.Open(now);
  if (!id.ok()) {
    const std::optional<web::HttpClientId> idle = core_.IdleClientToEvict();
    if (!idle) return nullptr;
    for (Slot& other : slots()) {
      if (other.pcb != nullptr && other.id == *idle) {
        ++counters_.evicted;
        static_cast<void>(Close(other));
        break;
      }
    }
    id = core_.Open(now);
    if (!id.ok()) return nullptr;
  }
  return SlotFor(*id);
}

// Every slot is busy with a request: a 503 from flash, then FIN. lwIP's defaults (tcp_recv_null) take
// whatever the client still sends.
err_t WebService::RefuseConnection(tcp_pcb* pcb) {
  ++counters_.refused_busy;
  NoteRefused();
  tcp_arg(pcb, nullptr);
  if (!WriteTcp(pcb, web::HttpServer::BusyResponse(), 0)) {
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  return CloseOrAbortTcp(pcb);
}

// At most a window at a time: the window never offers more than the buffer's free space.
std::size_t WebService::ReleasedInput(Slot& client) { return core_.TakeReleasedInput(client.id, TCP_WND); }

// A streamed body's next chunk, no larger than TCP takes now: copied at once, the buffer is free again.
void WebService::LoadOutput(Slot& client, hal::Micros now) {
  core_.LoadStreamChunk(client.id, tcp_sndbuf(client.pcb), now);
}

// The head lives in the server's response buffer, reused for the next answer: copied. A body from flash
// is referenced (lwIP keeps a ROM pbuf pointing at it).
u8_t WebService::WriteFlags(const Slot& client) const {
  return core_.PendingOutputIsStatic(client.id) ? 0 : TCP_WRITE_FLAG_COPY;
}

// At most TCP_SND_BUF bytes in TCP_SND_QUEUELEN segments wait for acknowledgement.
std::size_t WebService::SendRoom(tcp_pcb* pcb) const {
  return tcp_sndqueuelen(pcb) >= TCP_SND_QUEUELEN ? 0 : tcp_sndbuf(pcb);
}

}  // namespace firmware
