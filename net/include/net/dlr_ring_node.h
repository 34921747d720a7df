// The card as a DLR ring node (CIP Vol 2 ch 9; docs/network.md "Ring (DLR)"): a beacon-based node that
// also follows Announce frames, never a supervisor. A pure state machine like net::Acd: frames, link
// changes and time (hal::Micros) in; forwarding decisions, frames to send and deadlines out. No clock,
// no allocation, fixed sizes.
//
// Ports: 0 is DLR port 1 (the card's port L), 1 is DLR port 2 (port R).
//
//            beacon/announce from a supervisor
//   kIdle ─────────────────────────────────────> kNormal (ring state normal)   <──┐
//     ^                                          kFault  (ring state fault)    <──┤ beacons and announces
//     │ beacons timed out (or links down) on both ports, and no fresh announce    │ set the ring state
//     └───────────────────────────────────────────────────────────────────────────┘
//   kNormal -> kFault also when one port's beacons time out (the supervisor's beacon timeout) or its
//   link goes down. Every change between kNormal and kFault, and a change of supervisor, flushes the
//   switch's learning table (stations may now be reached the other way round the ring).
//
// Active supervisor: the first one heard; a beacon from another replaces it when its precedence is
// higher, or equal with a numerically higher MAC. Beacons of other supervisors are forwarded only.
//
// What OnFrame answers:
//   Beacon, Announce, Locate_Fault, Flush_Tables, Advertise, Learning_Update, and any DLR frame sent
//   unicast to another station (Link_Status, a full Sign_On): forward = pass it unchanged out of the
//   other port. Frames whose source is the card's own MAC and malformed frames are dropped (not
//   forwarded). Neighbor_Check request: a response on the same port (queued). Neighbor_Check response:
//   ends the check of that port (Locate_Fault). Locate_Fault: neighbour checks on both ports.
//   Flush_Tables: flush_learning_table, and with learning update enable a Learning_Update out of each
//   port with link (queued). Sign_On: sign_on = the caller passes it on now with ForwardSignOn (the
//   frame is not copied into the node).
//
// Frames to send wait in a fixed queue of kTransmitQueue entries; when it is full a new one is dropped
// and counted (a flood of ring frames cannot grow anything).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/addresses.h"
#include "hal/clock.h"
#include "net/dlr_frame.h"

namespace net {

inline constexpr std::size_t kDlrPorts = 2;

// Neighbour checks after Locate_Fault: a request, then up to kDlrNeighborCheckAttempts - 1 retries
// kDlrNeighborCheckTimeout apart; no response to any: Neighbor_Status to the supervisor.
inline constexpr hal::Micros kDlrNeighborCheckTimeout = 100 * hal::kMicrosPerMilli;
inline constexpr std::uint8_t kDlrNeighborCheckAttempts = 3;
// Announce frames come once a second; a node that knows the ring only from them forgets it after this.
inline constexpr hal::Micros kDlrAnnounceTimeout = 3 * hal::kMicrosPerSecond;

// DLR object attribute 1.
enum class DlrTopology : std::uint8_t { kLinear = 0, kRing = 1 };
// DLR object attribute 2. A node can tell only kNormal and kRingFault; the others are a supervisor's.
enum class DlrNetworkStatus : std::uint8_t {
  kNormal = 0,
  kRingFault = 1,
  kUnexpectedLoop = 2,
  kPartialFault = 3,
  kRapidFault = 4,
};
enum class DlrNodeState : std::uint8_t { kIdle, kFault, kNormal };

struct DlrSupervisor {
  base::MacAddress mac;
  base::Ipv4Address ip;
  std::uint8_t precedence = 0;
  std::uint32_t beacon_interval_us = 0;
  std::uint32_t beacon_timeout_us = 0;
};

struct DlrPortCounters {
  std::uint32_t frames = 0;   // DLR frames received on the port (malformed ones included)
  std::uint32_t beacons = 0;  // beacons of the active supervisor
  std::uint32_t answered = 0; // Neighbor_Check requests answered on the port
};

struct DlrCounters {
  std::uint32_t frames_in = 0;
  std::uint32_t malformed = 0;
  std::uint32_t neighbor_checks_answered = 0;
  std::uint32_t link_status_sent = 0;      // Link_Status frames queued
  std::uint32_t neighbor_status_sent = 0;  // Neighbor_Status frames queued
  std::uint32_t sign_ons = 0;              // Sign_On frames passed on
  std::uint32_t flushes = 0;               // learning-table flushes asked for
  std::uint32_t ring_faults = 0;           // transitions into kFault
  std::uint32_t transmit_dropped = 0;      // frames not queued (queue full) or not built (buffer short)
};

struct DlrRingStatus {
  DlrTopology topology = DlrTopology::kLinear;
  DlrNetworkStatus network_status = DlrNetworkStatus::kNormal;
  DlrNodeState node_state = DlrNodeState::kIdle;
  bool supervisor_known = false;  // supervisor holds the last active one (kept after kIdle for display)
  DlrSupervisor supervisor;
  std::array<DlrPortCounters, kDlrPorts> ports{};
  DlrCounters counters;
};

struct DlrReceive {
  bool forward = false;               // pass the frame unchanged out of the other port
  bool flush_learning_table = false;  // flush the switch's learning table now
  bool sign_on = false;               // call ForwardSignOn with this frame now
};

struct DlrTransmit {
  std::size_t length = 0;
  std::size_t port = 0;  // 0 or 1
};

class DlrRingNode {
 public:
  static constexpr std::size_t kTransmitQueue = 4;

  explicit DlrRingNode(const base::MacAddress& own_mac) : own_mac_(own_mac) {}
  // The IP address the node's frames carry (0.0.0.0 until the card has one).
  void SetIpAddress(base::Ipv4Address address) { own_ip_ = address; }

  // Any Ethernet frame received on `port`; frames that are not DLR return {} and count nothing.
  DlrReceive OnFrame(std::span<const std::uint8_t> frame, std::size_t port, hal::Micros now);
  // For a frame OnFrame answered sign_on: builds the Sign_On to pass on into `buffer`. It goes out of
  // the other port with the node's entry appended; when that port has no link, or the list is full,
  // it goes unicast to the supervisor out of the port it came from (docs/network.md). nullopt: the
  // frame is not a Sign_On or `buffer` is too small (counted in transmit_dropped).
  std::optional<DlrTransmit> ForwardSignOn(std::span<const std::uint8_t> frame, std::size_t port,
                                           std::span<std::uint8_t> buffer);

  // A port's link changed. While a ring is known, queues a Link_Status to the active supervisor. Returns
  // true when the switch's learning table is to be flushed (the node left kNormal).
  [[nodiscard]] bool OnLinkChange(std::size_t port, bool up, hal::Micros now);

  // Timers due at `now`: beacon timeouts per port, the announce timeout, neighbour-check retries and the
  // Neighbor_Status they end in. Returns true when the switch's learning table is to be flushed.
  [[nodiscard]] bool Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  // Builds the next queued frame into `buffer` (one per call); nullopt when nothing is queued.
  std::optional<DlrTransmit> NextTransmit(std::span<std::uint8_t> buffer, hal::Micros now);

  const DlrRingStatus& status() const { return status_; }

 private:
  struct Pending {
    DlrFrameType type = DlrFrameType::kNeighborCheckRequest;
    std::uint8_t port = 0;
    std::uint8_t argument = 0;  // request source port (response) or status byte (Link/Neighbor_Status)
    std::uint32_t sequence_id = 0;
  };
  struct PortState {
    bool link_up = true;                        // until OnLinkChange says otherwise
    bool neighbor_lost = false;                 // the last neighbour check of this port failed
    std::uint8_t check_attempts = 0;
    hal::Micros beacon_deadline = hal::kNever;  // kNever: no beacon expected on this port
    hal::Micros check_deadline = hal::kNever;   // kNever: no neighbour check waits for its response
    std::uint32_t check_first_sequence = 0;     // the requests of the running check
    std::uint32_t check_last_sequence = 0;
  };

  DlrReceive Receive(std::span<const std::uint8_t> frame, std::size_t port, hal::Micros now);
  DlrReceive OnBeacon(const DlrFrame& frame, std::size_t port, hal::Micros now);
  DlrReceive OnAnnounce(const DlrFrame& frame, hal::Micros now);
  DlrReceive OnFlushTables(const DlrFrame& frame);
  void OnLocateFault(const DlrFrame& frame, hal::Micros now);
  void OnNeighborResponse(const DlrFrame& frame, std::size_t port);
  bool BeaconsFresh(std::size_t port, hal::Micros now) const;
  bool BeaconsActive(hal::Micros now) const;  // beacons of the active supervisor on some port
  bool Flush(bool flush);                     // counts a flush asked for by Poll / OnLinkChange
  DlrNodeState Evaluate(hal::Micros now) const;
  bool UpdateState(hal::Micros now);
  void SendNeighborCheck(std::size_t port, hal::Micros now);
  void QueueLinkStatus(bool neighbor_status, std::size_t changed_port);
  bool Queue(const Pending& pending);
  base::Result<std::size_t> Build(const Pending& pending, std::span<std::uint8_t> buffer) const;
  bool RingKnown() const { return status_.node_state != DlrNodeState::kIdle; }
  std::uint32_t NextSequence() { return ++sequence_; }

  base::MacAddress own_mac_;
  base::Ipv4Address own_ip_;
  DlrRingStatus status_;
  std::array<PortState, kDlrPorts> ports_{};
  DlrRingState ring_state_ = DlrRingState::kNormal;  // as the active supervisor last said
  bool beacon_based_ = false;                        // the ring is known from beacons (else announces)
  hal::Micros announce_deadline_ = hal::kNever;
  std::uint32_t sequence_ = 0;
  std::array<Pending, kTransmitQueue> queue_{};
  std::size_t queue_head_ = 0;
  std::size_t queue_size_ = 0;
};

}  // namespace net
