#!/usr/bin/env bash
# The simulated inverter through the control socket (docs/simulator.md "In ipe002z-host"): get/set by
# title and number, terminals, trips, injected faults and status; power-cycle keeps the EEPROM in the
# state dir and clears the RAM-only registers; --param presets a new state dir only.
source "$(dirname "$0")/lib.sh"

host_addr=127.0.0.25

# ctl CMD: one command; its answer lines (without the final "ok") on stdout; fails on "error ...".
ctl() {
  local out
  out=$("$CTL" "$CARD_CONTROL" "$1") || fail "'$1' answered: $out"
  sed '$d' <<<"$out"
}
# ctl_error CMD: the one line a refused command answers.
ctl_error() {
  local out
  if out=$("$CTL" "$CARD_CONTROL" "$1"); then fail "'$1' was accepted: $out"; fi
  printf '%s\n' "$out"
}
expect() { [ "$2" = "$3" ] || fail "$1: got '$2', expected '$3'"; }
ready_lines() { test "$(grep -c '^ready ' "$CARD_LOG")" -ge "$1"; }

start_loopback_card "$host_addr"
expect "get acc (factory default 10.0 s)" "$(ctl 'get acc')" "acc = 100 (0x0064)"
expect "set acc 50" "$(ctl 'set acc 50')" "acc = 50 (0x0032)"
expect "get acc" "$(ctl 'get acc')" "acc = 50 (0x0032)"
expect "get 0009" "$(ctl 'get 0009')" "acc = 50 (0x0032)"
expect "set 000A 1" "$(ctl_error 'set 000A 1')" \
  "error no communication number 000A (numbers ending in A-F do not exist)"
expect "set acc 70000" "$(ctl_error 'set acc 70000')" "error acc: 70000 out of range 1..60000"
expect "set fd00 1" "$(ctl_error 'set fd00 1')" "error fd00 is read-only (monitor)"
expect "get nosuch" "$(ctl_error 'get nosuch')" "error unknown register 'nosuch'"
pass "get/set by title and number, with the model's refusals"

expect "set fa06" "$(ctl 'set fa06 0x8000')" "fa06 = 32768 (0x8000)"
ctl 'terminal ST on' >/dev/null
expect "terminal X" "$(ctl_error 'terminal X on')" "error unknown terminal 'X' (F R RES S1 S2 S3 VIB VIA ST)"
ctl 'trip err8' >/dev/null
status=$(ctl status)
grep -q '"state":"tripped"' <<<"$status" || fail "status after trip err8: $status"
grep -q '"trip":27,' <<<"$status" || fail "status does not show trip code 27: $status"
grep -q '"fa06":"0x8000"' <<<"$status" || fail "status does not show FA06: $status"
grep -q '"model":"vf-mb1"' <<<"$status" || fail "status does not show the model: $status"
pass "terminal, trip err8, status: $status"

ctl 'inject drop 1' >/dev/null
ctl 'inject delay until-cleared 150' >/dev/null
ctl 'inject clear' >/dev/null
expect "inject bogus" "$(ctl_error 'inject bogus')" \
  "error usage: inject drop|delay|corrupt|silent [COUNT|until-cleared] [DELAY-MS], inject clear"
pass "inject"

"$CTL" "$CARD_CONTROL" power-cycle >/dev/null || fail "power-cycle refused"
wait_for 10 ready_lines 2 || { cat "$CARD_LOG" >&2; fail "no second ready line after power-cycle"; }
image=$(cat "$WORK/state/inverter/vf-mb1.eeprom")
grep -q '^reg 0009 50 1$' <<<"$image" || fail "the state dir does not keep acc = 50 (1 write)"
grep -q '^trip-history 27 0 0 0$' <<<"$image" || fail "the state dir does not keep the trip history"
expect "get acc after power-cycle" "$(ctl 'get acc')" "acc = 50 (0x0032)"
expect "get fa06 after power-cycle" "$(ctl 'get fa06')" "fa06 = 0 (0x0000)"
status=$(ctl status)
grep -q '"trip":0,' <<<"$status" || fail "the power cycle did not clear err8: $status"
pass "power-cycle: acc = 50 kept in the state dir, RAM-only FA06 = 0, err8 cleared"
stop_card

# A new state dir takes the presets; once its file exists they are ignored (the restart passes the
# same --param again).
start_loopback_card "$host_addr" --param acc=30 --param 0010=40 --model vf-s15
expect "preset acc" "$(ctl 'get acc')" "acc = 30 (0x001E)"
expect "preset dec" "$(ctl 'get dec')" "dec = 40 (0x0028)"
[ -f "$WORK/state/inverter/vf-s15.eeprom" ] || fail "no vf-s15.eeprom in the state dir"
ctl 'set acc 45' >/dev/null
"$CTL" "$CARD_CONTROL" power-cycle >/dev/null || fail "power-cycle refused"
wait_for 10 ready_lines 2 || { cat "$CARD_LOG" >&2; fail "no second ready line after power-cycle"; }
expect "acc after restart with the same --param" "$(ctl 'get acc')" "acc = 45 (0x002D)"
pass "--param presets a new state dir only"
