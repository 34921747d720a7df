#!/usr/bin/env bash
# IO scanning only from the master c600-c603 (seed 000 §9, MB-4; docs/security.md "Modbus: the IO scanning
# master"), over TAP in a namespace (tools/netns). The card is started with c604 = 1 and master 10.232.0.1
# (the kernel side of tapL); a second address 10.232.0.3 on the same TAP is another host. The master's FC 23
# drives FA06/FA07; the other host's FC 23, 03, 06 and 16 on unit 255 are refused with exception 01, its
# writes to control registers through unit 0 (FA23, cmod, f899) with 02 and nothing changes in the
# inverter, while its drive-register read and a parameter write (acc) work. The master writes FA23 through
# unit 0, but not FA07 (its scanner's target, §9.1: 02).
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

def exception_of(r):
    return r.exception_code if isinstance(r, ExceptionResponse) else None

for what, r in (("FC 03", other.read_holding_registers(1, 2, slave=255)),
                ("FC 06", other.write_register(1, 0x0400, slave=255)),
                ("FC 16", other.write_registers(1, [0x0400, 6000], slave=255))):
    if exception_of(r) != 1:
        sys.exit(f"other host's {what} on unit 255: expected exception 01, got {r}")
print("ok: another host's FC 03, 06 and 16 on unit 255 get exception 01")
for number, name in ((0xFA23, "FA23"), (0x0003, "cmod"), (0x0899, "f899")):
    r = other.write_register(number, 0, slave=0)
    if exception_of(r) != 2:
        sys.exit(f"other host's write of {name} through unit 0: expected exception 02, got {r}")
r = other.write_registers(0xFA50, [1, 2], slave=1)
if exception_of(r) != 2:
    sys.exit(f"other host's FC 16 FA50-FA51 through unit 1: expected exception 02, got {r}")
print("ok: another host's writes of control registers (FA23, cmod, f899, FA50-FA51) get exception 02")
r = other.write_register(0x0009, 40, slave=0)
if isinstance(r, ExceptionResponse):
    sys.exit(f"other host's write of acc refused: {r}")
print("ok: another host still writes parameters (acc)")
r = master.write_register(0xFA23, 0x0080, slave=0)
if isinstance(r, ExceptionResponse):
    sys.exit(f"the master's write of FA23 through unit 0 refused: {r}")
r = master.write_register(0xFA07, 3000, slave=0)
if exception_of(r) != 2:
    sys.exit(f"the master's write of FA07 (its scanner's target) through unit 0: expected 02, got {r}")
print("ok: the master writes FA23 through unit 0; FA07 stays reserved for its scanner (02)")
PY
answer=$("$CTL" "$CARD_CONTROL" status)
grep -q '"fa06":"0xC400"' <<<"$answer" || fail "FA06 not written by the master: $answer"
[ "$("$CTL" "$CARD_CONTROL" "get fa23" | sed -n 's/^fa23[^=]*= \([0-9]*\).*/\1/p')" = 128 ] \
  || fail "FA23 is not the master's 0x0080: $("$CTL" "$CARD_CONTROL" "get fa23")"
[ "$("$CTL" "$CARD_CONTROL" "get cmod" | sed -n 's/^cmod[^=]*= \([0-9]*\).*/\1/p')" = 1 ] \
  || fail "cmod is not its factory 1 (written by the other host?): $("$CTL" "$CARD_CONTROL" "get cmod")"
[ "$("$CTL" "$CARD_CONTROL" "get acc" | sed -n 's/^acc[^=]*= \([0-9]*\).*/\1/p')" = 40 ] \
  || fail "acc is not the other host's 40: $("$CTL" "$CARD_CONTROL" "get acc")"
pass "IO scanning and control registers only from the master; FA06 = 0xC400, FA23 = 0x0080 in the inverter"
