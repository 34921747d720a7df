#!/usr/bin/env bash
# (e) An idle card sleeps: over 5 s it uses almost no CPU and the event loop wakes only for timers.
source "$(dirname "$0")/lib.sh"

start_loopback_card 127.0.0.22
sleep 1
ticks() { awk '{print $14 + $15}' "/proc/$CARD_PID/stat"; }
t0=$(ticks); p0=$(stat_of loop.passes)
sleep 5
t1=$(ticks); p1=$(stat_of loop.passes)
hz=$(getconf CLK_TCK)
cpu_ms=$(( (t1 - t0) * 1000 / hz ))
passes=$(( p1 - p0 ))
echo "idle 5 s: cpu ${cpu_ms} ms, ${passes} loop passes"
# lwIP's cyclic timers (ARP 1 s, IGMP 100 ms, reassembly 1 s) and libslirp's 1 s poll wake the loop a
# few dozen times a second at most; a busy loop would make hundreds of thousands of passes.
[ "$passes" -le 500 ] || fail "$passes passes in 5 s: the loop does not sleep"
[ "$cpu_ms" -le 100 ] || fail "${cpu_ms} ms of CPU in 5 s idle"
pass "idle card sleeps"
