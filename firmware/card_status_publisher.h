// Keeps what the card shows about itself current, in the inverter and in the front ends:
//
// - every kPublishInterval: the actual rates of the L/R ports (c502/c503), the MAC (c517-c522), the
//   address in use (c524-c535) and loss of carrier (c536 = 3 while no port has link) go to the register
//   proxy, which writes back what changed; the same values,
//   the drive-link state and c536 go to the Modbus server's option-board data (unit 251, FC 43);
// - after each configuration load (start-up, f899 = 1, link recovery): the configuration goes to every
//   front end (the Modbus and EtherNet/IP services open or close their ports by c500), and the drive's
//   identity is read once (FB05 model code, FE08 CPU version) for FC 43 on unit 248 and for the
//   DriveIdentitySink (the CIP Identity object's product code and name).
//
// Device-path code: no allocation; the firmware's composition root owns every object referenced here.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "card_netif.h"
#include "configurable_service.h"
#include "drive_link/register_proxy.h"
#include "event_loop.h"
#include "hal/frame_port.h"
#include "modbus/option_board.h"
#include "modbus/server.h"

namespace firmware {

// c502/c503 for a port's link: 0 unconnected, 1 10M full, 2 10M half, 3 100M full, 4 100M half. A port
// without a negotiated speed (a host TAP or loopback port) shows 100M full: what the card would
// negotiate with a switch.
std::uint16_t PortRateCode(const hal::LinkState& link);

// The FC 43 strings for the drive (unit 248): product code, version and product name from the model
// code FB05 and the CPU version FE08. docs/modbus.md "Read Device Identification" lists the table.
struct DriveIdentity {
  modbus::IdentityText product_code;
  modbus::IdentityText version;
  modbus::IdentityText product_name;
};
DriveIdentity DescribeDrive(std::uint16_t fb05, std::uint16_t fe08);

class CardStatusPublisher final : public Service,
                                  public drive_link::ConfigListener,
                                  private drive_link::AccessListener {
 public:
  static constexpr hal::Micros kPublishInterval = 100 * hal::kMicrosPerMilli;

  static constexpr std::size_t kMaxFrontEnds = 10;

  // At most kMaxFrontEnds front ends (more are ignored); `identity_sink` may be null.
  CardStatusPublisher(drive_link::RegisterProxy& proxy, modbus::Server& modbus_server,
                      std::span<ConfigurableService* const> front_ends, CardNetif& netif,
                      std::uint16_t firmware_version, DriveIdentitySink* identity_sink = nullptr);

  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return next_publish_; }

  void OnConfigLoaded(const config::ParsedConfig& parsed) override;

  // One more front end, for one built after the publisher (the web server, whose pages show the
  // publisher's data). kResourceExhausted beyond kMaxFrontEnds.
  base::Status AddFrontEnd(ConfigurableService& front_end);

  const modbus::OptionBoardData& board_data() const { return board_; }

 private:
  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;
  void RequestIdentity();
  void ConfigureFrontEnds(bool only_pending);
  config::CardStatus CurrentStatus();

  drive_link::RegisterProxy& proxy_;
  modbus::Server& modbus_server_;
  CardNetif& netif_;
  DriveIdentitySink* identity_sink_ = nullptr;
  std::array<ConfigurableService*, kMaxFrontEnds> front_ends_{};
  std::size_t front_end_count_ = 0;
  modbus::OptionBoardData board_;
  config::CardConfig config_;  // the last configuration loaded
  std::array<bool, kMaxFrontEnds> pending_{};  // a front end refused it (no PCB): try again
  hal::Micros next_publish_ = 0;

  // The identity reads: FB05 then FE08, one at a time; retried at the next publish when refused.
  bool identity_wanted_ = false;
  drive_link::AccessToken identity_token_ = drive_link::kNoAccess;
  std::uint16_t identity_step_ = 0;  // 0: FB05, 1: FE08
  std::uint16_t fb05_ = 0;
};

}  // namespace firmware
