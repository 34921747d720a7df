/* lwIP hooks of the card (LWIP_HOOK_FILENAME in lwipopts.h; docs/network.md "DHCP", "QoS (DSCP)").
 * Included by many lwIP sources: declarations only, C linkage. */
#ifndef IPE_LWIP_HOOKS_H
#define IPE_LWIP_HOOKS_H

#include "lwip/arch.h"

#ifdef __cplusplus
extern "C" {
#endif

struct netif;
struct dhcp_msg;

/* Appends option 61 (client identifier: type 0, then the host name) to every DHCP message, and option
 * 12 (host name) to DHCPDISCOVER (lwIP 2.1.3 sends it only in DHCPREQUEST), when netif->hostname is
 * set. Leaves the options alone when they would not fit with the end option. */
void ipe_dhcp_append_options(struct netif *netif, u8_t msg_type, struct dhcp_msg *msg, u16_t *options_len);

#ifdef __cplusplus
}
#endif

#define LWIP_HOOK_DHCP_APPEND_OPTIONS(netif, dhcp, state, msg, msg_type, options_len_ptr) \
  ipe_dhcp_append_options(netif, msg_type, msg, options_len_ptr)

/* ethernet_input: a tagged frame is taken only with VLAN ID 0 (a priority tag) around IPv4. */
#define LWIP_HOOK_VLAN_CHECK(netif, eth_hdr, vlan_hdr) \
  (VLAN_ID(vlan_hdr) == 0 && (vlan_hdr)->tpid == PP_HTONS(ETHTYPE_IP))

#endif /* IPE_LWIP_HOOKS_H */
