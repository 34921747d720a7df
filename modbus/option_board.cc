#include "modbus/option_board.h"

namespace modbus {
namespace {

using Map = std::array<std::uint16_t, kOptionBoardRegisterCount>;

// Puts `values` at `first` onwards, one per register.
template <typename Octets>
void Put(Map& map, std::size_t first, const Octets& values) {
  for (std::size_t i = 0; i < values.size(); ++i) map[first + i] = values[i];
}

// Register 47: the drive link's state as documented, independent of the enum's order.
std::uint16_t LinkStateCode(drive_link::LinkState state) {
  switch (state) {
    case drive_link::LinkState::kStarting:
      return 0;
    case drive_link::LinkState::kUp:
      return 1;
    case drive_link::LinkState::kDegraded:
      return 2;
    case drive_link::LinkState::kFault:
      return 3;
  }
  return 0;
}

// The whole map, in address order (docs/modbus.md "Unit 251" has the same table).
Map BuildMap(const OptionBoardView& view) {
  const config::CardConfig& config = view.config;
  const config::CardStatus& status = view.data.status;
  Map map{};
  map[0] = view.data.firmware_version;
  map[1] = static_cast<std::uint16_t>(config.protocol);      // c500
  map[2] = static_cast<std::uint16_t>(config.ip_mode);       // c504
  Put(map, 3, config.ip.octets());                           // c505-c508
  Put(map, 7, config.netmask.octets());                      // c509-c512
  Put(map, 11, config.gateway.octets());                     // c513-c516
  Put(map, 15, status.mac.octets());                         // c517-c522
  Put(map, 21, status.ip.octets());                          // c524-c527
  Put(map, 25, status.netmask.octets());                     // c528-c531
  Put(map, 29, status.gateway.octets());                     // c532-c535
  map[33] = status.ethernet_error;                           // c536
  Put(map, 34, status.port_rates);                           // c502, c503
  map[36] = config.timeout_tenths;                           // c523
  map[37] = config.loss_delay_tenths;                        // c100
  map[38] = config.loss_action;                              // c101
  map[39] = config.loss_preset_speed;                        // c102
  map[40] = config.loss_condition;                           // c103
  map[41] = config.io_scanning ? 1 : 0;                      // c604
  Put(map, 42, config.modbus_master.octets());               // c600-c603
  map[46] = config.web_server ? 1 : 0;                       // c554
  map[47] = LinkStateCode(view.data.drive_link);
  map[48] = view.clients;
  map[49] = static_cast<std::uint16_t>(view.loss);
  return map;
}

}  // namespace

base::Result<std::uint16_t> ReadOptionBoardRegister(const OptionBoardView& view, std::uint16_t address) {
  if (address >= kOptionBoardRegisterCount) return base::NotFound();
  return BuildMap(view)[address];
}

IdentityText FirmwareVersionText(std::uint16_t version) {
  constexpr std::string_view kDigits = "0123456789ABCDEF";
  std::array<char, 4> text{};
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned shift = static_cast<unsigned>(12 - 4 * i);
    text[i] = kDigits[(version >> shift) & 0xF];
  }
  return IdentityText(std::string_view(text.data(), text.size()));
}

}  // namespace modbus
