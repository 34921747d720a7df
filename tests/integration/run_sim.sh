#!/usr/bin/env bash
# tools/run-sim starts the card without root and prints its ready line; as root the test runs it as
# 'nobody' against the existing (read-only for nobody) build tree.
source "$(dirname "$0")/lib.sh"

WORK=$(mktemp -d /tmp/ipe-runsim.XXXXXX)
chmod 777 "$WORK"
CARD_LOG="$WORK/run-sim.log"
prefix=()
if [ "$(id -u)" = 0 ] && setpriv --reuid=nobody --regid=nogroup --clear-groups test -x "$ROOT/tools/run-sim" \
   && setpriv --reuid=nobody --regid=nogroup --clear-groups test -x "$FIRMWARE"; then
  prefix=(setpriv --reuid=nobody --regid=nogroup --clear-groups env HOME="$WORK" XDG_RUNTIME_DIR="$WORK")
else
  prefix=(env HOME="$WORK" XDG_RUNTIME_DIR="$WORK")
fi
"${prefix[@]}" "$ROOT/tools/run-sim" --host-addr 127.0.0.24 >"$CARD_LOG" 2>&1 &
CARD_PID=$!
trap 'kill -TERM $CARD_PID 2>/dev/null; wait $CARD_PID 2>/dev/null; rm -rf "$WORK"' EXIT
wait_for 60 grep -q '^ready ' "$CARD_LOG" || { cat "$CARD_LOG" >&2; fail "run-sim printed no ready line"; }
CARD_READY=$(grep -m1 '^ready ' "$CARD_LOG")
[ "$(ready_field enip)" = 127.0.0.24:44818 ] || fail "unexpected endpoints: $CARD_READY"
[ "$(ready_field state)" = "$WORK/.local/state/ipe002z" ] || fail "run-sim did not use its persistent state dir: $CARD_READY"
CARD_CONTROL=$(ready_field control)
[ "$(stat_of netif.link)" = up ] || fail "control socket of run-sim's card does not answer"
pass "run-sim (${prefix[0]}) ready: $CARD_READY"
