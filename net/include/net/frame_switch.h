// The card's internal two-port switch (NET-3, seed 000 §2.3; docs/network.md "The two-port switch"):
// which of the card itself and ports L/R get a frame. The card has one MAC behind a three-port switch
// (host, L, R), so drives can be daisy-chained: a frame that is not for the card passes to the other port.
//
// Received on a port (Ingress):
//   destination = the card's MAC          -> the card only
//   broadcast / multicast                 -> the card and the other port (flooded), except the IEEE
//                                            802.1D reserved group 01-80-C2-00-00-00..0F (STP, LLDP,
//                                            pause: link-local, never forwarded by a bridge) -> card only
//   another unicast MAC                   -> the other port, unless that MAC was learned on the port the
//                                            frame came from (filtered: both stations are on that side)
// Sent by the card (Egress): to the port its destination was learned on; unknown or group: every port.
//
// Learning: the source MAC of every received frame with a unicast source (not the card's own) is
// recorded with its port, in a fixed table of kCapacity entries. A full table replaces its oldest entry;
// a station that moves is re-learned by its next frame; a port whose link goes down forgets its entries
// (PortDown). There is no ageing timer: with two ports and forwarding to unknown destinations, a stale
// entry can only misdirect traffic until the station sends again, and a link-down flushes it.
//
// Device-path code: no allocation, no clock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"

namespace net {

inline constexpr std::size_t kSwitchPorts = 2;

struct SwitchDelivery {
  bool to_card = false;
  std::array<bool, kSwitchPorts> to_port{};  // forward out of port i

  bool operator==(const SwitchDelivery&) const = default;
};

class FrameSwitch {
 public:
  static constexpr std::size_t kCapacity = 64;

  FrameSwitch(const base::MacAddress& own_mac, std::size_t port_count)
      : own_mac_(own_mac), port_count_(port_count < kSwitchPorts ? port_count : kSwitchPorts) {}

  // A frame received on `port` (< port count); frames shorter than an Ethernet header go nowhere.
  SwitchDelivery Ingress(std::span<const std::uint8_t> frame, std::size_t port);
  // A frame the card sends: the ports it goes out of (before the link check).
  std::array<bool, kSwitchPorts> Egress(std::span<const std::uint8_t> frame) const;
  // The link of `port` went down: the stations learned there are forgotten.
  void PortDown(std::size_t port);
  // Every learned station is forgotten (a ring's Flush_Tables: the stations may now be behind the
  // other port).
  void Flush() {
    count_ = 0;
    oldest_ = 0;
  }

  // The port `mac` was learned on, or kSwitchPorts when unknown.
  std::size_t PortOf(const base::MacAddress& mac) const;
  std::size_t learned() const { return count_; }

 private:
  struct Entry {
    base::MacAddress mac{};
    std::uint8_t port = 0;
  };
  void Learn(const base::MacAddress& mac, std::size_t port);

  base::MacAddress own_mac_;
  std::size_t port_count_;
  std::array<Entry, kCapacity> entries_{};
  std::size_t count_ = 0;
  std::size_t oldest_ = 0;  // replaced next when the table is full
};

}  // namespace net
