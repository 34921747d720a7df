#!/usr/bin/env bash
# The card in a DLR ring with the scripted supervisor (net_dlr_ring.py says what is checked), then the
# card's own capture through tshark's DLR dissector: every ring frame the card sent or forwarded decodes,
# none is malformed. Run by tools/netns --ports 2 --pcap. With the argument `flood` (and without --pcap): the
# ring-frame flood alone, no capture check.
#
# The card runs with SCHED_FIFO and the supervisor with its checks one step below (as the hostile-peer
# and I/O tests do), the flood process at normal priority: the host is shared, and what is measured is
# the firmware's own scheduling and the beacon timing a Python supervisor can keep.
source "$(dirname "$0")/lib.sh"

export DLR_PHASE=${1:-ring}  # ring | flood

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
rt=()
if chrt -a -f -p 30 "$CARD_PID" 2>/dev/null; then
  rt=(chrt -f 20)
else
  echo "   (SCHED_FIFO not available: timing runs at normal priority)"
fi
"${rt[@]}" /usr/bin/python3 "$IT/net_dlr_ring.py" || fail "the ring test"
[ "$DLR_PHASE" = flood ] && exit 0

# The capture: the card's frames in and out, DLR among them.
sleep 0.5  # the card writes its capture as it goes
dlr_frames=$(tshark -r "$CARD_PCAP" -Y dlr 2>/dev/null | wc -l) || fail "tshark could not read $CARD_PCAP"
bad='_ws.malformed || (dlr && _ws.expert.severity == error)'
malformed=$(tshark -r "$CARD_PCAP" -Y "$bad" 2>/dev/null | wc -l)
kinds=$(tshark -r "$CARD_PCAP" -Y "dlr && eth.src == $CARD_MAC" -T fields -e enip.dlr.frametype 2>/dev/null |
  sort -u | tr '\n' ' ')
[ "$dlr_frames" -gt 1000 ] || fail "tshark found only $dlr_frames DLR frames in the card's capture"
[ "$malformed" = 0 ] || fail "tshark: $malformed malformed frames in the card's capture: $(tshark -r "$CARD_PCAP" -Y "$bad" 2>/dev/null | head -5)"
# Sent by the card itself: Neighbor_Check request 2 and response 3, Link/Neighbor_Status 4, Sign_On 7,
# Learning_Update 10.
[ "$kinds" = "0x02 0x03 0x04 0x07 0x0a " ] || fail "the card's own DLR frame types in the capture: '$kinds', want '0x02 0x03 0x04 0x07 0x0a '"
pass "tshark: $dlr_frames DLR frames in the card's capture, none malformed; the card's own: frame types $kinds"
