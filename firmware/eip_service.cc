#include "eip_service.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "lwip/ip.h"
#include "lwip/pbuf.h"
#include "tcp_pcb_util.h"

namespace firmware {
namespace {

static_assert(cip::kMaxSessions == IPE_MAX_ENIP_SESSIONS, "lwipopts.h sizes pools for these sessions");
static_assert(cip::kMaxTcpConnections == IPE_ENIP_TCP_CONNECTIONS, "lwipopts.h sizes pools for these connections");
// One largest reply in flight per session is what lwipopts.h reserves heap for (IPE_HEAP_ENIP).
static_assert(cip::kMaxReplyMessage == IPE_ENIP_REPLY_BYTES, "lwipopts.h sizes the heap for this reply");
static_assert(cip::kMaxReplyMessage <= TCP_SND_BUF, "the largest reply must fit an empty send buffer");

cip::Ipv4Endpoint Endpoint(const ip_addr_t* address, u16_t port) {
  return {base::Ipv4Address(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(address)))), port};
}

}  // namespace

EipService::~EipService() { Stop(); }

base::Status EipService::Configure(const config::CardConfig& config) {
  if (config.protocol == config::Protocol::kEtherNetIp) return Start();
  Stop();
  return base::OkStatus();
}

base::Status EipService::Start() {
  if (listening()) return base::OkStatus();
  udp_pcb* udp = udp_new_ip_type(IPADDR_TYPE_V4);
  if (udp == nullptr) return base::ResourceExhausted();
  if (udp_bind(udp, IP4_ADDR_ANY, udp_port_) != ERR_OK) {
    udp_remove(udp);
    return base::FailedPrecondition();
  }
  const base::Status tcp = TcpService::Start();
  if (!tcp.ok()) {
    udp_remove(udp);
    return tcp;
  }
  udp_ = udp;
  udp_->tos = tos_;
  udp_recv(udp_, &EipService::OnUdp, this);
  return base::OkStatus();
}

void EipService::Stop() {
  TcpService::Stop();
  if (udp_ != nullptr) {
    udp_remove(udp_);
    udp_ = nullptr;
  }
}

void EipService::Poll(hal::Micros now) {
  cip::DueDatagram due;
  while (server_.TakeDueDatagram(now, due)) SendDatagram(due.to, due.bytes);
  cip::TcpConnectionId expired;
  while (server_.TakeExpiredConnection(now, expired)) {
    if (Slot* connection = FindConnection(expired)) {
      static_cast<void>(CloseByCard(*connection));
    } else {
      server_.CloseTcpConnection(expired);
    }
  }
  static_cast<void>(WriteHeldReply());
  for (Slot& connection : slots()) {
    if (connection.pcb != nullptr && (connection.input_size > 0 || connection.pending)) {
      static_cast<void>(Serve(connection));
    }
  }
}

bool EipService::MustServeNow(const Slot& connection) const {
  if (!CanTakeReply(connection)) return false;
  return connection.pending ? server_.ReadyToRetry(connection.id) : connection.input_size > 0;
}

EipService::Slot* EipService::OpenConnection(tcp_pcb* pcb) {
  Slot* connection = FreeSlot();
  if (connection == nullptr) return nullptr;
  const base::Result<cip::TcpConnectionId> id =
      server_.OpenTcpConnection(Endpoint(&pcb->remote_ip, pcb->remote_port), clock_.NowMicros());
  if (!id.ok()) return nullptr;
  connection->id = *id;
  pcb->tos = tos_;
  connection->input_size = 0;
  connection->close_after_reply = false;
  connection->pending = false;
  return connection;
}

bool EipService::TakeData(Slot& connection, const pbuf& p) {
  // The window is reopened only by consumed bytes, so a window's worth always fits.
  if (p.tot_len > connection.input.size() - connection.input_size) return false;
  pbuf_copy_partial(&p, connection.input.data() + connection.input_size, p.tot_len, 0);
  connection.input_size += p.tot_len;
  return true;
}

bool EipService::CanTakeReply(const Slot& connection) const {
  return held_reply_size_ == 0 && !connection.close_after_reply &&
         tcp_sndbuf(connection.pcb) >= cip::kMaxReplyMessage && tcp_sndqueuelen(connection.pcb) < TCP_SND_QUEUELEN;
}

bool EipService::WriteHeldReply() {
  if (held_reply_size_ == 0) return true;
  if (!WriteTcp(held_by_->pcb, std::span<const std::uint8_t>(held_reply_.data(), held_reply_size_))) return false;
  held_reply_size_ = 0;
  held_by_ = nullptr;
  return true;
}

err_t EipService::Serve(Slot& connection) {
  if (!WriteHeldReply()) return ERR_OK;
  if (connection.close_after_reply) return CloseByCard(connection);
  const hal::Micros now = clock_.NowMicros();
  std::size_t consumed_total = 0;
  while (CanTakeReply(connection)) {
    cip::TcpStep step;
    const bool retry = connection.pending;
    if (retry) {
      // The message is in the core already; its reply waits for drive accesses.
      if (!server_.ReadyToRetry(connection.id)) break;
      step = server_.RetryTcp(connection.id, now);
      ++counters_.deferred_retries;
    } else {
      if (connection.input_size <= consumed_total) break;
      const std::span<const std::uint8_t> input(connection.input.data() + consumed_total,
                                                connection.input_size - consumed_total);
      step = server_.OnTcpData(connection.id, input, now);
    }
    consumed_total += step.consumed;
    if (step.pending && !connection.pending) ++counters_.deferred_replies;
    connection.pending = step.pending;
    if (!step.reply.empty() && !WriteTcp(connection.pcb, step.reply)) {
      // The core's reply buffer is reused by the next call: keep a copy (CanTakeReply stops the loop).
      ++counters_.write_stalls;
      std::memcpy(held_reply_.data(), step.reply.data(), step.reply.size());
      held_reply_size_ = step.reply.size();
      held_by_ = &connection;
    }
    if (step.close) {
      connection.close_after_reply = true;
      break;
    }
    if (step.pending) break;
    if (!retry && step.consumed == 0 && step.reply.empty()) break;  // cannot happen with input left; be safe
  }
  if (consumed_total > 0) {
    std::memmove(connection.input.data(), connection.input.data() + consumed_total,
                 connection.input_size - consumed_total);
    connection.input_size -= consumed_total;
    ReopenTcpWindow(connection.pcb, consumed_total);
  }
  if (connection.close_after_reply && held_by_ != &connection) return CloseByCard(connection);
  return ERR_OK;
}

void EipService::Release(Slot& connection) {
  if (held_by_ == &connection) {
    held_reply_size_ = 0;
    held_by_ = nullptr;
  }
  server_.CloseTcpConnection(connection.id);
}

EipService::Slot* EipService::FindConnection(cip::TcpConnectionId id) {
  for (Slot& connection : slots()) {
    if (connection.pcb != nullptr && connection.id == id) return &connection;
  }
  return nullptr;
}

void EipService::OnUdp(void* arg, udp_pcb* pcb, pbuf* p, const ip_addr_t* address, u16_t port) {
  auto* service = static_cast<EipService*>(arg);
  if (service == nullptr || service->udp_ != pcb) {
    pbuf_free(p);
    return;
  }
  service->ReceiveDatagram(p, address, port);
}

void EipService::ReceiveDatagram(pbuf* p, const ip_addr_t* address, u16_t port) {
  ++counters_.udp_received;
  if (p->tot_len > datagram_.size()) {
    // Longer than any request the core accepts (it would drop it too).
    ++counters_.udp_dropped;
    pbuf_free(p);
    return;
  }
  const std::size_t length = pbuf_copy_partial(p, datagram_.data(), p->tot_len, 0);
  pbuf_free(p);
  // Valid during the receive callback: where the datagram was sent to.
  const ip_addr_t* destination = ip_current_dest_addr();
  cip::UdpSource source;
  source.peer = Endpoint(address, port);
  source.broadcast = ip_addr_isbroadcast(destination, ip_current_input_netif()) || ip_addr_ismulticast(destination);
  const cip::UdpDecision decision =
      server_.OnUdpDatagram(std::span<const std::uint8_t>(datagram_.data(), length), source, clock_.NowMicros());
  if (decision.action == cip::UdpDecision::Action::kSendNow) SendDatagram(source.peer, decision.reply);
}

void EipService::SendDatagram(const cip::Ipv4Endpoint& to, std::span<const std::uint8_t> bytes) {
  if (udp_ == nullptr) return;
  pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(bytes.size()), PBUF_RAM);
  if (p == nullptr) {
    ++counters_.udp_dropped;
    return;
  }
  pbuf_take(p, bytes.data(), static_cast<u16_t>(bytes.size()));
  ip_addr_t address;
  ip_addr_set_ip4_u32_val(address, lwip_htonl(to.address.HostOrder()));
  if (udp_sendto(udp_, p, &address, to.port) == ERR_OK) {
    ++counters_.udp_sent;
  } else {
    ++counters_.udp_dropped;
  }
  pbuf_free(p);
}

}  // namespace firmware
