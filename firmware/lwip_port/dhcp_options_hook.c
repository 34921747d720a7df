/* The card's DHCP options beyond lwIP's (lwip_hooks.h). Built into the lwip library itself, so every
 * program linking lwIP has the hook. */
#include <string.h>

#include "lwip/opt.h"
#include "lwip/dhcp.h"
#include "lwip/netif.h"
#include "lwip/prot/dhcp.h"
#include "lwip_hooks.h"

/* One option (code, length, data) at *len, if it fits with one byte left for the end option. */
static void append_option(struct dhcp_msg *msg, u16_t *len, u8_t code, u8_t type_byte, int with_type,
                          const char *data, size_t data_len) {
  const size_t body = data_len + (with_type ? 1U : 0U);
  if (body > 255U || (size_t)*len + 2U + body + 1U > DHCP_OPTIONS_LEN) return;
  msg->options[(*len)++] = code;
  msg->options[(*len)++] = (u8_t)body;
  if (with_type) msg->options[(*len)++] = type_byte;
  memcpy(&msg->options[*len], data, data_len);
  *len = (u16_t)(*len + data_len);
}

void ipe_dhcp_append_options(struct netif *netif, u8_t msg_type, struct dhcp_msg *msg, u16_t *options_len) {
  const char *name = netif->hostname;
  if (name == NULL || name[0] == '\0') return;
  const size_t length = strlen(name);
  if (msg_type == DHCP_DISCOVER) {
    append_option(msg, options_len, DHCP_OPTION_HOSTNAME, 0, 0, name, length);
  }
  /* RFC 2132 §9.14: type 0 = an identifier that is not a hardware address. */
  append_option(msg, options_len, DHCP_OPTION_CLIENT_ID, 0, 1, name, length);
}
