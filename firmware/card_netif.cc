#include "card_netif.h"

#include <array>
#include <cstring>

#include "cip/qos_object.h"
#include "ipv4_lwip.h"
#include "lwip/etharp.h"
#include "lwip/igmp.h"
#include "lwip/pbuf.h"
#include "lwip/sys.h"
#include "netif/ethernet.h"

namespace firmware {
namespace {

// Broadcast and multicast destinations have the group bit (bit 0 of the first octet) set.
bool IsGroupAddress(std::span<const std::uint8_t> frame) { return !frame.empty() && (frame[0] & 0x01) != 0; }

}  // namespace

CardNetif::~CardNetif() {
  if (added_) netif_remove(&netif_);
}

void CardNetif::Start(const Ipv4Config& config, const char* hostname) {
  const ip4_addr_t address = ToLwip(config.address);
  const ip4_addr_t netmask = ToLwip(config.netmask);
  const ip4_addr_t gateway = ToLwip(config.gateway);
  netif_add(&netif_, &address, &netmask, &gateway, this, &CardNetif::InitCallback, ethernet_input);
  added_ = true;
  netif_set_hostname(&netif_, hostname);
  // lwIP calls this on every change of the address (manual, ACD, BOOTP, DHCP, a yield), so the guard
  // never works with a stale one and nothing is refreshed per frame.
  netif_set_status_callback(&netif_, &CardNetif::StatusCallback);
  RefreshArpIdentity();
  netif_set_default(&netif_);
  netif_set_up(&netif_);
  SyncLinkState();
}

err_t CardNetif::InitCallback(netif* nif) {
  auto* self = static_cast<CardNetif*>(nif->state);
  const base::MacAddress mac = self->port_.Mac();
  nif->name[0] = 'e';
  nif->name[1] = 'n';
  nif->mtu = 1500;
  nif->hwaddr_len = ETH_HWADDR_LEN;
  std::memcpy(nif->hwaddr, mac.octets().data(), mac.octets().size());
  nif->flags = NETIF_FLAG_BROADCAST | NETIF_FLAG_ETHARP | NETIF_FLAG_ETHERNET | NETIF_FLAG_IGMP;
  nif->output = etharp_output;
  nif->linkoutput = &CardNetif::LinkOutputCallback;
  // Set here, in the init callback, because netif_add() starts IGMP (and joins 224.0.0.1) right after it.
  netif_set_igmp_mac_filter(nif, &CardNetif::MacFilterCallback);
  return ERR_OK;
}

err_t CardNetif::MacFilterCallback(netif* nif, const ip4_addr_t* group, enum netif_mac_filter_action action) {
  auto* self = static_cast<CardNetif*>(nif->state);
  // RFC 1112 §6.4: 01-00-5E-00-00-00 plus the low-order 23 bits of the group address.
  const base::Ipv4Address::Octets address = FromLwip(group).octets();
  const base::MacAddress mac{0x01, 0x00, 0x5E, static_cast<std::uint8_t>(address[1] & 0x7F), address[2], address[3]};
  const base::Status status = action == NETIF_ADD_MAC_FILTER ? self->port_.JoinMulticast(mac)
                                                             : self->port_.LeaveMulticast(mac);
  return status.ok() ? ERR_OK : ERR_IF;
}

err_t CardNetif::LinkOutputCallback(netif* nif, pbuf* p) {
  return static_cast<CardNetif*>(nif->state)->LinkOutput(p);
}

err_t CardNetif::LinkOutput(pbuf* p) {
  std::array<std::uint8_t, hal::kMaxFrameBytes> frame;
  if (p->tot_len > frame.size()) {
    ++counters_.tx_dropped;
    return ERR_BUF;
  }
  std::size_t length = pbuf_copy_partial(p, frame.data(), p->tot_len, 0);
  arp_guard_.NoteSent(std::span<const std::uint8_t>(frame.data(), length), sys_now());
  if (qos_ != nullptr) length = cip::InsertPriorityTag(*qos_, frame, length);
  const std::span<const std::uint8_t> bytes(frame.data(), length);
  // A frame no port took is lost like on a cable with no link; TCP retransmits, UDP does not care.
  SendFrame(bytes);
  return ERR_OK;
}

bool CardNetif::SendFrame(std::span<const std::uint8_t> bytes) {
  const std::array<bool, net::kSwitchPorts> out = switch_.Egress(bytes);
  bool sent = false;
  for (std::size_t i = 0; i < port_.PortCount(); ++i) {
    if (out[i] && TransmitOn(i, bytes)) sent = true;
  }
  ++(sent ? counters_.tx_frames : counters_.tx_dropped);
  return sent;
}

bool CardNetif::SendFrameOn(hal::PortId port, std::span<const std::uint8_t> bytes) {
  const bool sent = hal::PortIndex(port) < port_.PortCount() && TransmitOn(hal::PortIndex(port), bytes);
  ++(sent ? counters_.tx_frames : counters_.tx_dropped);
  return sent;
}

bool CardNetif::TransmitOn(std::size_t port, std::span<const std::uint8_t> bytes) {
  const auto id = static_cast<hal::PortId>(port);
  if (!port_.Link(id).up) return false;
  PortTraffic& traffic = traffic_[port];
  if (!port_.Transmit(id, bytes).ok()) {
    ++traffic.out_discards;
    return false;
  }
  ++(IsGroupAddress(bytes) ? traffic.out_nucast : traffic.out_ucast);
  return true;
}

void CardNetif::StatusCallback(netif* nif) { static_cast<CardNetif*>(nif->state)->RefreshArpIdentity(); }

// The guard follows the address in use (it changes at run time: ACD, BOOTP, DHCP, a new configuration).
void CardNetif::RefreshArpIdentity() {
  base::MacAddress::Octets mac{};
  std::memcpy(mac.data(), netif_.hwaddr, mac.size());
  arp_guard_.SetIdentity(base::MacAddress(mac), FromLwip(netif_ip4_addr(&netif_)));
}

bool CardNetif::Has(base::Ipv4Address address) const {
  const ip4_addr_t wanted = ToLwip(address);
  eth_addr* mac = nullptr;
  const ip4_addr_t* found = nullptr;
  // etharp_find_addr does not change the netif; its signature predates const.
  return etharp_find_addr(const_cast<netif*>(&netif_), &wanted, &mac, &found) >= 0;
}

void CardNetif::Forward(std::span<const std::uint8_t> frame, const net::SwitchDelivery& delivery) {
  for (std::size_t i = 0; i < port_.PortCount(); ++i) {
    const auto id = static_cast<hal::PortId>(i);
    if (!delivery.to_port[i] || !port_.Link(id).up) continue;
    PortTraffic& traffic = traffic_[i];
    if (port_.Transmit(id, frame).ok()) {
      ++traffic.forwarded;
    } else {
      ++traffic.out_discards;
    }
  }
}

std::size_t CardNetif::PumpReceive(std::size_t max_frames) {
  std::array<std::uint8_t, hal::kMaxFrameBytes> frame;
  std::size_t taken = 0;
  while (taken < max_frames) {
    const base::Result<hal::ReceivedFrame> received = port_.Receive(frame);
    if (received.status().code() == base::StatusCode::kUnavailable) break;
    ++taken;
    if (!received.ok()) {
      ++counters_.rx_port_errors;
      continue;
    }
    const auto length = static_cast<u16_t>(received->length);
    const std::span<const std::uint8_t> bytes(frame.data(), length);
    PortTraffic& traffic = traffic_[hal::PortIndex(received->port)];
    ++(IsGroupAddress(bytes) ? traffic.in_nucast : traffic.in_ucast);
    if (switch_protocol_ != nullptr && switch_protocol_->Claims(bytes)) {
      ++counters_.switch_protocol_frames;
      if (switch_protocol_->OnFrame(bytes, received->port)) {
        net::SwitchDelivery delivery;
        for (std::size_t i = 0; i < port_.PortCount(); ++i) delivery.to_port[i] = i != hal::PortIndex(received->port);
        Forward(bytes, delivery);
      }
      continue;
    }
    const net::SwitchDelivery delivery = switch_.Ingress(bytes, hal::PortIndex(received->port));
    Forward(bytes, delivery);
    if (!delivery.to_card) continue;
    // An ACD yield in the observer removes the address before the guard and lwIP see the frame.
    if (observer_ != nullptr) observer_->OnFrameToCard(bytes);
    if (port_handler_ != nullptr && port_handler_->TakeFrame(received->port, bytes)) continue;
    const ArpGuard::Verdict verdict = arp_guard_.Inspect(bytes, *this, sys_now());
    if (verdict == ArpGuard::Verdict::kAnswer) {
      ++counters_.rx_frames;  // taken in, as lwIP would have: only its answer comes from the guard
      SendFrame(arp_guard_.reply());
    }
    if (verdict != ArpGuard::Verdict::kPass) continue;
    pbuf* p = pbuf_alloc(PBUF_RAW, length, PBUF_POOL);
    if (p == nullptr) {
      ++counters_.rx_dropped_no_pbuf;
      ++traffic.in_discards;
      continue;
    }
    pbuf_take(p, frame.data(), length);
    ++counters_.rx_frames;
    // netif_input_fn: "!= ERR_OK is the packet was NOT handled, in this case, the caller has to free
    // the pbuf".
    if (netif_.input(p, &netif_) != ERR_OK) pbuf_free(p);
  }
  return taken;
}

bool CardNetif::link_up() const { return netif_is_link_up(&netif_); }

bool CardNetif::SyncLinkState() {
  bool any_up = false;
  for (std::size_t i = 0; i < port_.PortCount(); ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const bool up = port_.Link(id).up;
    if (up != port_up_[i]) {
      port_up_[i] = up;
      if (!up) switch_.PortDown(i);
      if (up && observer_ != nullptr) observer_->OnPortLinkUp(id);
      if (switch_protocol_ != nullptr) switch_protocol_->OnLinkChange(id, up);
    }
    any_up = any_up || up;
  }
  if (any_up == link_up()) return false;
  if (any_up) {
    netif_set_link_up(&netif_);
  } else {
    netif_set_link_down(&netif_);
  }
  return true;
}

}  // namespace firmware
