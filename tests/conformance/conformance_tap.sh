#!/usr/bin/env bash
# The negative conformance suite over TAP (tools/netns, with --pcap): conformance.py PROTOCOL from a second
# host address NEG_IP (SUBNET.3; the health checks and the Modbus master use HOST_IP), then:
#   - the card process is still alive;
#   - tshark: no frame the card sent is malformed or carries an expert warning or error (our requests are
#     wrong on purpose and may be flagged: they are only counted; the TCP resets of connections the card
#     refuses or drops are expected and left out).
# usage (inside tools/netns): conformance_tap.sh modbus|eip
source "$(dirname "$0")/../integration/lib.sh"

protocol=${1:?usage: conformance_tap.sh modbus|eip}
HERE=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$HERE:$HERE/../integration${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export NEG_IP="${HOST_IP%.*}.3"
export CARD_IP HOST_IP CARD_PID CARD_CONTROL
case "$protocol" in
  modbus) port=502 ;;
  eip) port=44818 ;;
  *) fail "unknown protocol $protocol" ;;
esac

ip addr add "$NEG_IP/24" dev "$TAP_L"
wait_for 10 /usr/bin/python3 -c "import socket; socket.create_connection(('$CARD_IP', $port), 1).close()" \
  || fail "port $port not open"

started=$SECONDS
status=0
timeout 90 /usr/bin/python3 "$HERE/conformance.py" "$protocol" || status=$?
echo "   (suite: $((SECONDS - started)) s)"
kill -0 "$CARD_PID" 2>/dev/null || fail "the card process is gone"
[ "$status" = 0 ] || fail "conformance suite ($protocol): exit status $status"

sleep 0.3  # the last frames reach the capture file
pcap="$CARD_STATE_DIR/../conformance-$protocol.pcap"
cp "$CARD_PCAP" "$pcap"
count() { tshark -r "$pcap" -Y "$1" 2>/dev/null | wc -l; }
bad="_ws.malformed || _ws.expert.severity >= warning"
card="ip.src == $CARD_IP && !tcp.connection.rst && ($bad)"
# The CIP dissector shows a reply's [Request Path], taken from our request, inside the reply; its verdict on
# a path we made unsupported on purpose (a reserved logical format, a reserved segment type) is about our
# request, not about the card's frame. Those two messages alone do not count; any other message does.
request_path_only="^(Unsupported Logical Segment Format|Unsupported Segment Type)$"
malformed=$(count "ip.src == $CARD_IP && _ws.malformed")
flagged_by_us=$(tshark -r "$pcap" -Y "$card" -T fields -e _ws.expert.message -E aggregator=$'\n' 2>/dev/null |
                grep -v '^$' | grep -Ec "$request_path_only" || true)
others=$(tshark -r "$pcap" -Y "$card" -T fields -e _ws.expert.message -E aggregator=$'\n' 2>/dev/null |
         grep -v '^$' | grep -Evc "$request_path_only" || true)
n=$((malformed + others))
if [ "$n" -ne 0 ]; then
  tshark -r "$pcap" -Y "$card" 2>/dev/null | head -20
  tshark -r "$pcap" -Y "$card" -V 2>/dev/null | grep -E "^Frame |Expert Info|Malformed" | head -40
  fail "$n frames sent by the card are malformed or carry expert warnings"
fi
if [ "$protocol" = modbus ]; then dissected=$(count "ip.src == $CARD_IP && mbtcp"); else dissected=$(count "ip.src == $CARD_IP && enip"); fi
[ "$dissected" -ge 100 ] || fail "only $dissected $protocol frames from the card in the capture"
flagged=$(count "ip.src == $NEG_IP && ($bad)")
pass "capture: $dissected $protocol frames from the card, none malformed or flagged ($flagged of our deliberately wrong requests flagged; $flagged_by_us replies annotated for the request path they echo)"
