#include "modbus_tcp_service.h"

#include <algorithm>
#include <cstring>

#include "ipv4_lwip.h"
#include "lwip/ip.h"
#include "lwipopts.h"

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

ModbusTcpService::~ModbusTcpService() { Stop(); }

base::Status ModbusTcpService::Configure(const config::CardConfig& config) {
  core_.Configure(config);
  if (config.protocol == config::Protocol::kModbusTcp) return Start();
  Stop();
  return base::OkStatus();
}

ModbusTcpService::Slot* ModbusTcpService::OpenConnection(tcp_pcb* pcb) {
  const base::Result<modbus::ConnectionId> id = core_.Open(PeerAddress(pcb), clock_.NowMicros());
  return id.ok() ? SlotFor(*id) : nullptr;
}

// At most kMaxUnacknowledgedBytes in kMaxQueuedSegments wait for the peer's acknowledgement.
std::size_t ModbusTcpService::SendRoom(tcp_pcb* pcb) const {
  if (tcp_sndqueuelen(pcb) >= kMaxQueuedSegments) return 0;
  const std::size_t in_flight = TCP_SND_BUF - tcp_sndbuf(pcb);
  const std::size_t room = in_flight >= kMaxUnacknowledgedBytes ? 0 : kMaxUnacknowledgedBytes - in_flight;
  return std::min<std::size_t>(room, tcp_sndbuf(pcb));
}

}  // namespace firmware
