#!/usr/bin/env bash
# The Modbus TCP server over the loopback port with real clients: python3-pymodbus (drive registers,
# exceptions, FC 43, IO scanning, every c101 loss action with its timing), mbpoll, and a libmodbus C
# client (libmodbus's own exception checks). docs/modbus.md describes what is checked.
source "$(dirname "$0")/lib.sh"

start_loopback_card 127.0.0.27 --param c604=1 --param c523=5 --param c100=3
endpoint=$(ready_field modbus)
host=${endpoint%:*}
port=${endpoint##*:}

MODBUS_HOST=$host MODBUS_PORT=$port CARD_CONTROL=$CARD_CONTROL /usr/bin/python3 "$(dirname "$0")/modbus_pymodbus.py"

# mbpoll: read acc/dec (0-based references), write acc, read it back through the inverter.
out=$(mbpoll -m tcp -p "$port" -a 1 -0 -r 9 -c 2 -t 4 -1 "$host" 2>&1) || fail "mbpoll read: $out"
grep -q '^\[9\]:' <<<"$out" && grep -q '^\[10\]:' <<<"$out" || fail "mbpoll read: $out"
out=$(mbpoll -m tcp -p "$port" -a 1 -0 -r 9 -t 4 -1 "$host" 123 2>&1) || fail "mbpoll write: $out"
answer=$("$CTL" "$CARD_CONTROL" "get acc")
grep -q '^acc = 123 ' <<<"$answer" || fail "acc after mbpoll write: $answer"
pass "mbpoll reads and writes drive registers"

if [ -n "${MODBUS_CLIENT:-}" ]; then
  "$MODBUS_CLIENT" "$host" "$port" || fail "libmodbus client"
  pass "libmodbus client"
fi
