# Shared helpers of the integration tests (sourced). Every wait here is bounded.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
FIRMWARE=${FIRMWARE:-$ROOT/build/host/bin/ipe002z-host}
CTL="$ROOT/tools/card-ctl"

fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok: $*"; }

# stat_of NAME: one counter from the card's 'stats' answer.
stat_of() {
  local answer
  answer=$("$CTL" "$CARD_CONTROL" stats) || return 1
  sed -n "s/^$1=//p" <<<"$answer"
}

# stat_is NAME VALUE: the counter NAME of 'stats' is VALUE now (for wait_for, which re-runs it).
stat_is() { [ "$(stat_of "$1")" = "$2" ]; }

# param_is NAME VALUE: the simulated inverter's parameter NAME (e.g. c536) reads VALUE now.
param_is() { [ "$("$CTL" "$CARD_CONTROL" "get $1" | sed -n "s/^$1 = \([0-9]*\).*/\1/p")" = "$2" ]; }

# wait_for SECONDS COMMAND...: retry COMMAND every 0.1 s until it succeeds or time runs out.
wait_for() {
  local limit=$(( $1 * 10 )); shift
  for _ in $(seq "$limit"); do
    if "$@" >/dev/null 2>&1; then return 0; fi
    sleep 0.1
  done
  return 1
}

# start_loopback_card HOST_ADDR [extra firmware args...]: runs the card on the loopback port in the
# background (as the current user, or as RUN_AS when set and root), sets CARD_PID, CARD_CONTROL,
# CARD_LOG, CARD_READY, WORK. stop_card is installed as the EXIT trap.
start_loopback_card() {
  local host_addr=$1; shift
  WORK=$(mktemp -d /tmp/ipe-it.XXXXXX)
  chmod 777 "$WORK"
  CARD_CONTROL="$WORK/control.sock"
  CARD_LOG="$WORK/card.log"
  local prefix=() firmware=$FIRMWARE
  if [ -n "${RUN_AS:-}" ]; then
    prefix=(setpriv --reuid="$RUN_AS" --regid="$(id -g "$RUN_AS")" --clear-groups)
    # The build tree may sit where that user cannot reach (e.g. under /root): run a copy.
    if ! "${prefix[@]}" test -x "$firmware"; then cp "$firmware" "$WORK/"; firmware="$WORK/$(basename "$firmware")"; fi
  fi
  "${prefix[@]}" "$firmware" --net loopback --host-addr "$host_addr" --sim-control "$CARD_CONTROL" \
    --state-dir "$WORK/state" "$@" >"$CARD_LOG" 2>&1 &
  CARD_PID=$!
  trap stop_card EXIT
  wait_for 30 grep -q '^ready ' "$CARD_LOG" || { cat "$CARD_LOG" >&2; fail "card did not become ready"; }
  CARD_READY=$(grep -m1 '^ready ' "$CARD_LOG")
}

stop_card() {
  if [ -n "${CARD_PID:-}" ] && kill -0 "$CARD_PID" 2>/dev/null; then
    kill -TERM "$CARD_PID" 2>/dev/null || true
    wait_for 5 bash -c "! kill -0 $CARD_PID" || kill -KILL "$CARD_PID" 2>/dev/null || true
  fi
  [ -n "${WORK:-}" ] && rm -rf "$WORK"
  return 0
}

# ready_field NAME: a field of the ready line (e.g. ready_field modbus -> 127.0.0.2:5020).
ready_field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$CARD_READY"; }
