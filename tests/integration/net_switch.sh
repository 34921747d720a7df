#!/usr/bin/env bash
# The two-port switch and the daisy chain (docs/network.md "The two-port switch", issue 7). tools/netns
# --ports 2 gives the card tapL and tapR; this script moves tapR into a second namespace with its own
# host (SUBNET.3), so the two hosts are on either side of the card, as a PLC and a second drive on a
# daisy chain:
#   (a) the hosts reach each other through the card (ping, a TCP stream both ways), while each also
#       reaches the card itself (ping, Modbus); the card's switch counters show frames forwarded both ways;
#   (b) frames between the two hosts are not handed to the card's IP stack (its netif rx count grows by
#       far less than the bulk stream);
#   (c) port R unplugged (control socket): the far host is cut off, the near one still served; plugged
#       again: the chain works again; c502/c503 show each port's rate (3 = 100M full, 0 = unplugged).
source "$(dirname "$0")/lib.sh"

PEER_NS="${NETNS}-r"
FAR_IP="$SUBNET.3"
cleanup() { ip netns del "$PEER_NS" 2>/dev/null || true; }
trap cleanup EXIT

ip netns add "$PEER_NS"
ip link set "$TAP_R" netns "$PEER_NS"
ip -n "$PEER_NS" link set lo up
ip -n "$PEER_NS" addr add "$FAR_IP/24" dev "$TAP_R"
ip -n "$PEER_NS" link set "$TAP_R" up
far() { ip netns exec "$PEER_NS" "$@"; }
get_param() { "$CTL" "$CARD_CONTROL" "get $1" | sed -n "s/^$1 = \([0-9]*\).*/\1/p"; }

# --- (a) the chain and the card from both sides ---------------------------------------------------
wait_for 10 ping -c 1 -W 1 "$FAR_IP" || fail "the near host cannot reach the far host through the card"
far ping -c 3 -i 0.2 -W 1 "$HOST_IP" >/dev/null || fail "the far host cannot reach the near host"
ping -c 2 -i 0.2 -W 1 "$CARD_IP" >/dev/null || fail "the near host cannot reach the card"
far ping -c 2 -i 0.2 -W 1 "$CARD_IP" >/dev/null || fail "the far host cannot reach the card"
far mbpoll -m tcp -a 1 -0 -r $((0x0009)) -t 4 -1 "$CARD_IP" >/dev/null || fail "Modbus from the far host"
mbpoll -m tcp -a 1 -0 -r $((0x0009)) -t 4 -1 "$CARD_IP" >/dev/null || fail "Modbus from the near host"
pass "daisy chain: both hosts reach each other and the card (ping, Modbus)"

rx_before=$(stat_of netif.rx_frames)
# A TCP stream of 2 MB far -> near and 2 MB near -> far, through the card's switch.
/usr/bin/python3 - "$HOST_IP" "$FAR_IP" "$PEER_NS" <<'EOF' || fail "bulk transfer through the chain"
import os, socket, subprocess, sys, threading
near, far_ip, peer_ns = sys.argv[1], sys.argv[2], sys.argv[3]
SIZE = 2 * 1024 * 1024
listener = socket.socket()
listener.bind((near, 0))
listener.listen(1)
port = listener.getsockname()[1]
got = []
def serve():
    conn, _ = listener.accept()
    conn.settimeout(20)
    total = 0
    while total < SIZE:
        chunk = conn.recv(65536)
        if not chunk:
            break
        total += len(chunk)
    conn.sendall(b"x" * SIZE)
    conn.close()
    got.append(total)
t = threading.Thread(target=serve)
t.start()
client = ("import socket,sys;s=socket.create_connection(('%s',%d),timeout=20);s.sendall(b'y'*%d);n=0\n"
          "while n<%d:\n c=s.recv(65536)\n if not c: break\n n+=len(c)\nprint(n)") % (near, port, SIZE, SIZE)
out = subprocess.run(["ip", "netns", "exec", peer_ns, "/usr/bin/python3", "-c", client],
                     capture_output=True, text=True, timeout=30)
t.join(25)
assert got == [SIZE], f"near side received {got}"
assert out.stdout.strip() == str(SIZE), f"far side received {out.stdout!r} {out.stderr!r}"
print(f"ok: {SIZE} bytes each way through the card")
EOF
rx_after=$(stat_of netif.rx_frames)
forwarded_l=$(stat_of switch.L.forwarded)
forwarded_r=$(stat_of switch.R.forwarded)
[ "$forwarded_l" -gt 1000 ] && [ "$forwarded_r" -gt 1000 ] ||
  fail "switch counters: forwarded out of L $forwarded_l, out of R $forwarded_r"
# 4 MB in ~1448-byte segments is ~2900 data frames plus ACKs; the card's stack may see broadcasts and
# its own traffic, not the stream.
[ $((rx_after - rx_before)) -lt 200 ] || fail "the stream reached the card's IP stack: netif.rx_frames +$((rx_after - rx_before))"
pass "bulk stream forwarded (L $forwarded_l, R $forwarded_r frames), not given to lwIP (+$((rx_after - rx_before)) rx)"

[ "$(get_param c502)" = 3 ] && [ "$(get_param c503)" = 3 ] || fail "c502/c503: $(get_param c502)/$(get_param c503), want 3/3"

# --- (c) port R unplugged and plugged again --------------------------------------------------------
"$CTL" "$CARD_CONTROL" "link R down" >/dev/null || fail "link R down"
ping -c 1 -W 1 "$FAR_IP" >/dev/null 2>&1 && fail "the far host is reachable with port R unplugged"
ping -c 1 -W 1 "$CARD_IP" >/dev/null || fail "the card does not answer on port L with R unplugged"
wait_for 3 bash -c "[ \"\$(\"$CTL\" \"$CARD_CONTROL\" 'get c503' | sed -n 's/^c503 = \([0-9]*\).*/\1/p')\" = 0 ]" ||
  fail "c503 does not show port R unplugged: $(get_param c503)"
"$CTL" "$CARD_CONTROL" "link R up" >/dev/null || fail "link R up"
wait_for 5 ping -c 1 -W 1 "$FAR_IP" || fail "the chain does not come back with port R plugged"
far ping -c 1 -W 1 "$CARD_IP" >/dev/null || fail "the far host does not reach the card again"
pass "port R unplugged: far host cut off, card still served on L; plugged: chain back"
pass "net_switch"
