// libFuzzer target for the DLR frame codec and the ring node (net/dlr_frame.h, net/dlr_ring_node.h).
// The whole input is first parsed as one frame; then it is a script of records: one byte kind (its bit 7
// picks port 0 or 1), two bytes of time step in units of 10 µs, and for a frame two length bytes and
// that many bytes. Kinds (bits 0-6): 0 frame, 1 poll, 2 link down, 3 link up, 4 send what is queued;
// the rest: poll.
// Oracles: nothing is read or written outside a span (ASan); a parsed Neighbor_Check request rebuilds to
// the same fields; every frame the node sends or passes on parses again, comes from the node's MAC, is
// at least 60 bytes and fits the buffer; the queue never holds more than kTransmitQueue frames; a
// deadline never lies before the poll that set it; topology and network status agree with the state.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "net/dlr_frame.h"
#include "net/dlr_ring_node.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::Ipv4Address kOwnIp(192, 0, 2, 10);

std::array<std::uint8_t, 1518> buffer{};

void CheckParse(std::span<const std::uint8_t> frame) {
  const base::Result<net::DlrFrame> parsed = net::ParseDlrFrame(frame);
  if (!parsed.ok()) return;
  Require(parsed->pdu_offset == 14 || parsed->pdu_offset == 18);
  for (std::size_t i = 0; i < parsed->sign_on_nodes; ++i) (void)net::SignOnNode(frame, *parsed, i);
  if (parsed->type != net::DlrFrameType::kNeighborCheckRequest) return;
  net::DlrOrigin origin;
  origin.destination = parsed->destination;
  origin.source = parsed->source;
  origin.source_port = parsed->source_port;
  origin.source_ip = parsed->source_ip;
  origin.sequence_id = parsed->sequence_id;
  const base::Result<std::size_t> length = net::BuildNeighborCheckRequest(origin, buffer);
  Require(length.ok());
  const base::Result<net::DlrFrame> again = net::ParseDlrFrame(std::span(buffer).first(*length));
  Require(again.ok() && again->source == parsed->source && again->sequence_id == parsed->sequence_id &&
          again->source_port == parsed->source_port && again->source_ip == parsed->source_ip);
}

void CheckSent(std::span<const std::uint8_t> frame) {
  Require(frame.size() >= net::kEthernetMinFrameSize && frame.size() <= buffer.size());
  const base::Result<net::DlrFrame> parsed = net::ParseDlrFrame(frame);
  Require(parsed.ok() && parsed->source == kOwnMac);
}

void CheckStatus(const net::DlrRingStatus& status) {
  Require((status.topology == net::DlrTopology::kLinear) == (status.node_state == net::DlrNodeState::kIdle));
  Require((status.network_status == net::DlrNetworkStatus::kRingFault) ==
          (status.node_state == net::DlrNodeState::kFault));
}

void Drain(net::DlrRingNode& node, hal::Micros now) {
  std::size_t sent = 0;
  while (const auto transmit = node.NextTransmit(buffer, now)) {
    Require(++sent <= net::DlrRingNode::kTransmitQueue && transmit->port < net::kDlrPorts);
    CheckSent(std::span(buffer).first(transmit->length));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> rest(data, size);
  CheckParse(rest);
  net::DlrRingNode node(kOwnMac);
  node.SetIpAddress(kOwnIp);
  hal::Micros now = 0;
  while (rest.size() >= 3) {
    const std::uint8_t kind = rest[0] & 0x7F;
    const std::size_t port = rest[0] >> 7;
    now += static_cast<hal::Micros>(rest[1] << 8 | rest[2]) * 10;
    rest = rest.subspan(3);
    switch (kind) {
      case 0: {
        if (rest.size() < 2) return 0;
        const std::size_t wanted = static_cast<std::size_t>(rest[0] << 8 | rest[1]);
        const std::size_t length = wanted < rest.size() - 2 ? wanted : rest.size() - 2;
        const std::span<const std::uint8_t> frame = rest.subspan(2, length);
        rest = rest.subspan(2 + length);
        CheckParse(frame);
        const net::DlrReceive receive = node.OnFrame(frame, port, now);
        if (receive.sign_on) {
          Require(!receive.forward);
          if (const auto transmit = node.ForwardSignOn(frame, port, buffer)) {
            Require(transmit->port < net::kDlrPorts);
            CheckSent(std::span(buffer).first(transmit->length));
          }
        }
        break;
      }
      case 2:
      case 3:
        (void)node.OnLinkChange(port, kind == 3, now);
        break;
      case 4:
        Drain(node, now);
        break;
      default:
        (void)node.Poll(now);
        Require(node.NextDeadline() > now);
        break;
    }
    CheckStatus(node.status());
  }
  Drain(node, now);
  return 0;
}
