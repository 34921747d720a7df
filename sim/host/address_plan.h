// The card's manual address as the inverter keeps it, and `--ip`: both ipe002z-host and ipe002z-inverter
// key the address into the simulated inverter at every start, as a technician would on the panel, so the
// card (in-process or under QEMU) reads it from the drive at power-up like any other setting.
//
// c504 = 0 selects the manual address; c505-c508 hold the IP address, c509-c512 the subnet mask and
// c513-c516 the default gateway, one octet per parameter (seed 000 §3.1; communication numbers C505-C509
// and C510-C516: no number ends in A-F).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "sim_inverter.h"

namespace sim {

struct AddressPlan {  // host byte order
  std::uint32_t ip = 0;
  std::uint32_t netmask = 0;
  std::uint32_t gateway = 0;
};

// "10.0.2.15" -> host byte order; false when not a dotted quad of 0-255.
bool ParseIpv4(std::string_view text, std::uint32_t& out);
std::string FormatIpv4(std::uint32_t host_order);

// "A.B.C.D/N" with N 1-30.
bool ParseCidr(std::string_view text, std::uint32_t& ip, std::uint32_t& netmask);

// "A.B.C.D/N[,GW]"; the gateway is 0.0.0.0 (none) when not given.
bool ParseAddressPlan(std::string_view text, AddressPlan& plan);

// Writes c504 = 0 and c505-c516 as W (RAM and EEPROM, one counted EEPROM write each, as on the panel),
// then stores the image. False with `error` ("--ip: the inverter refused c505 (out of range)") when
// the model refuses one.
bool KeyManualAddress(SimulatedInverter& inverter, const AddressPlan& plan, std::string& error);

}  // namespace sim
