// The card's one IP interface, bound to lwIP, on top of the two-port frame port.
//
// The card has one MAC and one IP address behind its internal switch (net::FrameSwitch: the card, port
// L, port R). Receive: the switch decides per frame; a frame for the card goes to the observer (ACD
// reads ARP there) and then into lwIP through netif->input; a frame for another station passes to the
// other port (daisy chain); a per-port protocol's frame (LLDP) is taken before lwIP by the port frame
// handler, which is told the ingress port. Transmit: lwIP's frames go out of the port their destination
// was learned on, or every port with link when it is unknown. Link: the netif's link is up while at least one port has
// link; a port going down flushes the stations learned on it, one coming up is told to the observer.
//
// ARP: every frame for the card passes the ArpGuard (arp_guard.h) after the observer (ACD must see every
// ARP frame, also those the guard drops) and before lwIP: the guard keeps strangers out of lwIP's ARP
// cache (it answers their requests itself and drops replies nobody asked for).
//
// Multicast: lwIP's IGMP tells the netif which groups it joins and leaves (netif->igmp_mac_filter,
// 224.0.0.1 from the start); the netif passes each group's MAC (01:00:5e + the low 23 bits of the group
// address) to the frame port, whose MAC filter then lets the group's frames in.
//
// Buffer ownership: a received frame is copied into a PBUF_POOL chain; if lwIP's input function does
// not take it (returns != ERR_OK) the pbuf is freed here. Outgoing pbufs belong to lwIP: linkoutput
// only copies them into the port.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "arp_guard.h"
#include "base/addresses.h"
#include "hal/frame_port.h"
#include "lwip/netif.h"
#include "net/frame_switch.h"

namespace cip {
struct QosSettings;
}  // namespace cip

namespace firmware {

struct Ipv4Config {
  base::Ipv4Address address;
  base::Ipv4Address netmask;
  base::Ipv4Address gateway;

  bool operator==(const Ipv4Config&) const = default;
};

struct NetifCounters {
  std::uint64_t rx_frames = 0;
  std::uint64_t rx_dropped_no_pbuf = 0;  // PBUF_POOL empty: frame dropped as a MAC with a full ring would
  std::uint64_t rx_port_errors = 0;      // the port reported an oversize/runt frame
  std::uint64_t switch_protocol_frames = 0;  // taken by the switch protocol (DLR), not by lwIP
  std::uint64_t learning_flushes = 0;        // the switch's learning table emptied at the ring's request
  std::uint64_t tx_frames = 0;           // frames (lwIP's, ACD's, the ArpGuard's) handed to at least one port
  std::uint64_t tx_dropped = 0;          // no port with link, or every port refused the frame
};

// Per switch port, what the Ethernet Link object (0xF6) counts beyond the port's own octets and errors:
// frames by destination kind (bit 0 of the destination MAC set: broadcast or multicast) and frames
// dropped for lack of a buffer (in) or refused by the port (out).
struct PortTraffic {
  std::uint64_t in_ucast = 0;
  std::uint64_t in_nucast = 0;
  std::uint64_t in_discards = 0;
  std::uint64_t out_ucast = 0;
  std::uint64_t out_nucast = 0;
  std::uint64_t out_discards = 0;
  std::uint64_t forwarded = 0;  // frames passed out of this port for other stations (daisy chain)
};

// Sees the frames the switch delivers to the card, before lwIP does, and per-port link-up edges. It
// only reads: every frame still goes to lwIP. (Address Conflict Detection, docs/network.md.)
class NetifObserver {
 public:
  virtual ~NetifObserver() = default;
  virtual void OnFrameToCard(std::span<const std::uint8_t> frame) = 0;
  virtual void OnPortLinkUp(hal::PortId port) = 0;
};

// A protocol of the switch itself (the DLR ring node, docs/network.md "Ring (DLR)"). The frames it
// claims go to it, with the port they came in on, instead of through the switch's rules: they are
// neither learned from nor given to lwIP. OnFrame answers whether the switch passes the frame on,
// unchanged, out of the other port (a ring node forwards beacons at once, before anything else of the
// batch). It also hears of every change of a port's link. It flushes the switch's learning table and
// sends its own frames through the netif (FlushLearningTable, SendFrameOn).
class SwitchProtocol {
 public:
  virtual ~SwitchProtocol() = default;
  virtual bool Claims(std::span<const std::uint8_t> frame) const = 0;
  // True: forward the frame out of the other port.
  virtual bool OnFrame(std::span<const std::uint8_t> frame, hal::PortId port) = 0;
  virtual void OnLinkChange(hal::PortId port, bool up) = 0;
};

// Takes the frames for the card that belong to a per-port protocol (LLDP), with the port they came in
// on, after the observer and before lwIP. True: the frame was the handler's and goes no further.
class PortFrameHandler {
 public:
  virtual ~PortFrameHandler() = default;
  virtual bool TakeFrame(hal::PortId port, std::span<const std::uint8_t> frame) = 0;
};

class CardNetif final : private ArpCacheQuery {
 public:
  explicit CardNetif(hal::FramePort& port) : port_(port), switch_(port.Mac(), port.PortCount()) {}
  ~CardNetif();
  CardNetif(const CardNetif&) = delete;
  CardNetif& operator=(const CardNetif&) = delete;

  // Adds the netif to lwIP (lwip_init must have run) and brings it administratively up.
  void Start(const Ipv4Config& config, const char* hostname);

  // Moves at most `max_frames` received frames into lwIP; returns how many were taken from the port.
  // Bounded so that a flood cannot starve timers and I/O production.
  std::size_t PumpReceive(std::size_t max_frames);

  // Brings the lwIP link state in line with the ports'. Returns true when it changed.
  bool SyncLinkState();

  // At most one observer (null: none).
  void SetObserver(NetifObserver* observer) { observer_ = observer; }
  // At most one handler (null: none).
  void SetPortFrameHandler(PortFrameHandler* handler) { port_handler_ = handler; }
  // The QoS values in force (outliving the netif; null: none): with 802.1Q tagging on, lwIP's frames
  // of a CIP traffic class leave with a priority tag (cip::InsertPriorityTag).
  void SetQosTagging(const cip::QosSettings* qos) { qos_ = qos; }
  // Sends a frame the card builds itself (ACD's ARP probes) like lwIP's: by the switch's egress rule.
  // False when no port took it.
  bool SendFrame(std::span<const std::uint8_t> frame);
  // At most one switch protocol (null: none).
  void SetSwitchProtocol(SwitchProtocol* protocol) { switch_protocol_ = protocol; }
  // Forgets every station the switch learned (the ring's Flush_Tables, a change of the ring's state).
  void FlushLearningTable() {
    switch_.Flush();
    ++counters_.learning_flushes;
  }
  std::size_t learned_stations() const { return switch_.learned(); }
  // Sends a frame out of one port only, whatever the switch knows (LLDP is per link). False when the
  // port has no link or refused the frame.
  bool SendFrameOn(hal::PortId port, std::span<const std::uint8_t> frame);

  bool link_up() const;
  const NetifCounters& counters() const { return counters_; }
  const PortTraffic& traffic(hal::PortId port) const { return traffic_[hal::PortIndex(port)]; }
  const ArpGuardCounters& arp_guard_counters() const { return arp_guard_.counters(); }
  netif& lwip_netif() { return netif_; }
  hal::FramePort& port() { return port_; }
  const hal::FramePort& port() const { return port_; }

 private:
  static err_t InitCallback(netif* nif);
  static err_t LinkOutputCallback(netif* nif, pbuf* p);
  static void StatusCallback(netif* nif);
  static err_t MacFilterCallback(netif* nif, const ip4_addr_t* group, enum netif_mac_filter_action action);
  err_t LinkOutput(pbuf* p);
  bool TransmitOn(std::size_t port, std::span<const std::uint8_t> frame);  // counted per port
  void Forward(std::span<const std::uint8_t> frame, const net::SwitchDelivery& delivery);
  void RefreshArpIdentity();
  bool Has(base::Ipv4Address address) const override;  // ArpCacheQuery: a stable lwIP ARP entry

  hal::FramePort& port_;
  net::FrameSwitch switch_;
  NetifObserver* observer_ = nullptr;
  SwitchProtocol* switch_protocol_ = nullptr;
  PortFrameHandler* port_handler_ = nullptr;
  const cip::QosSettings* qos_ = nullptr;
  std::array<bool, hal::kMaxPorts> port_up_{};
  ArpGuard arp_guard_;
  netif netif_{};
  bool added_ = false;
  NetifCounters counters_;
  std::array<PortTraffic, hal::kMaxPorts> traffic_{};
};

}  // namespace firmware
