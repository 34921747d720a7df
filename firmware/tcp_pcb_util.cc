#include "tcp_pcb_util.h"

#include <algorithm>

namespace firmware {

base::Result<tcp_pcb*> OpenTcpListener(std::uint16_t port, void* arg, tcp_accept_fn accept) {
  tcp_pcb* pcb = tcp_new_ip_type(IPADDR_TYPE_V4);
  if (pcb == nullptr) return base::ResourceExhausted();
  // Connections of an earlier listener on this port may still be in TIME_WAIT (lwipopts.h SO_REUSE).
  ip_set_option(pcb, SOF_REUSEADDR);
  if (tcp_bind(pcb, IP4_ADDR_ANY, port) != ERR_OK) {
    tcp_close(pcb);
    return base::FailedPrecondition();
  }
  err_t err = ERR_OK;
  tcp_pcb* listener = tcp_listen_with_backlog_and_err(pcb, TCP_DEFAULT_LISTEN_BACKLOG, &err);
  if (listener == nullptr) {
    tcp_close(pcb);
    return base::ResourceExhausted();
  }
  tcp_arg(listener, arg);
  tcp_accept(listener, accept);
  return listener;
}

void CloseTcpListener(tcp_pcb*& listener) {
  if (listener == nullptr) return;
  tcp_arg(listener, nullptr);
  tcp_accept(listener, nullptr);
  tcp_close(listener);  // a listening PCB is always freed
  listener = nullptr;
}

void AttachTcpConnection(tcp_pcb* pcb, void* arg, const TcpCallbacks& callbacks, const TcpKeepalive& keepalive) {
  tcp_arg(pcb, arg);
  tcp_recv(pcb, callbacks.recv);
  tcp_sent(pcb, callbacks.sent);
  tcp_err(pcb, callbacks.err);
  tcp_poll(pcb, callbacks.poll, kTcpPollInterval);
  tcp_nagle_disable(pcb);
  ApplyKeepalive(pcb, keepalive);
}

void DetachTcpCallbacks(tcp_pcb* pcb) {
  tcp_arg(pcb, nullptr);
  tcp_recv(pcb, nullptr);
  tcp_sent(pcb, nullptr);
  tcp_err(pcb, nullptr);
  tcp_poll(pcb, nullptr, 0);
}

err_t DiscardTcpData(tcp_pcb* pcb, pbuf* p) {
  if (p != nullptr) {
    tcp_recved(pcb, p->tot_len);
    pbuf_free(p);
  }
  return ERR_OK;
}

void ReopenTcpWindow(tcp_pcb* pcb, std::size_t released) {
  while (released > 0) {
    const auto chunk = static_cast<u16_t>(std::min<std::size_t>(released, 0xFFFF));
    tcp_recved(pcb, chunk);
    released -= chunk;
  }
}

bool WriteTcp(tcp_pcb* pcb, std::span<const std::uint8_t> bytes, u8_t flags) {
  if (tcp_write(pcb, bytes.data(), static_cast<u16_t>(bytes.size()), flags) != ERR_OK) return false;
  tcp_output(pcb);
  return true;
}

err_t CloseOrAbortTcp(tcp_pcb* pcb) {
  if (tcp_close(pcb) != ERR_OK) {
    tcp_abort(pcb);
    return ERR_ABRT;
  }
  return ERR_OK;
}

}  // namespace firmware
