#!/usr/bin/env bash
# Class 1 I/O over TAP in a namespace (tools/netns) with an independent originator: st-ethernet-ip's I/O
# scanner (eip_scanner.js) owns the drive through assemblies 21/71 and then 100/150 at RPI 10 ms: connect,
# start forward at 60 Hz, stop, trip the simulated inverter, fault reset through the assembly,
# Forward_Close. Then tshark over the capture. docs/eip-tests.md "integration.eip_scanner" describes it.
#
# The card is started (integration.eip_scanner) with --pcap and the inverter presets c500=1 (EtherNet/IP),
# c101=1 (operation continues at a communication loss: the firmware counts the owner's Forward_Close as
# a loss, and with the factory c101=4 the inverter would trip err8, which only a power cycle clears),
# acc=20 and dec=20 (2.0 s ramps, so a ramp fits the test's time); f856 is the factory 2 (4-pole motor,
# 1800 rpm = 60 Hz).
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
RPI_MS=${EIP_SCANNER_RPI_MS:-10}

param() { "$CTL" "$CARD_CONTROL" "get $1" | sed -n "s/^$1 = \(-\{0,1\}[0-9]*\) .*/\1/p"; }
for expected in c500=1 c101=1 acc=20 dec=20 f856=2; do
  name=${expected%=*}
  got=$(param "$name")
  [ "$got" = "${expected#*=}" ] || fail "the card must be started with $expected (the inverter has $name = '$got')"
done
pass "inverter presets: c500=1, c101=1, acc=dec=2.0 s, f856=2"

command -v node >/dev/null || fail "node is not installed (tools/setup)"
[ -d "$ROOT/node_modules/st-ethernet-ip" ] || fail "st-ethernet-ip is not installed in $ROOT/node_modules (tools/setup)"
wait_for 10 timeout 1 bash -c "exec 3<>/dev/tcp/$CARD_IP/44818" || fail "EtherNet/IP port 44818 not open"
[ "$(stat_of io.open)" = 1 ] || fail "the card's UDP 2222 is not open (io.open = $(stat_of io.open))"

for profile in 21 100; do
  started=$SECONDS
  timeout 60 node "$IT/eip_scanner.js" "$CARD_IP" "$CARD_CONTROL" "$profile" "$RPI_MS" \
    || fail "st-ethernet-ip I/O scanner, assemblies $profile"
  echo "   ($((SECONDS - started)) s)"
done
[ "$(stat_of cip.connections)" = 0 ] || fail "connections left open: $(stat_of cip.connections)"
[ "$(stat_of cip.connection_timeouts)" = 0 ] || fail "connection timeouts: $(stat_of cip.connection_timeouts)"

# The capture: both Forward_Opens are in it, so Wireshark's CIP dissector follows the I/O on UDP 2222.
pcap="$CARD_STATE_DIR/../eip_scanner.pcap"
sleep 0.3  # the last frames reach the file
cp "$CARD_PCAP" "$pcap"
count() { tshark -r "$pcap" -Y "$1" 2>/dev/null | wc -l; }
show() { tshark -r "$pcap" -Y "$1" -V 2>/dev/null | grep -E "^Frame|Expert|Malformed|\[.*(Warning|Error)" | head -40; }
bad="_ws.malformed || _ws.expert.severity >= warning"
# Nothing malformed, no expert warning or error, in either direction.
n=$(count "($bad) && !tcp.connection.rst")
[ "$n" -eq 0 ] || { show "($bad) && !tcp.connection.rst"; fail "$n frames malformed or with expert warnings"; }
# Two Forward_Opens (0x54) answered with success, two Forward_Closes (0x4E) answered with success.
opens=$(count "ip.src == $HOST_IP && cip.service == 0x54")
opened=$(count "ip.src == $CARD_IP && cip.service == 0xd4 && cip.genstat == 0")
closes=$(count "ip.src == $HOST_IP && cip.service == 0x4e")
closed=$(count "ip.src == $CARD_IP && cip.service == 0xce && cip.genstat == 0")
[ "$opens" = 2 ] && [ "$opened" = 2 ] && [ "$closes" = 2 ] && [ "$closed" = 2 ] \
  || fail "Forward_Open $opens requests / $opened successes, Forward_Close $closes / $closed (expected 2 each)"
# Every UDP 2222 datagram is class 1 I/O of a connection the dissector knows from its Forward_Open
# (enip.fwd_open_in: the frame of that Forward_Open; cip.connection: the dissector's connection index).
io=$(count "udp.port == 2222")
linked="udp.port == 2222 && cipio && enip.fwd_open_in"
io_known=$(count "$linked")
from_card=$(count "$linked && ip.src == $CARD_IP && udp.srcport == 2222 && udp.dstport == 2222")
first=$(count "$linked && cip.connection == 0")
second=$(count "$linked && cip.connection == 1")
[ "$io" -ge 2000 ] || fail "only $io UDP 2222 frames in the capture"
[ "$io_known" = "$io" ] || { tshark -r "$pcap" -Y "udp.port == 2222 && !($linked)" 2>/dev/null | head -5
                             fail "$((io - io_known)) of $io UDP 2222 frames not dissected as CIP I/O of a Forward_Open"; }
[ "$from_card" -ge 1000 ] || fail "only $from_card T->O frames from the card"
[ "$first" -ge 1000 ] && [ "$second" -ge 1000 ] || fail "I/O frames per connection: $first and $second"
pass "capture: $io class 1 frames ($from_card from the card; $first on the 21/71 connection, $second on 100/150), all dissected as CIP I/O of their Forward_Open; nothing malformed, no expert warning"
pass "st-ethernet-ip I/O scanner: assemblies 21/71 and 100/150 at RPI $RPI_MS ms"
