#!/usr/bin/env bash
# ipe002z-inverter, the simulated inverter as its own process (docs/simulator.md "ipe002z-inverter"):
# the Toshiba protocol on a UNIX socket with the manuals' exact frames and replies, the control socket
# (set/get, trip, stats), one client at a time and a new client after the last one left, the EEPROM kept
# across a restart (SIGTERM stores it; P writes are lost), --ip keyed in at every start, TCP, --help and
# the exit codes of bad command lines. Everything stays on loopback and in a temporary directory.
source "$(dirname "$0")/lib.sh"

INVERTER=${INVERTER:-$ROOT/build/host/bin/ipe002z-inverter}
LINE="$ROOT/tests/integration/toshiba_line.py"
WORK=$(mktemp -d /tmp/ipe-inverter.XXXXXX)
SERIAL="$WORK/serial.sock"
CONTROL="$WORK/control.sock"
STATE="$WORK/state"
INV_PID=

cleanup() {
  if [ -n "$INV_PID" ] && kill -0 "$INV_PID" 2>/dev/null; then
    kill -TERM "$INV_PID" 2>/dev/null || true
    wait_for 5 bash -c "! kill -0 $INV_PID" || kill -KILL "$INV_PID" 2>/dev/null || true
  fi
  rm -rf "$WORK"
}
trap cleanup EXIT

expect() { [ "$2" = "$3" ] || fail "$1: got '$2', expected '$3'"; }
# ctl CMD: one control command; its answer lines without the final "ok"; fails on "error ...".
ctl() {
  local out
  out=$("$CTL" "$CONTROL" "$1") || fail "'$1' answered: $out"
  sed '$d' <<<"$out"
}
state_is() { ctl status | grep -q "\"state\":\"$1\""; }
# frames FRAME...: the replies, one line each ("-" for none), on one connection to the serial line.
frames() { "$LINE" "unix:$SERIAL" "$@" || fail "cannot talk on the serial line"; }

# start [FLAGS...]: runs the inverter in the background until its ready line, then waits out the
# power-on second (the drive does not communicate before it).
start() {
  # Emptied here, not by the background command's redirection: that runs in the child, which may not
  # have opened the file yet when the wait below reads the previous run's ready line from it.
  : >"$WORK/out"
  "$INVERTER" --serial "unix:$SERIAL" --sim-control "$CONTROL" --state-dir "$STATE" "$@" \
    >"$WORK/out" 2>"$WORK/err" &
  INV_PID=$!
  wait_for 10 grep -q '^inverter-ready ' "$WORK/out" || { cat "$WORK/err" >&2; fail "no ready line"; }
  wait_for 5 state_is stopped || fail "the inverter did not leave its power-on reset: $(ctl status)"
}
# stop: SIGTERM, which must end the process with status 0 after it stored its EEPROM.
stop() {
  kill -TERM "$INV_PID"
  local rc=0
  wait "$INV_PID" || rc=$?
  INV_PID=
  expect "exit status after SIGTERM" "$rc" 0
}

# --- Command line ---
"$INVERTER" --help >"$WORK/help" || fail "--help did not exit 0"
expect "--help" "$(head -1 "$WORK/help")" "usage: ipe002z-inverter --serial unix:PATH|tcp:HOST:PORT [options]"
grep -q -- '--sim-processing-ms N' "$WORK/help" || fail "--help does not list the inverter flags"
bad_flag() {  # bad_flag EXPECTED-FIRST-LINE ARGS...: exit status 2 and the reason on stderr
  local expected=$1 rc=0; shift
  "$INVERTER" "$@" >/dev/null 2>"$WORK/bad" || rc=$?
  expect "exit status of '$*'" "$rc" 2
  expect "message of '$*'" "$(head -1 "$WORK/bad")" "$expected"
}
bad_flag "ipe002z-inverter: missing --serial (unix:PATH or tcp:HOST:PORT)"
bad_flag "ipe002z-inverter: unknown option --bogus" --serial "unix:$SERIAL" --bogus 1
bad_flag "ipe002z-inverter: invalid value for --serial: 'serial.sock' (expected unix:PATH or tcp:HOST:PORT, HOST a numeric address or localhost)" \
  --serial serial.sock
bad_flag "ipe002z-inverter: invalid value for --param: 'acc=0' (out of range 1..60000)" \
  --serial "unix:$SERIAL" --param acc=0
bad_flag "ipe002z-inverter: invalid value for --ip: '10.0.2.15'" --serial "unix:$SERIAL" --ip 10.0.2.15
[ ! -e "$SERIAL" ] || fail "a refused command line created the socket"
pass "--help (exit 0), bad flags exit 2 with the reason"

# --- A new inverter: presets, --ip, the ready line ---
start --param acc=30 --ip 192.168.1.20/24,192.168.1.1
expect "ready line" "$(cat "$WORK/out")" \
  "inverter-ready serial=unix:$SERIAL control=$CONTROL model=vf-mb1 state=$STATE"
expect "get acc (preset)" "$(ctl 'get acc')" "acc = 30 (0x001E)"
expect "get c504" "$(ctl 'get c504')" "c504 = 0 (0x0000)"
expect "get c505" "$(ctl 'get c505')" "c505 = 192 (0x00C0)"
expect "get c508" "$(ctl 'get c508')" "c508 = 20 (0x0014)"
expect "get c512" "$(ctl 'get c512')" "c512 = 0 (0x0000)"
expect "get c516" "$(ctl 'get c516')" "c516 = 1 (0x0001)"
pass "ready: presets and the --ip address keyed in (c504 = 0, c505-c516)"

# --- The Toshiba protocol, exact bytes (seed 003 and seed 000 worked examples) ---
replies=$(frames "2F 52 FD 01 7F" "2F 52 00 09 8A" "ascii:(R0011&62)" "ascii:(W00111770&36)" "ascii:(R0011&62)" \
  "2F 57 00 10 00 64 FA" "2F 50 00 10 00 C8 57" "2F 52 00 10 91" "2F 52 00 01 82" "2F 52 FD 01 7E" "2F 4C 00 00 7B")
expect "replies" "$replies" "2F 52 FD 01 48 00 C7
2F 52 00 09 00 1E A8
28 52 30 30 31 31 31 46 34 30 26 33 44 29 0D
28 57 30 30 31 31 31 37 37 30 26 33 36 29 0D
28 52 30 30 31 31 31 37 37 30 26 33 31 29 0D
2F 57 00 10 00 64 FA
2F 50 00 10 00 C8 57
2F 52 00 10 00 C8 59
2F 4E 00 02 7F
2F 4E 00 04 81
-"
pass "R FD01 = 4800h, R acc, sample program 2 (fh 80 -> 60 Hz), W/P dec, errors 0002 and 0004, silence"

# --- The control socket on a running line ---
expect "set acc 45" "$(ctl 'set acc 45')" "acc = 45 (0x002D)"
expect "R acc after set" "$(frames "2F 52 00 09 8A")" "2F 52 00 09 00 2D B7"
expect "get dec (the P write)" "$(ctl 'get dec')" "dec = 200 (0x00C8)"
ctl 'trip err8' >/dev/null
grep -q '"trip":27,' <<<"$(ctl status)" || fail "status does not show err8: $(ctl status)"
expect "R FC90 while tripped (lowercase reply)" "$(frames "2F 52 FC 90 0D")" "2F 72 FC 90 00 1B 48"
ctl 'set c505 10' >/dev/null  # --ip keys it back at the next start
pass "set/get between frames, trip err8 seen on the line as a lowercase reply"

# --- One client at a time; a new client once the last one left (QEMU restarted) ---
python3 - "$SERIAL" <<'EOF' || fail "one client at a time"
import socket, sys
path = sys.argv[1]
def connect():
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(3)
    s.connect(path)
    return s
def exchange(s):
    s.sendall(bytes.fromhex("2F52FC900D"))
    reply = b""
    while len(reply) < 7:
        chunk = s.recv(16)
        if not chunk:
            break
        reply += chunk
    return reply.hex(" ").upper()
first = connect()
second = connect()
assert second.recv(1) == b"", "a second client was not refused"
assert exchange(first) == "2F 72 FC 90 00 1B 48", "the first client lost the line"
first.close()
third = connect()
assert exchange(third) == "2F 72 FC 90 00 1B 48", "a new client after the first left is not served"
third.close()
EOF
stats=$(ctl stats)
grep -qx 'serial.refused=1' <<<"$stats" || fail "stats: $stats"
grep -qx 'server.errors=2' <<<"$stats" || fail "stats: $stats"
pass "a second client is refused while the first lives; the next one after it left is served"

# --- The same socket path cannot be taken from a live inverter ---
rc=0
"$INVERTER" --serial "unix:$SERIAL" --state-dir "$WORK/other" >/dev/null 2>"$WORK/second" || rc=$?
expect "exit status of a second inverter on the same path" "$rc" 1
expect "its message" "$(cat "$WORK/second")" \
  "ipe002z-inverter: serial endpoint $SERIAL: another process listens there"

# --- Restart: the EEPROM is kept (W writes and panel sets), RAM is not, the trip is gone ---
stop
image=$(cat "$STATE/inverter/vf-mb1.eeprom")
grep -q '^reg 0009 45 2$' <<<"$image" || fail "the stored image does not keep acc = 45 (2 writes)"
grep -q '^reg 0011 6000 1$' <<<"$image" || fail "the stored image does not keep fh = 60 Hz"
grep -q '^trip-history 27 0 0 0$' <<<"$image" || fail "the stored image does not keep the trip history"
[ ! -e "$SERIAL" ] && [ ! -e "$CONTROL" ] || fail "the sockets were not removed at exit"
start --param acc=30 --ip 192.168.1.20/24,192.168.1.1
expect "get acc after restart (preset ignored)" "$(ctl 'get acc')" "acc = 45 (0x002D)"
expect "get c505 after restart (--ip)" "$(ctl 'get c505')" "c505 = 192 (0x00C0)"
grep -q '"trip":0,' <<<"$(ctl status)" || fail "err8 survived the power cycle: $(ctl status)"
replies=$(frames "ascii:(R0011&62)" "2F 52 00 09 8A" "2F 52 00 10 91")
expect "replies after restart" "$replies" "28 52 30 30 31 31 31 37 37 30 26 33 31 29 0D
2F 52 00 09 00 2D B7
2F 52 00 10 00 64 F5"
pass "restart: fh = 60 Hz (W) and acc = 45 (set) kept, dec back to 10 s (the P write was RAM only), err8 cleared"

# --- power-cycle on the control socket: the inverter alone, the line stays ---
ctl 'set fa06 0x8000' >/dev/null
ctl power-cycle >/dev/null
expect "fa06 after power-cycle" "$(ctl 'get fa06')" "fa06 = 0 (0x0000)"
wait_for 5 state_is stopped || fail "no power-on reset end after power-cycle: $(ctl status)"
expect "R acc after power-cycle" "$(frames "2F 52 00 09 8A")" "2F 52 00 09 00 2D B7"
stop
pass "power-cycle: RAM-only FA06 back to 0, the EEPROM kept, the line served again"

# --- TCP ---
: >"$WORK/out"  # not the child's redirection: see start()
"$INVERTER" --serial tcp:127.0.0.1:0 --state-dir "$STATE" >"$WORK/out" 2>"$WORK/err" &
INV_PID=$!
wait_for 10 grep -q '^inverter-ready ' "$WORK/out" || { cat "$WORK/err" >&2; fail "no ready line (tcp)"; }
endpoint=$(sed -n 's/^inverter-ready serial=\([^ ]*\) .*/\1/p' "$WORK/out")
[[ $endpoint =~ ^tcp:127\.0\.0\.1:[0-9]+$ ]] && [ "$endpoint" != tcp:127.0.0.1:0 ] || fail "ready line: $(cat "$WORK/out")"
reply=-
for _ in 1 2 3 4 5 6 7 8 9 10; do  # no control socket here: retry until the power-on second is over
  reply=$("$LINE" "$endpoint" "2F 52 00 09 8A") || fail "cannot connect to $endpoint"
  [ "$reply" = - ] || break
  sleep 0.2
done
expect "R acc over TCP" "$reply" "2F 52 00 09 00 2D B7"
stop
pass "tcp: a port the kernel chose ($endpoint), the same inverter state"

# --- QEMU's UART as the client (when qemu-system-arm is installed): the chardev connects to the socket,
# and a restarted QEMU gets the line again. -S: the machine is built (its chardev connected) but no guest
# code runs, so no firmware image is needed here. ---
if ! command -v qemu-system-arm >/dev/null || ! qemu-system-arm -machine help | grep -q '^mps2-an386 '; then
  pass "qemu: qemu-system-arm with mps2-an386 not installed, QEMU part skipped"
  exit 0
fi
start
QEMU_PID=
run_qemu() {
  qemu-system-arm -machine mps2-an386 -display none -monitor none -S \
    -chardev "socket,id=inverter,path=$SERIAL" -serial chardev:inverter >"$WORK/qemu.log" 2>&1 &
  QEMU_PID=$!
}
stat_value() { ctl stats | sed -n "s/^$1=//p"; }
stat_equals() { [ "$(stat_value "$1")" = "$2" ]; }
trap 'kill -KILL $QEMU_PID 2>/dev/null || true; cleanup' EXIT
run_qemu
wait_for 10 stat_equals serial.connections 1 || { cat "$WORK/qemu.log" >&2; fail "QEMU's chardev did not connect"; }
stat_equals serial.connected 1 || fail "QEMU's connection is not the line's client"
kill -KILL "$QEMU_PID"  # as a crash would
wait "$QEMU_PID" 2>/dev/null || true
run_qemu
wait_for 10 stat_equals serial.connections 2 || { cat "$WORK/qemu.log" >&2; fail "a restarted QEMU did not get the line"; }
stat_equals serial.refused 0 || fail "the restarted QEMU was refused: $(ctl stats)"
stat_equals serial.disconnects 1 || fail "the killed QEMU's connection was not dropped: $(ctl stats)"
kill -TERM "$QEMU_PID"
wait "$QEMU_PID" 2>/dev/null || true
stop
pass "qemu: -chardev socket,path=... connects as the line's client; a QEMU killed and started again gets it back"
