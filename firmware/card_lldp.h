// LLDP on the card's two ports (docs/network.md "LLDP"): net::LldpAgent bound to the netif. Frames with
// EtherType 0x88CC for the card come in through CardNetif's port frame handler with their port; the
// agent's frames go out of one port each (CardNetif::SendFrameOn). The system name follows the device
// name of each configuration load (c081-c096), the management address the address in use; the ports'
// links are followed at each poll (a link change is an event of the loop).
#pragma once

#include <span>
#include <string_view>

#include "card_addressing.h"
#include "card_netif.h"
#include "configurable_service.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "hal/text_line.h"
#include "net/lldp_agent.h"

namespace firmware {

class CardLldp final : public Service, public ConfigurableService, public PortFrameHandler, private net::LldpSink {
 public:
  // `system_description` has static storage.
  CardLldp(CardNetif& netif, const CardAddressing& addressing, const hal::Clock& clock,
           std::string_view system_description);

  base::Status Configure(const config::CardConfig& config) override;
  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return agent_.NextDeadline(); }
  bool TakeFrame(hal::PortId port, std::span<const std::uint8_t> frame) override;

  const net::LldpAgent& agent() const { return agent_; }

 private:
  void SendLldp(std::size_t port, std::span<const std::uint8_t> frame) override;

  CardNetif& netif_;
  const CardAddressing& addressing_;
  const hal::Clock& clock_;
  net::LldpAgent agent_;
  std::array<bool, net::kLldpPorts> up_{};
};

// A received chassis or port ID as `stats` and the web page show it: a MAC as aa:bb:cc:dd:ee:ff, an
// IPv4 network address dotted, anything else as text (see DescribeLldpText).
void DescribeLldpId(const net::LldpId& id, bool chassis, hal::TextLine& line);
// Text as received, each byte outside printable ASCII (and the space) shown as '_', so that a `stats`
// line stays one NAME=VALUE per field.
void DescribeLldpText(std::span<const std::uint8_t> text, hal::TextLine& line);

}  // namespace firmware
