// The card's DLR ring node in its frame path (docs/network.md "Ring (DLR)"): net::DlrRingNode bound to
// the netif's switch and to the clock.
//
// Frames: the netif gives every DLR frame (EtherType 0x80E1, tagged or not) to the node with the port
// it came in on, before the switch's rules; what the node passes on goes out of the other port at once,
// in the same receive batch, so a beacon is never queued behind the card's own work. What the node
// answers (Neighbor_Check responses, Link_Status, Learning_Update, a Sign_On with the card appended) is
// sent out of its port right away too, and whatever is still queued at the next poll then.
// Learning: a Flush_Tables, and every change of the node between normal and fault or of supervisor,
// empties the switch's learning table. The node's frames carry the address in use (0.0.0.0 without).
//
// The CIP DLR object (0x47) reads the node through DlrValues(); the web page and `stats` read status().
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "card_netif.h"
#include "cip/dlr_object.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "hal/frame_port.h"
#include "net/dlr_ring_node.h"

namespace firmware {

class CardRing final : public SwitchProtocol, public Service, public cip::DlrProvider {
 public:
  CardRing(CardNetif& netif, const hal::Clock& clock);

  // Service: the node's timers (beacon and announce timeouts, neighbour-check retries).
  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return node_.NextDeadline(); }

  // SwitchProtocol.
  bool Claims(std::span<const std::uint8_t> frame) const override;
  bool OnFrame(std::span<const std::uint8_t> frame, hal::PortId port) override;
  void OnLinkChange(hal::PortId port, bool up) override;

  // cip::DlrProvider.
  cip::DlrObjectValues DlrValues() const override;

  const net::DlrRingStatus& status() const { return node_.status(); }
  std::uint32_t frames_sent() const { return frames_sent_; }
  std::uint32_t send_failures() const { return send_failures_; }

 private:
  void SendQueued(hal::Micros now);
  void Send(const net::DlrTransmit& transmit, std::span<const std::uint8_t> buffer);
  void Flush(bool wanted);

  CardNetif& netif_;
  const hal::Clock& clock_;
  net::DlrRingNode node_;
  // The node's own frames are 60 bytes; only a passed-on Sign_On can be longer, and it is built on the
  // stack of the receive path (RAM is the card's tightest budget).
  std::array<std::uint8_t, net::kEthernetMinFrameSize> buffer_{};
  std::uint32_t frames_sent_ = 0;
  std::uint32_t send_failures_ = 0;  // the port had no link or refused the frame
};

}  // namespace firmware
