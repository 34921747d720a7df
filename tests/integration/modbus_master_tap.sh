#!/usr/bin/env bash
# IO scanning only from the master c600-c603 (seed 000 §9, MB-4), over TAP in a namespace (tools/netns).
# The card is started with c604 = 1 and master 10.232.0.1 (the kernel side of tapL); a second address
# 10.232.0.3 on the same TAP is another host. The master's FC 23 drives FA06/FA07; the other host's FC 23
# is refused with exception 01 and its drive-register read still works (unit 0 is not IO scanning).
source "$(dirname "$0")/lib.sh"

ip addr add "${HOST_IP%.*}.3/24" dev "$TAP_L"
wait_for 10 bash -c "/usr/bin/python3 -c 'import socket; socket.create_connection((\"$CARD_IP\", 502), 1)'" \
  || fail "Modbus port not open"

CARD_IP=$CARD_IP HOST_IP=$HOST_IP OTHER_IP=${HOST_IP%.*}.3 /usr/bin/python3 - <<'PY' || fail "master filtering"
import os, sys
from pymodbus.client import ModbusTcpClient
from pymodbus.pdu import ExceptionResponse
card = os.environ["CARD_IP"]
words = [0, 0xC400, 6000, 0, 0, 0, 0]
master = ModbusTcpClient(card, port=502, timeout=3, source_address=(os.environ["HOST_IP"], 0))
other = ModbusTcpClient(card, port=502, timeout=3, source_address=(os.environ["OTHER_IP"], 0))
assert master.connect() and other.connect()
r = master.readwrite_registers(read_address=0, read_count=7, write_address=0, write_registers=words, unit=255)
if isinstance(r, ExceptionResponse):
    sys.exit(f"master refused: {r}")
print("ok: the master's FC 23 is served")
r = other.readwrite_registers(read_address=0, read_count=7, write_address=0, write_registers=words, unit=255)
if not isinstance(r, ExceptionResponse) or r.exception_code != 1:
    sys.exit(f"other host: expected exception 01, got {r}")
print("ok: another host's FC 23 gets exception 01")
r = other.read_holding_registers(0x0009, 1, slave=0)
if isinstance(r, ExceptionResponse):
    sys.exit(f"other host's drive read refused: {r}")
print("ok: another host still reads drive registers")
PY
answer=$("$CTL" "$CARD_CONTROL" status)
grep -q '"fa06":"0xC400"' <<<"$answer" || fail "FA06 not written by the master: $answer"
pass "IO scanning only from the master; FA06 = 0xC400 in the inverter"
