#!/usr/bin/env bash
# QoS object 0x48 end to end over TAP in a namespace (tools/netns, --pcap): the DSCP of class 1 productions
# and explicit replies with the default values, exact codes for bad values, new values in force after an
# Identity Reset, 802.1Q priority tags; tshark reads the card's capture. The checks are qos_dscp.py's.
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CARD_IP CARD_MAC CARD_LOG CARD_PCAP
timeout 180 /usr/bin/python3 "$IT/qos_dscp.py" || fail "qos_dscp.py"
pass "QoS object: DSCP per traffic class, bad values, apply at reset, 802.1Q tags"
