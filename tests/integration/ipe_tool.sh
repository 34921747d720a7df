#!/usr/bin/env bash
# tools/ipe against the host card on the loopback port (docs/commissioning.md "Tests"): every subcommand,
# its exact output and exit code, and its effect checked in the simulated inverter (card-ctl).
#   card A (127.0.0.51, EtherNet/IP: c500=1, c101=1 so that the owner's Forward_Close leaves the drive as
#     it is, acc/dec 1 s): discover, identity (status 0x0034: bit 2 configured, c101 is not the factory 4), get, set (+ refusals: range, read-only, unknown, the card's
#     own), watch (--count and SIGINT), io (runs to 30 Hz, stops, Forward_Close), eds, backup of a
#     changed drive;
#   card B (127.0.0.52, a fresh state dir, factory c500=0: Modbus TCP): restore --dry-run and restore
#     over Modbus, the values checked in its inverter, the other model's file refused, --modbus get/set;
#   unreachable hosts: exit 3.
source "$(dirname "$0")/lib.sh"

IPE=${IPE:-$ROOT/tools/ipe}
KEEP=$(mktemp -d /tmp/ipe-tool-it.XXXXXX)
cleanup() { stop_card; rm -rf "$KEEP"; }

# run_ipe EXPECTED_EXIT ARGS...: runs the tool (bounded), output in $KEEP/out and $KEEP/err.
run_ipe() {
  local expected=$1; shift
  local rc=0
  timeout 60 "$IPE" "$@" >"$KEEP/out" 2>"$KEEP/err" || rc=$?
  if [ "$rc" != "$expected" ]; then
    echo "--- stdout" >&2; cat "$KEEP/out" >&2; echo "--- stderr" >&2; cat "$KEEP/err" >&2
    # What the card saw (once, 'no reply within 2000 ms' on a set after the EDS upload, not reproduced).
    echo "--- card stats" >&2; "$CTL" "$CARD_CONTROL" stats 2>&1 | grep -E 'tcp|eip\.|loop\.' >&2 || true
    fail "ipe $* exited $rc, expected $expected"
  fi
}
expect_out() { [ "$(cat "$KEEP/out")" = "$1" ] || fail "stdout was:
$(cat "$KEEP/out")
expected:
$1"; }
expect_err() { [ "$(cat "$KEEP/err")" = "$1" ] || fail "stderr was:
$(cat "$KEEP/err")
expected:
$1"; }
eeprom_writes() { "$CTL" "$CARD_CONTROL" status | sed -n 's/.*"eeprom_writes":\([0-9]*\).*/\1/p'; }
status_field() { "$CTL" "$CARD_CONTROL" status | sed -n "s/.*\"$1\":\"\{0,1\}\([^,\"}]*\).*/\1/p"; }

# ---- card A: EtherNet/IP ----------------------------------------------------------------------------
A=127.0.0.51
start_loopback_card "$A" --param c500=1 --param c101=1 --param acc=10 --param dec=10
trap cleanup EXIT
mac=$(ready_field mac)
serial=0x$(tr -d : <<<"$mac" | cut -c5-12 | tr a-f A-F)

run_ipe 0 discover --broadcast "$A" --timeout 2500
expect_out "$A card_ip=10.0.2.15 vendor=377 product_code=32000 product_name=\"VF-MB1\" serial=$serial revision=1.8 status=0x0034"
pass "discover: ListIdentity finds the card with its identity"

run_ipe 0 identity "$A"
expect_out "vendor_id = 377
device_type = 2
product_code = 32000 (VF-MB1)
revision = 1.8
status = 0x0034
serial_number = $serial
product_name = VF-MB1"
pass "identity: every Identity attribute"

run_ipe 0 get "$A" acc dec
expect_out "acc = 1.0 s
dec = 1.0 s"
pass "get acc dec over EtherNet/IP"

run_ipe 0 set "$A" acc=5.0 fh=60Hz
expect_out "acc = 5.0 s
fh = 60.00 Hz"
param_is acc 50 || fail "the inverter's acc is not 50 after set acc=5.0"
param_is fh 6000 || fail "the inverter's fh is not 6000 after set fh=60Hz"
pass "set acc=5.0 fh=60Hz reaches the inverter (50, 6000)"

writes=$(eeprom_writes)
run_ipe 2 set "$A" dec=2 acc=6000.1
expect_err "ipe: acc = 6000.1 s is outside 0.1 .. 6000.0 s on VF-MB1"
run_ipe 2 set "$A" acc=0.05
expect_err "ipe: acc: '0.05' has more decimals than acc takes (steps of 0.1 s)"
run_ipe 2 set "$A" fd00=1
expect_err "ipe: fd00 is read-only (Output frequency)"
run_ipe 2 get "$A" acc nosuch
expect_err "ipe: unknown parameter 'nosuch' (a panel title such as acc, dec, fh, c101, fd00)"
[ -z "$(cat "$KEEP/out")" ] || fail "get with an unknown name printed values"
param_is acc 50 && param_is dec 10 || fail "a refused set changed the inverter"
[ "$(eeprom_writes)" = "$writes" ] || fail "a refused set wrote the EEPROM ($writes -> $(eeprom_writes))"
pass "out of range, too many decimals, read-only, unknown name: exit 2, nothing written (dec not either)"

run_ipe 1 set "$A" fa23=1
expect_err "ipe: set fa23 = 0x0001: refused by the card: general status 0x09 (invalid attribute value)"
pass "the card's refusal is printed with its CIP status and the parameter's name (exit 1)"

run_ipe 0 watch "$A" fd00 fd01 --count 3 --interval 100ms
[ "$(wc -l <"$KEEP/out")" = 3 ] || fail "watch --count 3 printed $(wc -l <"$KEEP/out") lines"
grep -qvE '^fd00 = 0\.00 Hz  fd01 = 0x[0-9A-F]{4}$' "$KEEP/out" && fail "watch line format: $(cat "$KEEP/out")"
timeout 20 "$IPE" watch "$A" fd00 --interval 100ms >"$KEEP/watch" 2>&1 &
watch_pid=$!
wait_for 10 test -s "$KEEP/watch" || fail "watch printed nothing"
kill -INT "$watch_pid"
rc=0; wait "$watch_pid" || rc=$?
[ "$rc" = 0 ] || fail "watch ended with $rc on SIGINT, expected 0"
pass "watch: 3 lines with --count 3; SIGINT ends it with exit 0"

# io: 21/71 at 10 ms, Run Fwd + NetCtrl/NetRef at 30 Hz; the inverter reaches 30 Hz; at the end the tool
# sends a stop, then Forward_Close; with c101 = 1 the close itself changes nothing, so the drive is
# stopped by the tool and not tripped.
timeout 30 "$IPE" io "$A" --connection 21/71 --rpi 10ms --run --speed 30Hz --duration 6 >"$KEEP/io" 2>"$KEEP/io.err" &
io_pid=$!
wait_for 8 bash -c "[ \"\$(\"$CTL\" \"$CARD_CONTROL\" status | sed -n 's/.*\"output_hz\":\([0-9.]*\).*/\1/p')\" = 30.00 ]" \
  || fail "the drive did not reach 30 Hz under ipe io: $("$CTL" "$CARD_CONTROL" status)"
rc=0; wait "$io_pid" || rc=$?
[ "$rc" = 0 ] || { cat "$KEEP/io.err" >&2; fail "ipe io exited $rc"; }
grep -q 'running-fwd ready ctrl-from-net ref-from-net at-reference state=4 (enabled) speed=900 rpm (30.00 Hz)' "$KEEP/io" \
  || fail "io never showed the drive at 30 Hz: $(tail -3 "$KEEP/io")"
[ "$(tail -1 "$KEEP/io")" = "ready ctrl-from-net ref-from-net stopped state=3 (ready) speed=0 rpm (0.00 Hz)" ] \
  || fail "io's last line is not a stopped drive: $(tail -1 "$KEEP/io")"
[ "$(tail -1 "$KEEP/io.err")" = "io: connection closed (Forward_Close)" ] || fail "io did not close: $(cat "$KEEP/io.err")"
[ "$(status_field output_hz)" = 0.00 ] && [ "$(status_field trip)" = 0 ] && [ "$(status_field state)" = stopped ] \
  || fail "after io the drive is not stopped and healthy: $("$CTL" "$CARD_CONTROL" status)"
pass "io: the drive ran to 30 Hz (900 rpm) and was stopped before Forward_Close (stopped, no trip)"

# eds: the upload through the File object is the EDS the build wrote for this model, byte for byte.
built_eds="$EDS_DIR/IPE002Z_VF-MB1.eds"
[ -s "$built_eds" ] || fail "no built EDS at $built_eds"
run_ipe 0 eds "$A" "$KEEP/card.eds"
expect_err "eds: $(stat -c %s "$built_eds") bytes saved to $KEEP/card.eds (checksum ok)"
cmp "$built_eds" "$KEEP/card.eds" || fail "the uploaded EDS differs from the built $built_eds"
pass "eds: the File object upload equals the built VF-MB1 EDS ($(stat -c %s "$built_eds") bytes)"

# A changed drive, backed up.
run_ipe 0 set "$A" dec=3.0 c101=2
run_ipe 0 backup "$A" "$KEEP/drive.bak"
[ "$(tail -1 "$KEEP/err")" = "backup: 140 parameters of the VF-MB1 at $A saved to $KEEP/drive.bak" ] || fail "backup: $(cat "$KEEP/err")"
grep -qx "backup: 140/140 c604" "$KEEP/err" || fail "backup: no final progress line"
sed -n 2,4p "$KEEP/drive.bak" >"$KEEP/head"
[ "$(cat "$KEEP/head")" = "# model: VF-MB1
# product: VF-MB1
# card: $A" ] || fail "backup header: $(cat "$KEEP/head")"
grep -qx 'acc = 5.0 s  # 0009 Acceleration time 1 (unit per f519)' "$KEEP/drive.bak" || fail "backup has no acc line"
grep -qx 'dec = 3.0 s  # 0010 Deceleration time 1 (unit per f519)' "$KEEP/drive.bak" || fail "backup has no dec line"
[ "$(grep -vc '^#' "$KEEP/drive.bak")" = 140 ] || fail "backup holds $(grep -vc '^#' "$KEEP/drive.bak") values, not 140"
pass "backup: 140 settings with header and progress"

# A running drive is not restored (docs/commissioning.md "Restore decisions"): nothing is written.
run_ipe 0 set "$A" acc=7
timeout 30 "$IPE" io "$A" --run --speed 10Hz >"$KEEP/io2" 2>&1 &
io_pid=$!
wait_for 8 bash -c "\"$CTL\" \"$CARD_CONTROL\" status | grep -q '\"state\":\"running\"'" || fail "io did not run the drive"
writes=$(eeprom_writes)
run_ipe 1 restore "$A" "$KEEP/drive.bak"
[ "$(tail -1 "$KEEP/err")" = "ipe: restore: the drive is running (fd01 bit 10): stop it first; nothing written" ] \
  || fail "restore on a running drive: $(cat "$KEEP/err")"
[ "$(cat "$KEEP/out")" = "acc: 7.0 s -> 5.0 s" ] || fail "restore on a running drive: diff $(cat "$KEEP/out")"
param_is acc 70 && [ "$(eeprom_writes)" = "$writes" ] || fail "restore wrote to a running drive"
pass "restore on a running drive: exit 1, the diff shown, nothing written"
# Ctrl-C ends io: a stop, then Forward_Close, exit 0, the drive stopped and not tripped.
kill -INT "$io_pid"
rc=0; wait "$io_pid" || rc=$?
[ "$rc" = 0 ] || { cat "$KEEP/io2" >&2; fail "ipe io ended with $rc on SIGINT"; }
[ "$(tail -1 "$KEEP/io2")" = "io: connection closed (Forward_Close)" ] || fail "io after SIGINT: $(tail -3 "$KEEP/io2")"
[ "$(status_field output_hz)" = 0.00 ] && [ "$(status_field trip)" = 0 ] && [ "$(status_field state)" = stopped ] \
  || fail "after io's SIGINT the drive is not stopped and healthy: $("$CTL" "$CARD_CONTROL" status)"
pass "io on SIGINT: stop, Forward_Close, exit 0, the drive stopped"
stop_card

# ---- card B: fresh, Modbus TCP (factory c500 = 0) ----------------------------------------------------
B=127.0.0.52
start_loopback_card "$B"
trap cleanup EXIT
mb_port=$(ready_field modbus | cut -d: -f2)
writes=$(eeprom_writes)
run_ipe 0 restore "$B" "$KEEP/drive.bak" --modbus --port "$mb_port" --dry-run
expect_out "acc: 10.0 s -> 5.0 s
dec: 10.0 s -> 3.0 s
fh: 80.00 Hz -> 60.00 Hz
c101: 4 -> 2
c500: 0 -> 1"
[ "$(tail -1 "$KEEP/err")" = "restore: 5 differences, nothing written (--dry-run)" ] || fail "dry run: $(cat "$KEEP/err")"
[ "$(eeprom_writes)" = "$writes" ] && param_is acc 100 || fail "--dry-run wrote to the inverter"
pass "restore --dry-run: the exact diff, nothing written"

sed 's/^# model: VF-MB1$/# model: VF-S15/' "$KEEP/drive.bak" >"$KEEP/s15.bak"
run_ipe 2 restore "$B" "$KEEP/s15.bak" --modbus --port "$mb_port"
expect_err "ipe: restore: $KEEP/s15.bak is a backup of a VF-S15; the card at $B drives a VF-MB1: nothing written"
[ "$(eeprom_writes)" = "$writes" ] || fail "the other model's file wrote to the inverter"
pass "restore of a VF-S15 file onto a VF-MB1: exit 2, nothing written"

run_ipe 0 restore "$B" "$KEEP/drive.bak" --modbus --port "$mb_port"
grep -qx "restore: 5 written, 0 refused" "$KEEP/err" || fail "restore: $(cat "$KEEP/err")"
grep -q "restore: c500 act only after a reset" "$KEEP/err" || fail "restore did not name c500 as acting after a reset"
param_is acc 50 && param_is dec 30 && param_is fh 6000 && param_is c101 2 && param_is c500 1 \
  || fail "the fresh inverter does not hold the restored values"
run_ipe 0 restore "$B" "$KEEP/drive.bak" --modbus --port "$mb_port"
[ -z "$(cat "$KEEP/out")" ] || fail "a second restore found differences: $(cat "$KEEP/out")"
pass "restore onto a fresh drive: acc 50, dec 30, fh 6000, c101 2, c500 1 in its inverter; again: no difference"

run_ipe 0 get "$B" acc dec --modbus --port "$mb_port"
expect_out "acc = 5.0 s
dec = 3.0 s"
run_ipe 0 set "$B" dec=4.5 --modbus --port "$mb_port"
param_is dec 45 || fail "set dec=4.5 over Modbus did not reach the inverter"
run_ipe 1 set "$B" fa23=1 --modbus --port "$mb_port"
expect_err "ipe: set fa23 = 0x0001: refused by the card: Modbus exception 03 (illegal data value)"
pass "--modbus get/set, and the card's exception by name"

# ---- help and the wrapper ------------------------------------------------------------------------------
run_ipe 0 restore --help
[ "$(head -1 "$KEEP/out")" = "usage: ipe restore HOST FILE [--dry-run] [--modbus [--unit ID]] [--port N] [--timeout MS]" ] \
  || fail "restore --help: $(head -1 "$KEEP/out")"
run_ipe 2 restore "$B"
[ "$(head -1 "$KEEP/err")" = "ipe: wrong number of arguments for 'restore'" ] || fail "usage error: $(cat "$KEEP/err")"
IPE="$ROOT/tools/ipe" run_ipe 0 --help
[ "$(head -1 "$KEEP/out")" = "usage: ipe [--port N] [--timeout MS] COMMAND ARGS..." ] || fail "tools/ipe --help: $(cat "$KEEP/out")"
pass "--help for the tool (through the tools/ipe wrapper) and a command; a usage error exits 2"

# ---- unreachable ---------------------------------------------------------------------------------------
run_ipe 3 get 127.0.0.53 acc --timeout 1000
expect_err "ipe: 127.0.0.53:44818: Connection refused (is the card on EtherNet/IP, c500 = 1? --modbus reaches a Modbus card)"
run_ipe 3 discover --broadcast 127.0.0.53 --timeout 500
expect_err "ipe: discover: no card answered within 500 ms"
pass "unreachable host and no answer: exit 3"
