#!/usr/bin/env bash
# The Modbus TCP server over TAP in a namespace (tools/netns; the card is started with
# --tcp-keepalive 1000,500,3 and --pcap). docs/modbus.md "Tests" describes what is checked:
#   (a) mbpoll reads and writes drive registers; the write is seen in the simulated inverter;
#   (b) the libmodbus C client (MODBUS_CLIENT, when libmodbus was found) passes;
#   (c) keepalive: a client on a second host address does one request, then the address is removed, so
#       the peer vanishes without FIN or RST. The card must probe it (3 keepalive probes in the capture),
#       drop the connection (RST) within idle + count x interval (+ lwIP's 500 ms timer, + margin), not
#       before, and free its slot (modbus.clients back); a fresh client is served afterwards.
source "$(dirname "$0")/lib.sh"

# The card's --tcp-keepalive (CMakeLists.txt passes it): in ms, ms, probes.
KEEP_IDLE_MS=1000
KEEP_INTERVAL_MS=500
KEEP_COUNT=3
OTHER_IP=${HOST_IP%.*}.3

clients_are() { [ "$(stat_of modbus.clients)" = "$1" ]; }

helper_pid=""
cleanup() {
  if [ -n "$helper_pid" ] && kill -0 "$helper_pid" 2>/dev/null; then kill "$helper_pid" 2>/dev/null || true; fi
  [ -n "${STATE:-}" ] && rm -f "$STATE"
  ip addr del "$OTHER_IP/24" dev "$TAP_L" 2>/dev/null || true  # the namespace goes anyway (tools/netns)
  return 0
}
trap cleanup EXIT

wait_for 10 bash -c "/usr/bin/python3 -c 'import socket; socket.create_connection((\"$CARD_IP\", 502), 1)'" \
  || fail "Modbus port not open"

# (a) mbpoll: read acc/dec (0-based references), write acc, read it back through the inverter.
out=$(timeout 10 mbpoll -m tcp -p 502 -a 1 -0 -r 9 -c 2 -t 4 -1 "$CARD_IP" 2>&1) || fail "mbpoll read: $out"
grep -q '^\[9\]:' <<<"$out" && grep -q '^\[10\]:' <<<"$out" || fail "mbpoll read: $out"
out=$(timeout 10 mbpoll -m tcp -p 502 -a 1 -0 -r 9 -t 4 -1 "$CARD_IP" 123 2>&1) || fail "mbpoll write: $out"
answer=$("$CTL" "$CARD_CONTROL" "get acc")
grep -q '^acc = 123 ' <<<"$answer" || fail "acc after mbpoll write: $answer"
out=$(timeout 10 mbpoll -m tcp -p 502 -a 1 -0 -r 9 -t 4 -1 "$CARD_IP" 2>&1) || fail "mbpoll read back: $out"
grep -q '^\[9\]:[[:space:]]*123$' <<<"$out" || fail "mbpoll read back: $out"
pass "mbpoll reads and writes drive registers over TAP (acc = 123 in the inverter)"

# (b) the libmodbus C client.
if [ -n "${MODBUS_CLIENT:-}" ]; then
  timeout 30 "$MODBUS_CLIENT" "$CARD_IP" 502 || fail "libmodbus client"
  pass "libmodbus client over TAP"
else
  echo "note: no libmodbus client (libmodbus not found at configure time)"
fi

# (c) keepalive expiry of a vanished peer.
wait_for 10 clients_are 0 || fail "clients of (a)/(b) still open: $(stat_of modbus.clients)"
idle_before=$(stat_of modbus.idle_closes)
lost_before=$(stat_of modbus.lost)
[ -n "$lost_before" ] || fail "the card's stats have no modbus.lost line"
ip addr add "$OTHER_IP/24" dev "$TAP_L"
STATE=$(mktemp /tmp/ipe-modbus-tap.XXXXXX)

# One FC 03 (acc, unit 1) from OTHER_IP on a raw socket, then hold the socket open without sending:
# the process is killed below.
/usr/bin/python3 - "$CARD_IP" "$OTHER_IP" "$STATE" <<'PY' &
import socket, struct, sys, time
card, source, state = sys.argv[1:4]
s = socket.create_connection((card, 502), timeout=5, source_address=(source, 0))
s.sendall(struct.pack(">HHHBBHH", 0x1234, 0, 6, 1, 0x03, 0x0009, 1))
answer = b""
while len(answer) < 11:
    chunk = s.recv(11 - len(answer))
    if not chunk:
        sys.exit("closed before the answer")
    answer += chunk
tid, protocol, length, unit, function, count, value = struct.unpack(">HHHBBBH", answer)
if (tid, protocol, length, unit, function, count) != (0x1234, 0, 5, 1, 0x03, 2):
    sys.exit(f"unexpected answer {answer.hex()}")
with open(state, "w") as f:
    f.write(f"served {value} {s.getsockname()[1]}\n")
time.sleep(60)
PY
helper_pid=$!
wait_for 10 grep -q '^served ' "$STATE" || fail "the client on $OTHER_IP was not served"
t_served=$(date +%s%N)
read -r _ value client_port <"$STATE"
[ "$value" = 123 ] || fail "acc read from $OTHER_IP: $value"
clients_are 1 || fail "clients while $OTHER_IP is connected: $(stat_of modbus.clients)"
# The peer vanishes: no FIN, no RST (the kernel can no longer send from that address, and drops what
# the card sends there).
ip addr del "$OTHER_IP/24" dev "$TAP_L"
t_deleted=$(date +%s%N)
(( (t_deleted - t_served) / 1000000 < KEEP_IDLE_MS - 200 )) \
  || fail "address removed only $(( (t_deleted - t_served) / 1000000 )) ms after the answer (a probe may have been answered)"

# Dropped after idle + count x interval from the last segment; lwIP checks every 500 ms.
expected_ms=$(( KEEP_IDLE_MS + KEEP_COUNT * KEEP_INTERVAL_MS ))
limit_ms=$(( expected_ms + 500 + 3000 ))
dropped=""
while (( ($(date +%s%N) - t_deleted) / 1000000 < limit_ms )); do
  if clients_are 0; then dropped=$(date +%s%N); break; fi
  sleep 0.05
done
[ -n "$dropped" ] || fail "connection from $OTHER_IP not dropped within $limit_ms ms (clients $(stat_of modbus.clients))"
elapsed_ms=$(( (dropped - t_served) / 1000000 ))
(( elapsed_ms >= expected_ms - 500 )) || fail "dropped after $elapsed_ms ms, before the keepalive could expire ($expected_ms ms)"
[ "$(stat_of modbus.idle_closes)" = "$idle_before" ] || fail "closed by the server's idle rule, not by keepalive"
lost_after=$(stat_of modbus.lost)
[ "$lost_after" = $(( lost_before + 1 )) ] || fail "modbus.lost $lost_before -> $lost_after, expected +1"
kill "$helper_pid" 2>/dev/null || true
wait "$helper_pid" 2>/dev/null || true
helper_pid=""

# The capture: the card probed the vanished peer KEEP_COUNT times, then reset the connection.
if [ -n "${CARD_PCAP:-}" ] && [ -s "$CARD_PCAP" ]; then
  conn="ip.src == $CARD_IP && ip.dst == $OTHER_IP && tcp.dstport == $client_port"
  probes=$(tshark -r "$CARD_PCAP" -Y "$conn && tcp.analysis.keep_alive" 2>/dev/null | wc -l)
  [ "$probes" = "$KEEP_COUNT" ] || { tshark -r "$CARD_PCAP" -Y "$conn" >&2; fail "$probes keepalive probes, expected $KEEP_COUNT"; }
  resets=$(tshark -r "$CARD_PCAP" -Y "$conn && tcp.flags.reset == 1" 2>/dev/null | wc -l)
  [ "$resets" -ge 1 ] || fail "no RST to the vanished peer in the capture"
  pass "capture: $probes keepalive probes to $OTHER_IP:$client_port, then RST"
fi
pass "vanished peer dropped by keepalive after $elapsed_ms ms (idle + count x interval = $expected_ms ms); its slot is free"

# A fresh client is served, and its slot is freed when it closes.
CARD_IP=$CARD_IP /usr/bin/python3 - <<'PY' || fail "fresh client after the keepalive drop"
import os, socket, struct, sys
s = socket.create_connection((os.environ["CARD_IP"], 502), timeout=5)
s.sendall(struct.pack(">HHHBBHH", 7, 0, 6, 1, 0x03, 0x0009, 1))
answer = b""
while len(answer) < 11:
    chunk = s.recv(11 - len(answer))
    if not chunk:
        sys.exit("closed before the answer")
    answer += chunk
if answer != struct.pack(">HHHBBBH", 7, 0, 5, 1, 0x03, 2, 123):
    sys.exit(f"unexpected answer {answer.hex()}")
s.close()
PY
wait_for 10 clients_are 0 || fail "fresh client's slot not freed: $(stat_of modbus.clients)"
pass "a fresh client is served after the drop"
