// Stub: the state machine is implemented in a following commit.
#include "net/dlr_ring_node.h"

namespace net {

DlrReceive DlrRingNode::OnFrame(std::span<const std::uint8_t>, std::size_t, hal::Micros) { return {}; }
std::optional<DlrTransmit> DlrRingNode::ForwardSignOn(std::span<const std::uint8_t>, std::size_t,
                                                      std::span<std::uint8_t>) {
  return std::nullopt;
}
bool DlrRingNode::OnLinkChange(std::size_t, bool, hal::Micros) { return false; }
bool DlrRingNode::Poll(hal::Micros) { return false; }
hal::Micros DlrRingNode::NextDeadline() const { return hal::kNever; }
std::optional<DlrTransmit> DlrRingNode::NextTransmit(std::span<std::uint8_t>, hal::Micros) { return std::nullopt; }

}  // namespace net
