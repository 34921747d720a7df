#include "net/dlr_ring_node.h"

namespace net {
namespace {

// The DLR port number (1 or 2) of a port index.
constexpr std::uint8_t PortNumber(std::size_t port) { return port == 0 ? 1 : 2; }
constexpr std::size_t Other(std::size_t port) { return port ^ 1U; }

// A supervisor replaces the active one with a higher precedence, or an equal one and a higher MAC.
bool Outranks(std::uint8_t precedence, const base::MacAddress& mac, const DlrSupervisor& active) {
  if (precedence != active.precedence) return precedence > active.precedence;
  return mac.octets() > active.mac.octets();
}

}  // namespace

DlrReceive DlrRingNode::OnFrame(std::span<const std::uint8_t> frame, std::size_t port, hal::Micros now) {
  const DlrReceive receive = Receive(frame, port, now);
  if (receive.flush_learning_table) ++status_.counters.flushes;
  return receive;
}

DlrReceive DlrRingNode::Receive(std::span<const std::uint8_t> frame, std::size_t port, hal::Micros now) {
  if (port >= kDlrPorts) return {};
  const base::Result<DlrFrame> parsed = ParseDlrFrame(frame);
  if (parsed.status().code() == base::StatusCode::kNotFound) return {};
  ++status_.counters.frames_in;
  ++status_.ports[port].frames;
  if (!parsed.ok()) {
    ++status_.counters.malformed;
    return {};
  }
  const DlrFrame& dlr = *parsed;
  if (dlr.source == own_mac_) return {};  // the card's own frame came round the ring
  // Unicast to another station (Link_Status, a full Sign_On on its way to the supervisor).
  if (!dlr.destination.IsMulticast() && dlr.destination != own_mac_) return {.forward = true};

  switch (dlr.type) {
    case DlrFrameType::kBeacon:
      return OnBeacon(dlr, port, now);
    case DlrFrameType::kAnnounce:
      return OnAnnounce(dlr, now);
    case DlrFrameType::kFlushTables:
      return OnFlushTables(dlr);
    case DlrFrameType::kLocateFault:
      OnLocateFault(dlr, now);
      return {.forward = true};
    case DlrFrameType::kNeighborCheckRequest:
      if (Queue({DlrFrameType::kNeighborCheckResponse, static_cast<std::uint8_t>(port), dlr.source_port,
                 dlr.sequence_id})) {
        ++status_.counters.neighbor_checks_answered;
        ++status_.ports[port].answered;
      }
      return {};
    case DlrFrameType::kNeighborCheckResponse:
      OnNeighborResponse(dlr, port);
      return {};
    case DlrFrameType::kSignOn:
      // The supervisor signs the ring on in its normal state only; elsewhere the frame is stale.
      return {.sign_on = status_.node_state == DlrNodeState::kNormal};
    case DlrFrameType::kLinkStatus:
    case DlrFrameType::kAdvertise:
    case DlrFrameType::kLearningUpdate:
      return {.forward = true};
  }
  return {};
}

DlrReceive DlrRingNode::OnBeacon(const DlrFrame& beacon, std::size_t port, hal::Micros now) {
  DlrReceive receive{.forward = true};
  const bool active = BeaconsActive(now);
  const bool tracked = active && beacon.source == status_.supervisor.mac;
  if (active && !tracked && !Outranks(beacon.precedence, beacon.source, status_.supervisor)) {
    return receive;  // a lower supervisor: passed on, not followed
  }
  if (!tracked) {
    // A new active supervisor: from now on both ports expect its beacons within its timeout.
    status_.supervisor_known = true;
    status_.supervisor.mac = beacon.source;
    beacon_based_ = true;
    announce_deadline_ = hal::kNever;
    for (PortState& state : ports_) state.beacon_deadline = state.link_up ? now + beacon.timeout_us : hal::kNever;
    receive.flush_learning_table = true;
  }
  status_.supervisor.ip = beacon.source_ip;
  status_.supervisor.precedence = beacon.precedence;
  status_.supervisor.beacon_interval_us = beacon.interval_us;
  status_.supervisor.beacon_timeout_us = beacon.timeout_us;
  ports_[port].beacon_deadline = now + beacon.timeout_us;
  ++status_.ports[port].beacons;
  ring_state_ = beacon.ring_state;
  receive.flush_learning_table = UpdateState(now) || receive.flush_learning_table;
  return receive;
}

DlrReceive DlrRingNode::OnAnnounce(const DlrFrame& announce, hal::Micros now) {
  DlrReceive receive{.forward = true};
  if (BeaconsActive(now)) return receive;  // beacons say more, and sooner
  const bool tracked = RingKnown() && announce.source == status_.supervisor.mac;
  if (RingKnown() && !tracked) return receive;  // announces carry no precedence: the first one is kept
  if (!tracked) {
    status_.supervisor_known = true;
    status_.supervisor = DlrSupervisor{};
    status_.supervisor.mac = announce.source;
    receive.flush_learning_table = true;
  }
  status_.supervisor.ip = announce.source_ip;
  announce_deadline_ = now + kDlrAnnounceTimeout;
  ring_state_ = announce.ring_state;
  receive.flush_learning_table = UpdateState(now) || receive.flush_learning_table;
  return receive;
}

DlrReceive DlrRingNode::OnFlushTables(const DlrFrame& flush) {
  DlrReceive receive{.forward = true};
  if (!RingKnown()) return receive;
  receive.flush_learning_table = true;
  if (flush.learning_update_enable) {
    const std::uint32_t sequence = NextSequence();
    for (std::size_t port = 0; port < kDlrPorts; ++port) {
      if (ports_[port].link_up) Queue({DlrFrameType::kLearningUpdate, static_cast<std::uint8_t>(port), 0, sequence});
    }
  }
  return receive;
}

void DlrRingNode::OnLocateFault(const DlrFrame& locate, hal::Micros now) {
  if (status_.node_state != DlrNodeState::kFault || locate.source != status_.supervisor.mac) return;
  for (std::size_t port = 0; port < kDlrPorts; ++port) {
    PortState& state = ports_[port];
    if (!state.link_up || state.check_deadline != hal::kNever) continue;  // no neighbour, or checking already
    state.check_attempts = 0;
    state.neighbor_lost = false;
    state.check_first_sequence = sequence_ + 1;
    SendNeighborCheck(port, now);
  }
}

void DlrRingNode::OnNeighborResponse(const DlrFrame& response, std::size_t port) {
  PortState& state = ports_[port];
  if (state.check_deadline == hal::kNever || response.request_source_port != PortNumber(port)) return;
  // Any of this check's requests counts (a late answer to the first is still an answer).
  if (response.sequence_id - state.check_first_sequence > state.check_last_sequence - state.check_first_sequence) {
    return;
  }
  state.check_deadline = hal::kNever;
  state.neighbor_lost = false;
}

void DlrRingNode::SendNeighborCheck(std::size_t port, hal::Micros now) {
  PortState& state = ports_[port];
  state.check_last_sequence = NextSequence();
  ++state.check_attempts;
  state.check_deadline = now + kDlrNeighborCheckTimeout;
  Queue({DlrFrameType::kNeighborCheckRequest, static_cast<std::uint8_t>(port), 0, state.check_last_sequence});
}

std::optional<DlrTransmit> DlrRingNode::ForwardSignOn(std::span<const std::uint8_t> frame, std::size_t port,
                                                      std::span<std::uint8_t> buffer) {
  const base::Result<DlrFrame> parsed = ParseDlrFrame(frame);
  if (port >= kDlrPorts || !parsed.ok() || parsed->type != DlrFrameType::kSignOn) return std::nullopt;
  const bool room = SignOnHasRoom(parsed->sign_on_nodes);
  const std::size_t other = Other(port);
  // Round the ring out of the other port; when that is closed or the list full, straight back to the
  // supervisor (unicast) out of the port the frame came in on.
  const bool onward = room && ports_[other].link_up;
  const base::MacAddress& destination = onward ? parsed->destination : status_.supervisor.mac;
  const base::Result<std::size_t> length =
      BuildSignOn(frame, *parsed, destination, DlrNode{own_mac_, own_ip_}, room, buffer);
  if (!length.ok()) {
    ++status_.counters.transmit_dropped;
    return std::nullopt;
  }
  ++status_.counters.sign_ons;
  return DlrTransmit{*length, onward ? other : port};
}

bool DlrRingNode::OnLinkChange(std::size_t port, bool up, hal::Micros now) {
  if (port >= kDlrPorts || ports_[port].link_up == up) return false;
  PortState& state = ports_[port];
  state.link_up = up;
  if (!up) {
    state.beacon_deadline = hal::kNever;
    state.check_deadline = hal::kNever;
  }
  if (RingKnown()) QueueLinkStatus(false, port);
  return Flush(UpdateState(now));
}

bool DlrRingNode::Poll(hal::Micros now) {
  for (PortState& state : ports_) {
    if (state.beacon_deadline <= now) state.beacon_deadline = hal::kNever;
  }
  if (announce_deadline_ <= now) announce_deadline_ = hal::kNever;
  for (std::size_t port = 0; port < kDlrPorts; ++port) {
    PortState& state = ports_[port];
    if (state.check_deadline > now) continue;
    if (state.check_attempts < kDlrNeighborCheckAttempts) {
      SendNeighborCheck(port, now);
    } else {
      state.check_deadline = hal::kNever;
      state.neighbor_lost = true;
      QueueLinkStatus(true, port);
    }
  }
  return Flush(UpdateState(now));
}

hal::Micros DlrRingNode::NextDeadline() const {
  hal::Micros next = announce_deadline_;
  for (const PortState& state : ports_) {
    if (state.beacon_deadline < next) next = state.beacon_deadline;
    if (state.check_deadline < next) next = state.check_deadline;
  }
  return next;
}

bool DlrRingNode::Flush(bool flush) {
  if (flush) ++status_.counters.flushes;
  return flush;
}

bool DlrRingNode::BeaconsActive(hal::Micros now) const {
  return beacon_based_ && (BeaconsFresh(0, now) || BeaconsFresh(1, now));
}

bool DlrRingNode::BeaconsFresh(std::size_t port, hal::Micros now) const {
  return ports_[port].beacon_deadline != hal::kNever && now < ports_[port].beacon_deadline;
}

// Beacons decide while any port still has them: normal needs the supervisor's word and beacons on both
// ports. Without beacons a fresh announce decides; with neither the node is idle (no ring).
DlrNodeState DlrRingNode::Evaluate(hal::Micros now) const {
  const bool beacons = BeaconsActive(now);
  const bool announced = announce_deadline_ != hal::kNever && now < announce_deadline_;
  if (!beacons && !announced) return DlrNodeState::kIdle;
  if (ring_state_ == DlrRingState::kFault) return DlrNodeState::kFault;
  if (beacons && !(BeaconsFresh(0, now) && BeaconsFresh(1, now))) return DlrNodeState::kFault;
  return DlrNodeState::kNormal;
}

bool DlrRingNode::UpdateState(hal::Micros now) {
  const DlrNodeState next = Evaluate(now);
  if (!BeaconsActive(now)) beacon_based_ = false;
  if (next == status_.node_state) return false;
  status_.node_state = next;
  status_.topology = next == DlrNodeState::kIdle ? DlrTopology::kLinear : DlrTopology::kRing;
  status_.network_status = next == DlrNodeState::kFault ? DlrNetworkStatus::kRingFault : DlrNetworkStatus::kNormal;
  if (next == DlrNodeState::kFault) ++status_.counters.ring_faults;
  if (next != DlrNodeState::kFault) {
    for (PortState& state : ports_) state.check_deadline = hal::kNever;  // neighbour checks belong to a fault
  }
  return true;
}

void DlrRingNode::QueueLinkStatus(bool neighbor_status, std::size_t changed_port) {
  // Towards the supervisor out of the port that did not change or fail, else the changed one.
  std::size_t port = Other(changed_port);
  if (!ports_[port].link_up) port = changed_port;
  if (!ports_[port].link_up) return;  // no way out
  DlrLinkStatus link_status;
  link_status.neighbor_status = neighbor_status;
  link_status.port1_active = neighbor_status ? !ports_[0].neighbor_lost : ports_[0].link_up;
  link_status.port2_active = neighbor_status ? !ports_[1].neighbor_lost : ports_[1].link_up;
  if (Queue({DlrFrameType::kLinkStatus, static_cast<std::uint8_t>(port), link_status.Encode(), NextSequence()})) {
    ++(neighbor_status ? status_.counters.neighbor_status_sent : status_.counters.link_status_sent);
  }
}

bool DlrRingNode::Queue(const Pending& pending) {
  if (queue_size_ == kTransmitQueue) {
    ++status_.counters.transmit_dropped;
    return false;
  }
  queue_[(queue_head_ + queue_size_) % kTransmitQueue] = pending;
  ++queue_size_;
  return true;
}

base::Result<std::size_t> DlrRingNode::Build(const Pending& pending, std::span<std::uint8_t> buffer) const {
  DlrOrigin origin;
  origin.source = own_mac_;
  origin.source_ip = own_ip_;
  origin.sequence_id = pending.sequence_id;
  switch (pending.type) {
    case DlrFrameType::kNeighborCheckRequest:
      origin.destination = kDlrNeighborCheckMac;
      origin.source_port = PortNumber(pending.port);
      return BuildNeighborCheckRequest(origin, buffer);
    case DlrFrameType::kNeighborCheckResponse:
      origin.destination = kDlrNeighborCheckMac;
      origin.source_port = PortNumber(pending.port);
      return BuildNeighborCheckResponse(origin, pending.argument, buffer);
    case DlrFrameType::kLinkStatus:
      origin.destination = status_.supervisor.mac;
      return BuildLinkStatus(origin, DlrLinkStatus::Decode(pending.argument), buffer);
    case DlrFrameType::kLearningUpdate:
      origin.destination = kDlrLearningUpdateMac;
      return BuildLearningUpdate(origin, buffer);
    default:
      return base::Internal();
  }
}

std::optional<DlrTransmit> DlrRingNode::NextTransmit(std::span<std::uint8_t> buffer, hal::Micros) {
  while (queue_size_ > 0) {
    const Pending pending = queue_[queue_head_];
    queue_head_ = (queue_head_ + 1) % kTransmitQueue;
    --queue_size_;
    const base::Result<std::size_t> length = Build(pending, buffer);
    if (length.ok()) return DlrTransmit{*length, pending.port};
    ++status_.counters.transmit_dropped;
  }
  return std::nullopt;
}

}  // namespace net
