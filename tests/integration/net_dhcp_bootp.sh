#!/usr/bin/env bash
# DHCP and BOOTP addressing against dnsmasq (docs/network.md "Addressing", issue 7). Run by tools/netns
# --no-ip with c504 = 2 and the device name "drive-7" (c081-c087) preset in the inverter:
#   (a) DHCP: dnsmasq hands 10.x.77 to the client identifier "drive-7" (type 0); the card comes up with
#       it, NS flashes 5 times (Modbus TCP) while it waits, then shows steady green; c524-c535 mirror
#       address, mask and gateway; the lease carries host name and client id; the lease (2 min) is
#       renewed at T1 without the address or an open TCP connection changing.
#   (b) BOOTP: c504 = 1 and f899 = 1 written over Modbus restart the card's network side: the DHCP
#       address goes, a BOOTP server that knows the card's MAC gives 10.x.88, mirrored to c524-c535.
source "$(dirname "$0")/lib.sh"

W=$(mktemp -d /tmp/ipe-dhcp.XXXXXX)
DNSMASQ_PID=""
cleanup() {
  [ -n "$DNSMASQ_PID" ] && kill "$DNSMASQ_PID" 2>/dev/null
  rm -rf "$W"
}
trap cleanup EXIT

start_dnsmasq() {  # extra dnsmasq options...
  [ -n "$DNSMASQ_PID" ] && { kill "$DNSMASQ_PID" 2>/dev/null; wait "$DNSMASQ_PID" 2>/dev/null || true; }
  : >"$W/dnsmasq.log"
  dnsmasq --keep-in-foreground --conf-file=/dev/null --port=0 --user=root --interface="$TAP_L" \
    --bind-interfaces --log-dhcp --log-facility="$W/dnsmasq.log" --dhcp-leasefile="$W/leases" \
    --pid-file="$W/dnsmasq.pid" --dhcp-option=3,"$SUBNET.1" "$@" &
  DNSMASQ_PID=$!
}

get_param() { "$CTL" "$CARD_CONTROL" "get $1" | sed -n "s/^$1 = \([0-9]*\).*/\1/p"; }

# mirrored A.B.C.D FIRST: c-parameters FIRST..FIRST+3 (decimal titles) hold A, B, C, D.
mirrored() {
  local want=$1 first=$2 got="" title
  for i in 0 1 2 3; do
    title=$((first + i))
    got+="$(get_param "c$title")"
    [ "$i" -lt 3 ] && got+="."
  done
  [ "$got" = "$want" ]
}

address_line() { grep "^address " "$CARD_LOG" | tail -n 1; }

[ "$CARD_IP" = "0.0.0.0" ] || fail "the card should start without an address in DHCP mode (ready: $CARD_READY)"
grep -q "^address " "$CARD_LOG" && fail "an address before any server answered: $(address_line)"

# --- (a) DHCP -------------------------------------------------------------------------------------
# dnsmasq comes up a few seconds late, so NS shows several groups of 5 flashes first.
sleep 6
led_from=$(wc -l <"$CARD_LOG")
start_dnsmasq --dhcp-range="$SUBNET.100,$SUBNET.150,255.255.255.0,2m" --dhcp-host="id:drive-7,$SUBNET.77"
wait_for 30 grep -q "^address mode=dhcp phase=in-use ip=$SUBNET.77/24 gw=$SUBNET.1 " "$CARD_LOG" ||
  fail "no DHCP address: $(address_line); dnsmasq: $(tail -5 "$W/dnsmasq.log")"
pass "DHCP: $(address_line | cut -d' ' -f2-5)"
"$(dirname "$0")/led_log.py" "$CARD_LOG" NS count5 || fail "NS did not flash 5 times while DHCP ran"
"$(dirname "$0")/led_log.py" "$CARD_LOG" MS steady-green --from-line "$led_from" || fail "MS not green"
wait_for 5 "$(dirname "$0")/led_log.py" "$CARD_LOG" NS steady-green --from-line "$led_from" ||
  fail "NS not steady green with the address: $("$CTL" "$CARD_CONTROL" leds)"
pass "LEDs: NS 5 flashes while acquiring, then steady green"

wait_for 5 mirrored "$SUBNET.77" 524 || fail "c524-c527 do not show the address"
mirrored "255.255.255.0" 528 || fail "c528-c531 do not show the mask"
mirrored "$SUBNET.1" 532 || fail "c532-c535 do not show the gateway"
pass "c524-c535 mirror $SUBNET.77/255.255.255.0 gw $SUBNET.1"

# Lease file: expiry MAC IP hostname client-id. Client id = type 0 + "drive-7".
lease=$(grep " $SUBNET.77 " "$W/leases" || true)
read -r _ lease_mac _ lease_host lease_id <<<"$lease"
[ "$lease_mac" = "$CARD_MAC" ] || fail "lease MAC '$lease_mac' is not the card's $CARD_MAC ($lease)"
[ "$lease_host" = "drive-7" ] || fail "lease host name '$lease_host' ($lease)"
[ "$lease_id" = "00:64:72:69:76:65:2d:37" ] || fail "lease client id '$lease_id' ($lease)"
pass "lease: host name drive-7, client id 00 'drive-7', MAC $CARD_MAC"

# Renewal at T1 (half of the 2-minute lease): a second DHCPACK for the same address, the address and an
# open Modbus connection unchanged.
/usr/bin/python3 - "$SUBNET.77" "$W/dnsmasq.log" <<'EOF' || fail "renewal"
import re, socket, struct, sys, time
ip, log = sys.argv[1], sys.argv[2]
s = socket.create_connection((ip, 502), timeout=3)
def read_c524():
    s.sendall(struct.pack(">HHHBBHH", 1, 0, 6, 1, 3, 0xC524, 1))
    reply = s.recv(64)
    assert reply[7] == 3, reply.hex()
    return struct.unpack(">H", reply[9:11])[0]
first = read_c524()
deadline = time.monotonic() + 80
while time.monotonic() < deadline:
    acks = re.findall(r"DHCPACK\(\S+\) " + re.escape(ip), open(log).read())
    if len(acks) >= 2:
        break
    time.sleep(1)
else:
    sys.exit(f"no renewal within 80 s: {len(acks)} DHCPACK")
time.sleep(0.5)
assert read_c524() == first == int(ip.split(".")[0]), "the connection or c524 changed across the renewal"
print("ok: lease renewed (DHCPACK #2) on the same TCP connection")
EOF
address_line | grep -q "ip=$SUBNET.77/24" || fail "address changed after the renewal: $(address_line)"

# --- (b) BOOTP after a communication reset --------------------------------------------------------
start_dnsmasq --dhcp-range="$SUBNET.0,static,255.255.255.0" --dhcp-host="$CARD_MAC,$SUBNET.88"
led_from=$(wc -l <"$CARD_LOG")
mbpoll -m tcp -a 1 -0 -r $((0xC504)) -t 4 -1 "$SUBNET.77" 1 >/dev/null || fail "c504 = 1 over Modbus"
timeout 10 mbpoll -m tcp -a 1 -0 -r $((0x0899)) -t 4 -1 "$SUBNET.77" 1 >/dev/null || true  # the reset cuts the reply
wait_for 30 grep -q "^address mode=bootp phase=in-use ip=$SUBNET.88/24 gw=$SUBNET.1 " "$CARD_LOG" ||
  fail "no BOOTP address: $(address_line); stats: $("$CTL" "$CARD_CONTROL" stats | grep '^addr\.'); dnsmasq: $(tail -5 "$W/dnsmasq.log")"
grep -q "BOOTP(.*) $SUBNET.88 $CARD_MAC" "$W/dnsmasq.log" || fail "dnsmasq did not log a BOOTP answer: $(tail -5 "$W/dnsmasq.log")"
wait_for 5 mirrored "$SUBNET.88" 524 || fail "c524-c527 do not show the BOOTP address"
[ "$(get_param c504)" = 1 ] || fail "c504 is not 1"
ping -c 1 -W 2 "$SUBNET.88" >/dev/null || fail "no ping answer at the BOOTP address"
ping -c 1 -W 1 "$SUBNET.77" >/dev/null 2>&1 && fail "the DHCP address still answers after the reset"
pass "BOOTP by MAC after c504 = 1 and f899 = 1: $SUBNET.88, mirrored, the old address gone"
pass "net_dhcp_bootp"
