#!/usr/bin/env bash
# (c) The card on the loopback port (libslirp) as an unprivileged user: the forwards are bound on the
# chosen loopback address (with fallbacks below 1024), and a TCP connection to a forwarded port reaches
# lwIP inside the card.
source "$(dirname "$0")/lib.sh"

if [ "$(id -u)" = 0 ]; then RUN_AS=nobody; fi
host_addr=127.0.0.21
start_loopback_card "$host_addr"

if [ -n "${RUN_AS:-}" ]; then
  uid=$(awk '/^Uid:/ {print $2}' "/proc/$CARD_PID/status")
  [ "$uid" = "$(id -u nobody)" ] || fail "card runs as uid $uid, not nobody"
  pass "card runs as nobody"
fi

# Which Modbus/HTTP ports an unprivileged process may bind depends on the kernel setting.
low=$(cat /proc/sys/net/ipv4/ip_unprivileged_port_start)
exp_mb=5020; exp_http=8080
[ "$low" -le 502 ] && exp_mb=502
[ "$low" -le 80 ] && exp_http=80
[ "$(ready_field modbus)" = "$host_addr:$exp_mb" ] || fail "modbus endpoint $(ready_field modbus), expected $host_addr:$exp_mb"
[ "$(ready_field http)" = "$host_addr:$exp_http" ] || fail "http endpoint $(ready_field http), expected $host_addr:$exp_http"
[ "$(ready_field enip)" = "$host_addr:44818" ] || fail "enip endpoint $(ready_field enip)"
[ "$(ready_field enip-udp)" = "$host_addr:44818" ] || fail "enip-udp endpoint $(ready_field enip-udp)"
[ "$(ready_field io)" = "$host_addr:2222" ] || fail "io endpoint $(ready_field io)"
[ "$(ready_field ip)" = 10.0.2.15 ] || fail "card address $(ready_field ip)"
pass "ready line: $CARD_READY"

# A scanner on the same host can bind its own UDP 2222 (on 127.0.0.1) while the card holds its forward.
/usr/bin/python3 - <<PY || fail "scanner could not bind 127.0.0.1:2222 beside the card"
import socket
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(("127.0.0.1", 2222))
PY
pass "a scanner binds 127.0.0.1:2222 beside the card's $host_addr:2222"

before=$(stat_of lwip.tcp.recv)
# Nothing serves TCP 44818 inside the card yet, so lwIP answers the SYN with a reset, which libslirp
# turns into a closed connection on the host side.
/usr/bin/python3 - "$host_addr" <<'PY' || fail "TCP connection through the forward did not reach the card"
import socket, sys
s = socket.create_connection((sys.argv[1], 44818), timeout=5)
s.settimeout(5)
try:
    data = s.recv(16)
except ConnectionResetError:
    data = b""
sys.exit(0 if data == b"" else 1)
PY
after=$(stat_of lwip.tcp.recv)
[ "$after" -gt "$before" ] || fail "lwIP saw no TCP segment (tcp.recv $before -> $after)"
pass "forwarded TCP reached lwIP (tcp.recv $before -> $after) and was closed by the card"
