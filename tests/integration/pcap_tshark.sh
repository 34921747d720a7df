#!/usr/bin/env bash
# (d) The card's --pcap capture is read by tshark, holds our traffic, and has no malformed frame.
source "$(dirname "$0")/lib.sh"

ping -c 3 -i 0.2 -W 2 "$CARD_IP" >/dev/null || fail "no ping reply"
timeout 5 arping -c 1 -w 2 -I "$TAP_L" "$CARD_IP" >/dev/null 2>&1 || true
# A TCP SYN to a port nobody listens on yet: lwIP answers with RST, which goes into the capture too.
timeout 3 bash -c "exec 3<>/dev/tcp/$CARD_IP/44818" 2>/dev/null || true
sleep 0.5

frames=$(tshark -r "$CARD_PCAP" 2>/dev/null | wc -l)
[ "$frames" -ge 8 ] || fail "only $frames frames captured"
replies=$(tshark -r "$CARD_PCAP" -Y "icmp.type == 0 && ip.src == $CARD_IP" 2>/dev/null | wc -l)
[ "$replies" -eq 3 ] || fail "expected 3 echo replies in the capture, found $replies"
arp=$(tshark -r "$CARD_PCAP" -Y "arp.opcode == 2 && arp.src.proto_ipv4 == $CARD_IP" 2>/dev/null | wc -l)
[ "$arp" -ge 1 ] || fail "no ARP reply from the card in the capture"
rst=$(tshark -r "$CARD_PCAP" -Y "tcp.flags.reset == 1 && ip.src == $CARD_IP && tcp.srcport == 44818" 2>/dev/null | wc -l)
[ "$rst" -ge 1 ] || fail "no TCP RST from the card in the capture"
malformed=$(tshark -r "$CARD_PCAP" -Y "_ws.malformed || _ws.expert.severity == error" 2>/dev/null | wc -l)
[ "$malformed" -eq 0 ] || { tshark -r "$CARD_PCAP" -Y "_ws.malformed || _ws.expert.severity == error"; fail "$malformed malformed frames"; }
pass "$frames frames, 3 echo replies, ARP reply, RST; no malformed frame"
