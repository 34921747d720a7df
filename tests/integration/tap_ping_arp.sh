#!/usr/bin/env bash
# (a) The card on a TAP port answers ping and ARP with its own MAC. Runs inside tools/netns.
source "$(dirname "$0")/lib.sh"

ping -c 3 -i 0.2 -W 2 "$CARD_IP" >/tmp/ping.$$ || { cat /tmp/ping.$$; fail "no ping reply"; }
grep -q "3 received" /tmp/ping.$$ || { cat /tmp/ping.$$; fail "lost ping replies"; }
rm -f /tmp/ping.$$
pass "3 of 3 echo replies from $CARD_IP"

neigh=$(ip neigh show "$CARD_IP" dev "$TAP_L")
grep -qi "lladdr $CARD_MAC" <<<"$neigh" || fail "neighbour entry '$neigh' does not carry $CARD_MAC"
pass "kernel learned $CARD_IP at $CARD_MAC through ARP"

# An explicit ARP request, answered by the card (unicast reply carrying its MAC).
out=$(timeout 10 arping -c 2 -w 5 -I "$TAP_L" "$CARD_IP" 2>&1) || { echo "$out"; fail "no ARP reply"; }
grep -qi "$CARD_MAC" <<<"$out" || { echo "$out"; fail "ARP reply without the card's MAC"; }
pass "arping answered by $CARD_MAC"

# Nobody else answers for an address that is not the card's.
if timeout 5 arping -c 1 -w 2 -I "$TAP_L" "${CARD_IP%.*}.77" >/dev/null 2>&1; then
  fail "someone answered ARP for an address that is not the card's"
fi
pass "no ARP reply for a foreign address"
