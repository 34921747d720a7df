// Ethernet frame port: the card's MAC with its two switch ports, L (left) and R (right).
//
// Contract:
// - Frames are whole Ethernet II frames without preamble and FCS: destination MAC first, 14..1518 bytes
//   (1518 leaves room for one 802.1Q tag).
// - Receive() never blocks. It copies the oldest waiting frame into the caller's buffer and says which
//   port it arrived on; kUnavailable means no frame is waiting. A frame that does not fit the buffer is
//   dropped, counted as an rx error and reported as kOutOfRange (the next call returns the next frame).
// - Transmit() never blocks and copies the frame before returning (the caller keeps its buffer).
//   kFailedPrecondition: the port's link is down (frame dropped). kResourceExhausted: the transmit queue
//   is full (frame dropped, as a MAC with a full ring would). kNotFound: no such port.
// - Link() is cheap and may be called every loop pass; the event loop compares it with what lwIP knows.
// - Counters are cumulative since start and feed the Ethernet Link object (0xF6) and the web page.
// - Multicast: broadcast always passes. A port whose MAC filters multicast (a board's hash filter)
//   delivers a multicast group's frames from JoinMulticast() until LeaveMulticast(); joins of one group
//   nest (it stays until as many leaves). A port that cannot filter finely enough passes more than was
//   asked, never less (a full filter table: every multicast frame). A port that passes every multicast
//   frame anyway (the host backends) keeps the default, which accepts both calls and changes nothing.
//   LeaveMulticast() of a group that was not joined: kNotFound.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "base/status.h"

namespace hal {

inline constexpr std::size_t kMinFrameBytes = 14;
inline constexpr std::size_t kMaxFrameBytes = 1518;
inline constexpr std::size_t kMaxPorts = 2;

enum class PortId : std::uint8_t { kLeft = 0, kRight = 1 };

constexpr std::size_t PortIndex(PortId port) { return static_cast<std::size_t>(port); }
constexpr char PortLetter(PortId port) { return port == PortId::kLeft ? 'L' : 'R'; }

enum class LinkSpeed : std::uint8_t { kNone = 0, k10Mbps = 10, k100Mbps = 100 };

struct LinkState {
  bool up = false;
  LinkSpeed speed = LinkSpeed::kNone;
  bool full_duplex = false;
  bool auto_negotiated = false;
};

struct PortCounters {
  std::uint64_t rx_frames = 0;
  std::uint64_t rx_octets = 0;
  std::uint64_t rx_errors = 0;  // oversize, runt, or dropped because the receive queue was full
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_octets = 0;
  std::uint64_t tx_errors = 0;  // dropped: link down or transmit queue full
};

struct ReceivedFrame {
  std::size_t length = 0;
  PortId port = PortId::kLeft;
};

class FramePort {
 public:
  virtual ~FramePort() = default;

  // The card's own (factory) MAC address.
  virtual base::MacAddress Mac() const = 0;
  // Ports [0, PortCount()) exist; a card with one port populated reports 1.
  virtual std::size_t PortCount() const = 0;
  virtual LinkState Link(PortId port) const = 0;
  virtual PortCounters Counters(PortId port) const = 0;

  virtual base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) = 0;
  virtual base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) = 0;

  // The multicast groups to receive (lwIP's IGMP joins them through the netif's MAC filter hook). The
  // default is a port that receives every multicast frame: there is nothing to program. (Inline, so
  // the interface keeps no key function: its vtable and type information come with each user, built
  // with or without RTTI.)
  virtual base::Status JoinMulticast(const base::MacAddress&) { return base::OkStatus(); }
  virtual base::Status LeaveMulticast(const base::MacAddress&) { return base::OkStatus(); }
};

}  // namespace hal
