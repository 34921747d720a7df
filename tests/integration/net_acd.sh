#!/usr/bin/env bash
# Address Conflict Detection on the wire (docs/network.md "Address Conflict Detection", issue 7), with the
# card on TAP in a namespace (tools/netns --pcap, Modbus TCP):
#   (a) start-up: 4 ARP probes 200 ms apart for the address, then announcements; arping -0 (a host
#       probing for the card's address) gets the card's ordinary ARP reply;
#   (b) a conflict while probing: the address is changed over Modbus (c508) to one the kernel of the
#       namespace holds, and f899 = 1 restarts the network side; the kernel answers the probe, so the
#       card never takes the address: no announcement, phase conflict, attribute 11 = activity 1 with the
#       kernel's MAC and ARP PDU; power-cycle brings the card back on its --ip address;
#   (c) conflicts while in use (scapy): the first is defended with one announcement and the address kept,
#       the second within 10 s makes the card drop it: attribute 11 = activity 2 with the second packet,
#       NS flashes 4 times (Modbus TCP "duplicate IP"), no ping answer.
source "$(dirname "$0")/lib.sh"

OTHER_MAC=00:00:5e:00:53:99
address_now() { "$CTL" "$CARD_CONTROL" address | head -n 1; }
pcap_count() { tshark -r "$CARD_PCAP" -Y "$1" 2>/dev/null | wc -l; }
hex_ip() { printf '%02x' ${1//./ }; }
hex_mac() { tr -d ':' <<<"$1"; }

# --- (a) start-up ------------------------------------------------------------------------------------
probes=$(tshark -r "$CARD_PCAP" -T fields -e frame.time_relative \
  -Y "arp.src.hw_mac == $CARD_MAC && arp.src.proto_ipv4 == 0.0.0.0 && arp.dst.proto_ipv4 == $CARD_IP" 2>/dev/null)
[ "$(wc -l <<<"$probes")" = 4 ] || fail "start-up probes: $(wc -l <<<"$probes"), want 4: $probes"
/usr/bin/python3 - "$probes" <<'EOF' || fail "probe spacing"
import sys
t = [float(x) for x in sys.argv[1].split()]
gaps = [round((b - a) * 1000) for a, b in zip(t, t[1:])]
assert all(150 <= g <= 260 for g in gaps), f"probe gaps {gaps} ms, want 200"
print(f"ok: 4 probes, gaps {gaps} ms")
EOF
announce_filter="eth.dst == ff:ff:ff:ff:ff:ff && arp.opcode == 1 && arp.src.hw_mac == $CARD_MAC && arp.src.proto_ipv4 == $CARD_IP && arp.dst.proto_ipv4 == $CARD_IP"
announcements() { pcap_count "$announce_filter"; }
announcements_at_least() { [ "$(announcements)" -ge "$1" ]; }
wait_for 5 announcements_at_least 2 || fail "no announcements after the probes"
reply=$(arping -0 -c 2 -w 3 -i "$TAP_L" "$CARD_IP" 2>&1 || true)
grep -qi "$CARD_MAC" <<<"$reply" || fail "arping -0 (a probe for the card's address) got no reply from $CARD_MAC: $reply"
pass "start-up: 4 probes ~200 ms apart, announcements, probes from others answered"

# --- (b) conflict while probing ------------------------------------------------------------------------
TAKEN="$SUBNET.3"
ip addr add "$TAKEN/24" dev "$TAP_L"
KERNEL_MAC=$(cat "/sys/class/net/$TAP_L/address")
mbpoll -m tcp -a 1 -0 -r $((0xC508)) -t 4 -1 "$CARD_IP" 3 >/dev/null || fail "c508 = 3 over Modbus"
timeout 10 mbpoll -m tcp -a 1 -0 -r $((0x0899)) -t 4 -1 "$CARD_IP" 1 >/dev/null || true
wait_for 15 bash -c "\"$CTL\" \"$CARD_CONTROL\" address | grep -q 'phase=conflict'" ||
  fail "no probe conflict for $TAKEN: $(address_now)"
state=$(address_now)
grep -q "mode=manual phase=conflict ip=0.0.0.0/0 gw=0.0.0.0 duplicate=1 " <<<"$state" || fail "state: $state"
# Attribute 11: activity 1, the kernel's MAC, its ARP reply PDU (op 2, sender = kernel MAC + .3,
# target = the card's MAC + 0.0.0.0: the answer to a probe).
want="01$(hex_mac "$KERNEL_MAC")000108000604""0002$(hex_mac "$KERNEL_MAC")$(hex_ip "$TAKEN")$(hex_mac "$CARD_MAC")00000000"
grep -q "conflict=$want\$" <<<"$state" || fail "attribute 11 after a probe conflict: $state; want conflict=$want"
[ "$(pcap_count "arp.src.hw_mac == $CARD_MAC && arp.src.proto_ipv4 == $TAKEN")" = 0 ] ||
  fail "the card announced $TAKEN although it is taken"
ping -c 1 -W 1 "$CARD_IP" >/dev/null 2>&1 && fail "the old address still answers after the restart"
pass "probe conflict: $TAKEN not taken, attribute 11 = $want"
ip addr del "$TAKEN/24" dev "$TAP_L"

"$CTL" "$CARD_CONTROL" power-cycle >/dev/null || fail "power-cycle refused"
second_ready() { [ "$(grep -c '^ready ' "$CARD_LOG")" -ge 2 ]; }
wait_for 15 second_ready || fail "no ready line after power-cycle"
grep '^ready ' "$CARD_LOG" | tail -n 1 | grep -q "ip=$CARD_IP " || fail "not back on $CARD_IP: $(grep '^ready ' "$CARD_LOG" | tail -n 1)"
wait_for 5 ping -c 1 -W 1 "$CARD_IP" || fail "no ping after power-cycle"
pass "power-cycle: --ip brings the card back on $CARD_IP"

# --- (c) conflicts while in use ------------------------------------------------------------------------
sleep 3  # the announcements of the new start are over
before=$(announcements)
inject() {  # ARP operation 1 (request) or 2 (reply) from OTHER_MAC claiming the card's address
  /usr/bin/python3 - "$TAP_L" "$OTHER_MAC" "$CARD_IP" "$1" <<'EOF'
import sys
from scapy.all import ARP, Ether, sendp
iface, mac, ip, op = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
sendp(Ether(src=mac, dst="ff:ff:ff:ff:ff:ff") / ARP(op=op, hwsrc=mac, psrc=ip, hwdst="ff:ff:ff:ff:ff:ff", pdst=ip),
      iface=iface, verbose=False)
EOF
}
inject 1
wait_for 3 announcements_at_least $((before + 1)) || fail "no defence announcement ($before -> $(announcements))"
state=$(address_now)
grep -q "phase=in-use ip=$CARD_IP/24 .*duplicate=0 conflict=02$(hex_mac "$OTHER_MAC")" <<<"$state" || fail "after one conflict: $state"
ping -c 1 -W 1 "$CARD_IP" >/dev/null || fail "the defended address does not answer"
pass "first conflict defended with one announcement, address kept"

led_from=$(wc -l <"$CARD_LOG")
inject 2
want="02$(hex_mac "$OTHER_MAC")000108000604""0002$(hex_mac "$OTHER_MAC")$(hex_ip "$CARD_IP")ffffffffffff$(hex_ip "$CARD_IP")"
wait_for 3 bash -c "\"$CTL\" \"$CARD_CONTROL\" address | grep -q 'phase=conflict'" || fail "no yield: $(address_now)"
grep -q "duplicate=1 conflict=$want\$" <<<"$(address_now)" || fail "attribute 11 after the yield: $(address_now); want $want"
sleep 1
[ "$(announcements)" = $((before + 1)) ] || fail "announcements: $before before, $(announcements) after the defence and the yield (want 1 more): $(tshark -r "$CARD_PCAP" -Y "arp" 2>/dev/null | tail -8)"
ping -c 1 -W 1 "$CARD_IP" >/dev/null 2>&1 && fail "the yielded address still answers"
"$CTL" "$CARD_CONTROL" stats | grep -q "^addr.duplicate=1" || fail "stats addr.duplicate"
sleep 5.5
"$(dirname "$0")/led_log.py" "$CARD_LOG" NS count4 --from-line "$led_from" || fail "NS does not flash 4 times"
pass "second conflict within 10 s: address given up, attribute 11 = $want, NS 4 flashes"
pass "net_acd"
