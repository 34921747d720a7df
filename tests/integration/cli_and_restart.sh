#!/usr/bin/env bash
# The command line: --help, bad flags (usage on stderr, exit 2); power-cycle restarts the card with its
# state dir (same MAC) and prints a new ready line.
source "$(dirname "$0")/lib.sh"

usage=$("$FIRMWARE" --help) || fail "--help exited non-zero"
grep -q -- "--net loopback | tap:IF" <<<"$usage" || fail "--help does not print the usage"
for bad in "--bogus" "--net eth0" "--ip 10.0.0.1" "--ip 300.1.1.1/24" "--model vf-x" \
           "--param c500" "--param =1" "--param c500=abc" "--host-addr 10.0.0.1" "--state-dir"; do
  set +e
  # shellcheck disable=SC2086
  "$FIRMWARE" $bad >/dev/null 2>"/tmp/ipe-cli.$$"
  rc=$?
  set -e
  [ "$rc" = 2 ] || fail "'$bad' exited $rc, expected 2"
  grep -q "^usage: $(basename "$FIRMWARE")" "/tmp/ipe-cli.$$" || fail "'$bad' printed no usage on stderr"
done
rm -f "/tmp/ipe-cli.$$"
pass "bad flags: usage on stderr, exit 2"

start_loopback_card 127.0.0.23 --param c500=1 --model vf-s15
mac=$(ready_field mac)
"$CTL" "$CARD_CONTROL" power-cycle >/dev/null || fail "power-cycle refused"
ready_lines() { test "$(grep -c '^ready ' "$CARD_LOG")" -ge 2; }
wait_for 10 ready_lines || { cat "$CARD_LOG"; fail "no second ready line after power-cycle"; }
second=$(grep '^ready ' "$CARD_LOG" | sed -n 2p)
grep -q " mac=$mac " <<<"$second" || fail "MAC changed across the restart: $second"
kill -0 "$CARD_PID" || fail "the card process did not survive its restart"
[ "$(stat_of netif.link)" = up ] || fail "control socket dead after restart"
out=$("$CTL" "$CARD_CONTROL" "frobnicate" || true)
[ "$out" = "error unknown command (try 'help')" ] || fail "unknown command answer: '$out'"
pass "power-cycle: same process id, same MAC $mac, control socket back"
