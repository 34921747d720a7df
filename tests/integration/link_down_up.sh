#!/usr/bin/env bash
# (b) Unplugging and plugging the cable through the control socket: lwIP follows (link state, no
# traffic while down, gratuitous ARP when the link returns); c536 = 3 (loss of carrier) while no port has
# link; NS flashes 3 times (Modbus TCP "unplugged"); ACD sends two semi-active probes after the link
# returns. Runs inside tools/netns.
source "$(dirname "$0")/lib.sh"

[ "$(stat_of netif.link)" = up ] || fail "link not up at start"
ping -c 1 -W 2 "$CARD_IP" >/dev/null || fail "no ping before unplugging"

"$CTL" "$CARD_CONTROL" "link L down" >/dev/null || fail "link L down refused"
led_from=$(wc -l <"$CARD_LOG")
wait_for 3 stat_is netif.link down || fail "lwIP netif did not go down"
[ "$(stat_of port.L.link)" = down ] || fail "port L still reports link"
leds=$("$CTL" "$CARD_CONTROL" leds)
grep -q "LNK-L=off" <<<"$leds" || fail "LNK-L not off with the cable out: $leds"
pass "link down: netif down, port L down, LNK-L off"
wait_for 3 param_is c536 3 || fail "c536 does not show loss of carrier: $("$CTL" "$CARD_CONTROL" "get c536")"
pass "c536 = 3 (loss of carrier)"

ip neigh flush dev "$TAP_L"
if ping -c 2 -i 0.3 -W 1 "$CARD_IP" >/dev/null 2>&1; then fail "card answered with the cable out"; fi
pass "no answer while unplugged"

# lwIP announces itself (gratuitous ARP) when the link comes back.
timeout 10 tcpdump -n -i "$TAP_L" -c 1 -l "arp and arp[6:2] = 1 and arp[14:4] = arp[24:4]" \
  >"$CARD_STATE_DIR/garp.txt" 2>/dev/null &
dump=$!
sleep 1
sleep 4  # (5 s unplugged in all: two groups of NS flashes)
"$(dirname "$0")/led_log.py" "$CARD_LOG" NS count3 --from-line "$led_from" || fail "NS does not flash 3 times while unplugged"
pass "NS: 3 flashes while unplugged"
probes_before=$(stat_of addr.acd_frames_sent)
"$CTL" "$CARD_CONTROL" "link L up" >/dev/null || fail "link L up refused"
wait_for 3 stat_is netif.link up || fail "lwIP netif did not come back up"
wait "$dump" || fail "no gratuitous ARP after the link came back"
grep -q "$CARD_IP" "$CARD_STATE_DIR/garp.txt" || fail "gratuitous ARP not for $CARD_IP"
pass "link up: netif up and gratuitous ARP for $CARD_IP"

ping -c 2 -i 0.3 -W 2 "$CARD_IP" >/dev/null || fail "no ping after plugging back"
wait_for 3 param_is c536 0 || fail "c536 not back to 0 with the link"
semi_active() { [ "$(stat_of addr.acd_frames_sent)" -ge $((probes_before + 2)) ]; }
wait_for 3 semi_active || fail "no semi-active ACD probes after the link came back"
pass "c536 back to 0; two semi-active ACD probes"
[ "$(stat_of loop.link_changes)" -ge 2 ] || fail "event loop did not count the link changes"
pass "ping works again"

out=$("$CTL" "$CARD_CONTROL" "link R down" || true)
[ "$out" = "error port R NOT_FOUND (not present)" ] || fail "absent port R: got '$out'"
out=$("$CTL" "$CARD_CONTROL" "link X down" || true)
[ "$out" = "error usage: link L|R up|down" ] || fail "bad port letter: got '$out'"
pass "control socket refuses an absent port and a bad letter with exact errors"
