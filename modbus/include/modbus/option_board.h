// What the Modbus server shows of the card itself: the register map of unit 251 (the option board's
// server, seed 000 §8.2) and the strings of Read Device Identification (§8.8). The firmware fills an
// OptionBoardData and hands it to the server whenever something in it changes; the server adds what
// it knows itself (its configuration, its clients, the loss supervision).
//
// The map (docs/modbus.md "Unit 251") is read-only, one value per register, octets of addresses one
// per register in the order of the c-parameters that hold them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/status.h"
#include "config/card_config.h"
#include "drive_link/link_client.h"

namespace modbus {

// A short ASCII string of fixed capacity (no heap). Longer text is cut at kCapacity characters; 32
// keeps every Read Device Identification answer inside one PDU.
class IdentityText {
 public:
  static constexpr std::size_t kCapacity = 32;
  constexpr IdentityText() = default;
  constexpr explicit IdentityText(std::string_view text) { Set(text); }
  constexpr void Set(std::string_view text) {
    length_ = text.size() < kCapacity ? text.size() : kCapacity;
    for (std::size_t i = 0; i < length_; ++i) chars_[i] = text[i];
  }
  constexpr std::string_view view() const { return std::string_view(chars_.data(), length_); }

 private:
  std::array<char, kCapacity> chars_{};
  std::size_t length_ = 0;
};

struct OptionBoardData {
  // The card's firmware version, shown as 4 hex digits: 0x0106 is "0106" (FC 43 unit 251, object 2)
  // and register 0 of unit 251.
  std::uint16_t firmware_version = 0x0106;
  // c502/c503, the MAC, the actual address (c524-c535) and c536, as the card writes them back.
  config::CardStatus status;
  drive_link::LinkState drive_link = drive_link::LinkState::kStarting;
  // Read from the inverter at start-up (the firmware's job); empty until then, and sent as such.
  IdentityText drive_product_code;  // FC 43 unit 248 object 1, e.g. "VFMB1S-2007PL"
  IdentityText drive_version;       // object 2, e.g. "10801"
  IdentityText drive_product_name;  // object 4, "VF-MB1" or "VF-S15"
  IdentityText model_name{"TSB"};                    // object 5
  IdentityText user_application_name{"ModbusTCP"};  // object 6
};

// What the server itself adds to the map.
enum class LossState : std::uint16_t {
  kDisabled = 0,  // c523 = 0
  kWaiting = 1,   // no counted communication yet (or since start-up)
  kRunning = 2,   // supervising: counted communication within c523
  kLost = 3,      // c523 expired: NetworkLost reported, waiting for the master
};

struct OptionBoardView {
  const OptionBoardData& data;
  const config::CardConfig& config;
  std::uint16_t clients = 0;  // open Modbus TCP connections
  LossState loss = LossState::kDisabled;
};

// Registers of unit 251: addresses 0 .. kOptionBoardRegisterCount-1.
inline constexpr std::uint16_t kOptionBoardRegisterCount = 50;

// The value at `address`; kNotFound outside the map.
base::Result<std::uint16_t> ReadOptionBoardRegister(const OptionBoardView& view, std::uint16_t address);

// The firmware version as FC 43 shows it: 4 upper-case hex digits.
IdentityText FirmwareVersionText(std::uint16_t version);

}  // namespace modbus
