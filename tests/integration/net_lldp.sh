#!/usr/bin/env bash
# LLDP with Debian's lldpd as the real neighbour (docs/network.md "LLDP", issue 22). tools/netns --ports 2
# gives the card tapL and tapR in this namespace; one lldpd runs on both, with its own control socket,
# configuration and PID file in a temporary directory (nothing outside the namespace is touched), a 1 s
# transmit interval (TTL 4 s), system name "lldp-peer", port IDs by interface name and 10.253.0.1 as
# its management address. The card's device name is "lldp-node" (c081-c089, preset by CMakeLists.txt).
#   (a) lldpd sees the card on each port with exactly: chassis ID = the card's MAC, port ID local "1"
#       (tapL) / "2" (tapR), TTL 120, system name, system description, management address = the card's
#       IP, port description;
#   (b) the card sees lldpd on the right port (`stats`: lldp.L.0 / lldp.R.0 with lldpd's chassis ID,
#       port ID, TTL, name and management address) and on the web page's statistics (JSON);
#   (c) the card's switch does not forward LLDP: lldpd hears only the card, never itself;
#   (d) lldpd stops: its shutdown LLDPDU (TTL 0) removes it from the card's table;
#   (e) tshark decodes the card's LLDP frames from the capture with no malformed or error item.
source "$(dirname "$0")/lib.sh"

LLDP_DIR=$(mktemp -d /tmp/ipe-lldp.XXXXXX)
chmod 755 "$LLDP_DIR"  # lldpd runs lldpcli on its socket as its unprivileged user
LLDP_SOCK="$LLDP_DIR/lldpd.socket"
LLDP_PID_FILE="$LLDP_DIR/lldpd.pid"
NAME=lldp-node
DESCRIPTION="IPE002Z EtherNet/IP + Modbus TCP option card, firmware V1.06"

stop_lldpd() {
  local pid
  pid=$(cat "$LLDP_PID_FILE" 2>/dev/null) || return 0
  if kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null || true
    wait_for 5 bash -c "! kill -0 $pid" || kill -KILL "$pid" 2>/dev/null || true
  fi
  rm -f "$LLDP_PID_FILE"
}
cleanup() { stop_lldpd; rm -rf "$LLDP_DIR"; }
trap cleanup EXIT

lldpcli_kv() { lldpcli -u "$LLDP_SOCK" -f keyvalue "$@"; }
# kv KEY TEXT: the value of KEY in lldpcli's keyvalue TEXT.
kv() { sed -n "s/^$1=//p" <<<"$2"; }

cat >"$LLDP_DIR/lldpd.conf" <<EOF
configure lldp tx-interval 1
configure lldp portidsubtype ifname
configure system hostname lldp-peer
configure system ip management pattern $HOST_IP
EOF
# -d: stays in the foreground (no daemon, no /run/lldpd.pid); -O: our configuration only.
lldpd -d -u "$LLDP_SOCK" -I "$TAP_L,$TAP_R" -O "$LLDP_DIR/lldpd.conf" >"$LLDP_DIR/lldpd.log" 2>&1 &
echo $! >"$LLDP_PID_FILE"
wait_for 10 lldpcli -u "$LLDP_SOCK" show chassis || { cat "$LLDP_DIR/lldpd.log" >&2; fail "lldpd did not start"; }
PEER_CHASSIS=$(kv local-chassis.chassis.mac "$(lldpcli_kv show chassis)")
[ -n "$PEER_CHASSIS" ] || fail "lldpd shows no chassis MAC: $(lldpcli_kv show chassis)"

# The card sent its first frames before lldpd ran: a link-up makes it send again within a second.
for port in L R; do
  "$CTL" "$CARD_CONTROL" "link $port down" >/dev/null || fail "link $port down"
  "$CTL" "$CARD_CONTROL" "link $port up" >/dev/null || fail "link $port up"
done

# --- (a) lldpd sees the card ------------------------------------------------------------------------
neighbour_complete() {
  local out
  out=$(lldpcli_kv show neighbors ports "$1") || return 1
  [ "$(kv "lldp.$1.chassis.mac" "$out")" = "$CARD_MAC" ] && [ -n "$(kv "lldp.$1.chassis.mgmt-ip" "$out")" ]
}
for tap in "$TAP_L" "$TAP_R"; do
  wait_for 10 neighbour_complete "$tap" || fail "lldpd does not see the card on $tap: $(lldpcli_kv show neighbors)"
done
check_neighbour() {  # TAP PORT_ID LETTER
  local out
  out=$(lldpcli_kv show neighbors ports "$1")
  [ "$(grep -c "^lldp\.$1\.chassis\.mac=" <<<"$out")" = 1 ] || fail "$1: not exactly one neighbour: $out"
  [ "$(kv "lldp.$1.chassis.mac" "$out")" = "$CARD_MAC" ] || fail "$1: chassis $(kv "lldp.$1.chassis.mac" "$out")"
  [ "$(kv "lldp.$1.port.local" "$out")" = "$2" ] || fail "$1: port id: $out"
  [ "$(kv "lldp.$1.port.ttl" "$out")" = 120 ] || fail "$1: ttl $(kv "lldp.$1.port.ttl" "$out")"
  [ "$(kv "lldp.$1.port.descr" "$out")" = "port $3" ] || fail "$1: port description: $out"
  [ "$(kv "lldp.$1.chassis.name" "$out")" = "$NAME" ] || fail "$1: system name $(kv "lldp.$1.chassis.name" "$out")"
  [ "$(kv "lldp.$1.chassis.descr" "$out")" = "$DESCRIPTION" ] || fail "$1: description $(kv "lldp.$1.chassis.descr" "$out")"
  [ "$(kv "lldp.$1.chassis.mgmt-ip" "$out")" = "$CARD_IP" ] || fail "$1: management address: $out"
  [ "$(kv "lldp.$1.chassis.Bridge.enabled" "$out")" = on ] || fail "$1: capabilities: $out"
}
check_neighbour "$TAP_L" 1 L
check_neighbour "$TAP_R" 2 R
pass "lldpd sees the card on both ports: chassis $CARD_MAC, port 1/2, TTL 120, name $NAME, mgmt $CARD_IP"

# --- (b) the card sees lldpd ------------------------------------------------------------------------
stats_line() { "$CTL" "$CARD_CONTROL" stats | grep "^lldp\.$1\.0 "; }
expected() { echo "lldp.$1.0 chassis=$PEER_CHASSIS port=$2 ttl=4 name=lldp-peer mgmt=$HOST_IP"; }
wait_for 5 bash -c "\"$CTL\" \"$CARD_CONTROL\" stats | grep -qx '$(expected L "$TAP_L")'" ||
  fail "card stats, port L: '$(stats_line L)', want '$(expected L "$TAP_L")'"
wait_for 5 bash -c "\"$CTL\" \"$CARD_CONTROL\" stats | grep -qx '$(expected R "$TAP_R")'" ||
  fail "card stats, port R: '$(stats_line R)', want '$(expected R "$TAP_R")'"
[ "$(stat_of lldp.neighbours)" = 2 ] || fail "lldp.neighbours $(stat_of lldp.neighbours), want 2"
[ "$(stat_of lldp.malformed)" = 0 ] && [ "$(stat_of lldp.table_full)" = 0 ] || fail "lldp counters: $("$CTL" "$CARD_CONTROL" stats | grep '^lldp\.')"
[ "$(stat_of lldp.frames_out)" -ge 4 ] || fail "lldp.frames_out $(stat_of lldp.frames_out)"
pass "the card sees lldpd: $(stats_line L)"

# The web page's statistics (GET /api/statistics after a login with the default read password).
JAR="$LLDP_DIR/cookies"
curl -s --max-time 5 -c "$JAR" -b "$JAR" -H 'Content-Type: application/json' -d '{"password":"USER"}' \
  "http://$CARD_IP/api/login" >/dev/null || fail "web login"
curl -s --max-time 5 -b "$JAR" "http://$CARD_IP/api/statistics" >"$LLDP_DIR/statistics.json" || fail "GET /api/statistics"
/usr/bin/python3 - "$LLDP_DIR/statistics.json" "$PEER_CHASSIS" "$HOST_IP" "$TAP_L" "$TAP_R" <<'EOF' || fail "web statistics"
import json, sys
path, chassis, mgmt, tap_l, tap_r = sys.argv[1:]
lldp = json.load(open(path))["lldp"]
got = sorted((n["port"], n["chassis"], n["port_id"], n["name"], n["mgmt"], n["ttl"]) for n in lldp["neighbours"])
want = [("L", chassis, tap_l, "lldp-peer", mgmt, 4), ("R", chassis, tap_r, "lldp-peer", mgmt, 4)]
assert got == want, f"{got} != {want}"
assert lldp["malformed"] == 0 and lldp["frames_in"] >= 2, lldp
print(f"ok: web statistics: {got}")
EOF

# --- (c) no LLDP through the card's switch: lldpd hears the card only -----------------------------
others=$(lldpcli_kv show neighbors | grep '\.chassis\.mac=' | grep -vc "=$CARD_MAC$" || true)
[ "$others" = 0 ] || fail "lldpd hears another chassis through the card: $(lldpcli_kv show neighbors | grep chassis.mac)"
pass "the card's switch forwards no LLDP frame"

# --- (d) lldpd's shutdown LLDPDU removes it from the card's table ---------------------------------
stop_lldpd
wait_for 3 stat_is lldp.neighbours 0 || fail "lldpd still in the card's table: $("$CTL" "$CARD_CONTROL" stats | grep '^lldp\.')"
[ "$(stat_of lldp.aged_out)" = 0 ] || fail "removed by ageing, not by lldpd's TTL 0: lldp.aged_out $(stat_of lldp.aged_out)"
pass "lldpd's shutdown LLDPDU removed it from the card's table"

# --- (e) tshark over the card's capture -------------------------------------------------------------
sleep 0.3
card_frames=$(tshark -r "$CARD_PCAP" -Y "lldp && eth.src == $CARD_MAC" 2>/dev/null | wc -l)
[ "$card_frames" -ge 4 ] || fail "only $card_frames LLDP frames from the card in the capture"
named=$(tshark -r "$CARD_PCAP" -Y "lldp && eth.src == $CARD_MAC && lldp.tlv.system.name == \"$NAME\" && lldp.time_to_live == 120" 2>/dev/null | wc -l)
[ "$named" -ge 2 ] || fail "tshark does not read system name $NAME and TTL 120 in the card's frames"
malformed=$(tshark -r "$CARD_PCAP" -Y "lldp && (_ws.malformed || _ws.expert.severity == error)" 2>/dev/null | wc -l)
[ "$malformed" -eq 0 ] || { tshark -r "$CARD_PCAP" -Y "lldp && (_ws.malformed || _ws.expert.severity == error)" -V | head -80; fail "$malformed malformed LLDP frames"; }
pass "tshark: $card_frames LLDP frames from the card, none malformed"
pass "net_lldp"
