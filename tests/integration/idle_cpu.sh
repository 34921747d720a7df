#!/usr/bin/env bash
# (e) An idle card sleeps: over 5 s without network traffic it uses little CPU and the event loop wakes
# only for timers and the drive link (the cyclic exchange with the inverter runs all the time, as on a
# real card: a request and its reply wake the loop a few times per transaction).
source "$(dirname "$0")/lib.sh"

start_loopback_card 127.0.0.22
sleep 1
ticks() { awk '{print $14 + $15}' "/proc/$CARD_PID/stat"; }
t0=$(ticks); p0=$(stat_of loop.passes); f0=$(stat_of drive.frames_sent)
sleep 5
t1=$(ticks); p1=$(stat_of loop.passes); f1=$(stat_of drive.frames_sent)
hz=$(getconf CLK_TCK)
cpu_ms=$(( (t1 - t0) * 1000 / hz ))
passes=$(( p1 - p0 ))
frames=$(( f1 - f0 ))
echo "idle 5 s: cpu ${cpu_ms} ms, ${passes} loop passes, ${frames} drive-link requests"
[ "$frames" -ge 100 ] || fail "only $frames drive-link requests in 5 s: the cyclic exchange is not running"
# lwIP's cyclic timers (ARP 1 s, IGMP 100 ms, reassembly 1 s) and libslirp's 1 s poll wake the loop a
# few dozen times a second at most; a busy loop would make hundreds of thousands of passes.
# Per request: the write, the reply bytes (possibly in two reads), the simulated inverter's timers.
limit=$(( 500 + 5 * frames ))
[ "$passes" -le "$limit" ] || fail "$passes passes in 5 s (limit $limit): the loop does not sleep"
[ "$cpu_ms" -le 250 ] || fail "${cpu_ms} ms of CPU in 5 s idle (limit 5 %)"
pass "idle card sleeps"
