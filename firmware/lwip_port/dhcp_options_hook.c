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

/* The type the message really has: lwIP writes option 53 first (dhcp_create_msg). lwIP 2.1.3's
 * dhcp_rebind passes DHCP_DISCOVER to the hook for its DHCPREQUEST, which already carries lwIP's own
 * option 12: trusting the argument would add the host name twice (and, with a 16-character name, leave
 * no room for option 61). */
static u8_t message_type(const struct dhcp_msg *msg, u16_t len, u8_t given) {
  if (len >= 3 && msg->options[0] == DHCP_OPTION_MESSAGE_TYPE && msg->options[1] == DHCP_OPTION_MESSAGE_TYPE_LEN) {
    return msg->options[2];
  }
  return given;
}

void ipe_dhcp_append_options(struct netif *netif, u8_t msg_type, struct dhcp_msg *msg, u16_t *options_len) {
  const char *name = netif->hostname;
  if (name == NULL || name[0] == '\0') return;
  const size_t length = strlen(name);
  if (message_type(msg, *options_len, msg_type) == DHCP_DISCOVER) {
    append_option(msg, options_len, DHCP_OPTION_HOSTNAME, 0, 0, name, length);
  }
  /* RFC 2132 §9.14: type 0 = an identifier that is not a hardware address. */
  append_option(msg, options_len, DHCP_OPTION_CLIENT_ID, 0, 1, name, length);
}
