// IPv4 addresses between the card's base::Ipv4Address (as in the CIP objects, the c-parameters and
// net/) and lwIP's network-order ip4_addr_t.
#pragma once

#include "base/addresses.h"
#include "lwip/ip4_addr.h"

namespace firmware {

inline ip4_addr_t ToLwip(base::Ipv4Address address) {
  ip4_addr_t lwip_address;
  ip4_addr_set_u32(&lwip_address, lwip_htonl(address.HostOrder()));
  return lwip_address;
}

// 0.0.0.0 for a null address (lwIP's accessors return null for a netif without IPv4).
inline base::Ipv4Address FromLwip(const ip4_addr_t* address) {
  return address == nullptr ? base::Ipv4Address() : base::Ipv4Address(lwip_ntohl(ip4_addr_get_u32(address)));
}

}  // namespace firmware
