#include "io_service.h"

#include <span>

#include "cip/qos_object.h"
#include "lwip/pbuf.h"

namespace firmware {

base::Status IoService::Configure(const config::CardConfig& config) {
  if (config.protocol == config::Protocol::kEtherNetIp) return Start();
  Stop();
  return base::OkStatus();
}

base::Status IoService::Start() {
  if (pcb_ != nullptr) return base::OkStatus();
  udp_pcb* pcb = udp_new_ip_type(IPADDR_TYPE_V4);
  if (pcb == nullptr) return base::ResourceExhausted();
  if (udp_bind(pcb, IP4_ADDR_ANY, port_) != ERR_OK) {
    udp_remove(pcb);
    return base::FailedPrecondition();
  }
  pcb_ = pcb;
  udp_recv(pcb_, &IoService::OnUdp, this);
  return base::OkStatus();
}

void IoService::Stop() {
  if (pcb_ == nullptr) return;
  udp_remove(pcb_);
  pcb_ = nullptr;
}

void IoService::Poll(hal::Micros now) {
  // Productions are due even while the port is closed (c500 changed under open connections): they
  // are taken, so the schedule stays on its grid, and not sent.
  cip::IoDatagram datagram;
  while (manager_.TakeDueProduction(now, datagram)) Send(datagram);
}

hal::Micros IoService::NextDeadline() const { return manager_.NextDeadline(); }

void IoService::OnUdp(void* arg, udp_pcb* pcb, pbuf* p, const ip_addr_t* address, u16_t port) {
  auto* service = static_cast<IoService*>(arg);
  if (service == nullptr || service->pcb_ != pcb) {
    pbuf_free(p);
    return;
  }
  service->Receive(p, address, port);
}

void IoService::Receive(pbuf* p, const ip_addr_t* address, u16_t port) {
  ++counters_.received;
  if (p->tot_len > datagram_.size()) {
    ++counters_.too_long;
    pbuf_free(p);
    return;
  }
  const std::size_t length = pbuf_copy_partial(p, datagram_.data(), p->tot_len, 0);
  pbuf_free(p);
  const cip::Ipv4Endpoint from{base::Ipv4Address(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(address)))), port};
  manager_.OnIoDatagram(std::span<const std::uint8_t>(datagram_.data(), length), from, clock_.NowMicros());
}

void IoService::Send(const cip::IoDatagram& datagram) {
  if (pcb_ == nullptr) return;
  pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(datagram.bytes.size()), PBUF_RAM);
  if (p == nullptr) {
    ++counters_.send_failed;
    return;
  }
  pbuf_take(p, datagram.bytes.data(), static_cast<u16_t>(datagram.bytes.size()));
  ip_addr_t address;
  ip_addr_set_ip4_u32_val(address, lwip_htonl(datagram.to.address.HostOrder()));
  if (datagram.multicast) udp_set_multicast_ttl(pcb_, ttl_.MulticastTtl());
  pcb_->tos = qos_ == nullptr ? 0 : cip::TosOfDscp(cip::DscpForPriority(*qos_, datagram.priority));
  if (udp_sendto(pcb_, p, &address, datagram.to.port) == ERR_OK) {
    ++counters_.sent;
  } else {
    ++counters_.send_failed;
  }
  pbuf_free(p);
}

}  // namespace firmware
