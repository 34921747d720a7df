#include "card_ring.h"

#include "ipv4_lwip.h"
#include "lwip/netif.h"

namespace firmware {
namespace {

// Ports of the switch and DLR ring ports: L is ring port 1 (index 0), R ring port 2 (index 1).
hal::PortId PortOf(std::size_t ring_port) { return ring_port == 0 ? hal::PortId::kLeft : hal::PortId::kRight; }

}  // namespace

CardRing::CardRing(CardNetif& netif, const hal::Clock& clock)
    : netif_(netif), clock_(clock), node_(netif.port().Mac()) {}

bool CardRing::Claims(std::span<const std::uint8_t> frame) const { return net::IsDlrFrame(frame); }

bool CardRing::OnFrame(std::span<const std::uint8_t> frame, hal::PortId port) {
  const hal::Micros now = clock_.NowMicros();
  node_.SetIpAddress(FromLwip(netif_ip4_addr(&netif_.lwip_netif())));
  const std::size_t ring_port = hal::PortIndex(port);
  const net::DlrReceive receive = node_.OnFrame(frame, ring_port, now);
  Flush(receive.flush_learning_table);
  if (receive.sign_on) {
    std::array<std::uint8_t, hal::kMaxFrameBytes> sign_on_frame;
    if (const std::optional<net::DlrTransmit> sign_on = node_.ForwardSignOn(frame, ring_port, sign_on_frame)) {
      Send(*sign_on, sign_on_frame);
    }
  }
  SendQueued(now);
  return receive.forward;
}

void CardRing::OnLinkChange(hal::PortId port, bool up) {
  const hal::Micros now = clock_.NowMicros();
  Flush(node_.OnLinkChange(hal::PortIndex(port), up, now));
  SendQueued(now);
}

void CardRing::Poll(hal::Micros now) {
  node_.SetIpAddress(FromLwip(netif_ip4_addr(&netif_.lwip_netif())));
  Flush(node_.Poll(now));
  SendQueued(now);
}

void CardRing::SendQueued(hal::Micros now) {
  // The queue is fixed (DlrRingNode::kTransmitQueue): this loop ends.
  while (const std::optional<net::DlrTransmit> transmit = node_.NextTransmit(buffer_, now)) Send(*transmit, buffer_);
}

void CardRing::Send(const net::DlrTransmit& transmit, std::span<const std::uint8_t> buffer) {
  if (netif_.SendFrameOn(PortOf(transmit.port), buffer.first(transmit.length))) {
    ++frames_sent_;
  } else {
    ++send_failures_;
  }
}

void CardRing::Flush(bool wanted) {
  if (wanted) netif_.FlushLearningTable();
}

cip::DlrObjectValues CardRing::DlrValues() const {
  const net::DlrRingStatus& s = node_.status();
  cip::DlrObjectValues values;
  values.network_topology = static_cast<std::uint8_t>(s.topology);
  values.network_status = static_cast<std::uint8_t>(s.network_status);
  if (s.supervisor_known) {
    values.supervisor_ip = s.supervisor.ip.HostOrder();
    values.supervisor_mac = s.supervisor.mac;
    values.supervisor_precedence = s.supervisor.precedence;
  }
  return values;
}

}  // namespace firmware
