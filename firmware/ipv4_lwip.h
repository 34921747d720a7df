// IPv4 addresses between the card's host-order integers (192.168.0.10 = 0xC0A8000A, as in the CIP
// objects, the c-parameters and net/) and lwIP's network-order ip4_addr_t.
#pragma once

#include <array>
#include <cstdint>

#include "lwip/ip4_addr.h"

namespace firmware {

inline ip4_addr_t ToLwip(std::uint32_t host_order) {
  ip4_addr_t address;
  ip4_addr_set_u32(&address, lwip_htonl(host_order));
  return address;
}

// 0 for a null address (lwIP's accessors return null for a netif without IPv4).
inline std::uint32_t HostOrder(const ip4_addr_t* address) {
  return address == nullptr ? 0 : lwip_ntohl(ip4_addr_get_u32(address));
}

// Four parameters of one octet each, most significant first (c505-c508, c524-c527 ...).
constexpr std::uint32_t FromOctets(const std::array<std::uint8_t, 4>& octets) {
  return static_cast<std::uint32_t>(octets[0]) << 24 | static_cast<std::uint32_t>(octets[1]) << 16 |
         static_cast<std::uint32_t>(octets[2]) << 8 | octets[3];
}

}  // namespace firmware
