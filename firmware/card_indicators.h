// The card's indicators, driven by one state model (NET-5, seed 000 §2.4; docs/network.md "LED model"):
// MS and NS from net::LedModel, LNK L/R from each port's link (green 100 Mbit/s, yellow 10 Mbit/s, off),
// and the power-up test on all four from the moment the card starts.
//
// Inputs, gathered at every poll: the protocol (c500, from each configuration load), the drive link
// (configured = configuration loaded; minor fault = link degraded; major = e-23), the addressing (an
// address in use, BOOTP/DHCP running, duplicate address), the ports' links, and the connections
// (EtherNet/IP: the connection table; Modbus TCP: the loss action of c523, err8).
#pragma once

#include "card_addressing.h"
#include "cip/io_connection.h"
#include "configurable_service.h"
#include "drive_link/register_proxy.h"
#include "event_loop.h"
#include "hal/frame_port.h"
#include "hal/leds.h"
#include "net/led_model.h"

namespace firmware {

struct IndicatorSources {
  const hal::FramePort& port;
  const drive_link::RegisterProxy& proxy;
  const CardAddressing& addressing;
  const cip::ConnectionTable* connections = nullptr;  // null: no EtherNet/IP side
};

class CardIndicators final : public Service, public ConfigurableService {
 public:
  // Starts the power-up test at `now`.
  CardIndicators(const IndicatorSources& sources, hal::Leds& leds, hal::Micros now);

  // Runs the power-up test again from `now`: the card calls it when its loop starts, so that a slow
  // start (a first boot hashing the default passwords) does not eat into the test's steps.
  void RestartPowerUpTest(hal::Micros now) {
    model_.StartPowerUpTest(now);
    next_change_ = 0;
  }

  base::Status Configure(const config::CardConfig& config) override;
  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return next_change_; }

  // The inputs as gathered now (for tests and the control socket).
  net::LedInputs Gather() const;
  const net::LedModel& model() const { return model_; }

 private:
  void DriveLinkLeds(hal::Micros now);
  // The ports' link state as the LNK LEDs show it: up and 10 Mbit/s per port, one bit each.
  std::uint8_t PortLinks() const;

  IndicatorSources sources_;
  hal::Leds& leds_;
  net::LedModel model_;
  net::Protocol protocol_ = net::Protocol::kModbusTcp;
  hal::Micros next_change_ = 0;
  std::uint8_t port_links_ = 0xFF;  // PortLinks() at the last update (0xFF: none yet)
};

}  // namespace firmware
