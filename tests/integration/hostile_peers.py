#!/usr/bin/python3
"""Hostile peers for the integration tests (docs/robustness.md "Hostile peers"). Standard library only.

  hostile_peers.py hostile CARD SECONDS SPEC...   slow and stuck clients for SECONDS, then exit
  hostile_peers.py healthy CARD PROTOCOL N P99_MS [LABEL]
                                                  N round trips of one healthy client; prints the percentiles,
                                                  exits 1 when p99 >= P99_MS or a reply is wrong
  hostile_peers.py flood CARD SECONDS IFACE       broadcast ListIdentity (UDP 44818) and ARP requests on
                                                  IFACE for SECONDS, as fast as one process can send

SPEC is PROTOCOL:SLOW:STUCK (e.g. modbus:4:3): SLOW clients send a valid request one byte per second, over
and over; STUCK clients send requests without ever reading (small receive buffer) until their send buffer
is full, then keep offering one more request a second. PROTOCOL is modbus (502), eip (44818) or http (80).

Every loop is bounded in time; only the card's address (a namespace the test made) is contacted.
"""
import os
import random
import select
import socket
import struct
import sys
import threading
import time

PORTS = {"modbus": 502, "eip": 44818, "http": 80}

# Modbus: FC 03 of the option board (unit 251, answered by the card itself): 1 register / 50 registers.
MODBUS_READ = bytes.fromhex("0001 0000 0006 FB 03 0000 0001")
MODBUS_READ_ALL = bytes.fromhex("0002 0000 0006 FB 03 0000 0032")
# EtherNet/IP: ListIdentity over TCP (no session needed; about 100 bytes back).
EIP_LIST_IDENTITY = struct.pack("<HHII8sI", 0x0063, 0, 0, 0, b"hostile!", 0)
HTTP_SESSION = b"GET /api/session HTTP/1.1\r\nHost: card\r\n\r\n"
HTTP_PAGE = b"GET / HTTP/1.1\r\nHost: card\r\n\r\n"

SLOW_REQUEST = {"modbus": MODBUS_READ, "eip": EIP_LIST_IDENTITY, "http": HTTP_SESSION}
STUCK_REQUEST = {"modbus": MODBUS_READ_ALL, "eip": EIP_LIST_IDENTITY, "http": HTTP_PAGE}


def connect(card, port, rcvbuf=None):
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    if rcvbuf is not None:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)  # before connect: the window stays small
    sock.settimeout(3.0)
    sock.connect((card, port))
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return sock


# ---- hostile -------------------------------------------------------------------------------------

def slow_client(card, port, request, until, stats):
    """One byte per second of `request`, repeated; reconnects when the card closes (HTTP's 408)."""
    sock, i = None, 0
    while time.monotonic() < until:
        try:
            if sock is None:
                sock, i = connect(card, port), 0
                stats["slow_connects"] += 1
            sock.send(request[i % len(request):i % len(request) + 1])
            i += 1
            stats["slow_bytes"] += 1
            # Drain whatever came back (an answer after a whole request, a 408) without blocking.
            ready, _, _ = select.select([sock], [], [], 0)
            if ready and not sock.recv(4096):
                raise ConnectionError("closed by the card")
        except OSError:
            stats["slow_closed"] += 1
            if sock is not None:
                sock.close()
            sock = None
        time.sleep(max(0.0, min(1.0, until - time.monotonic())))
    if sock is not None:
        sock.close()


def stuck_client(card, port, request, until, stats):
    """Requests without reading: the card's answers fill our (small) window, then our sends block."""
    try:
        sock = connect(card, port, rcvbuf=1024)
    except OSError:
        stats["stuck_refused"] += 1
        return
    sock.setblocking(False)
    sent = 0
    while time.monotonic() < until and sent < (4 << 20):
        try:
            sent += sock.send(request)
            continue
        except BlockingIOError:
            time.sleep(min(1.0, max(0.0, until - time.monotonic())))
        except OSError:
            stats["stuck_closed"] += 1
            break
    stats["stuck_bytes"] += sent
    time.sleep(max(0.0, until - time.monotonic()))
    sock.close()


def hostile(card, seconds, specs):
    until = time.monotonic() + seconds
    stats = {k: 0 for k in ("slow_connects", "slow_bytes", "slow_closed", "stuck_bytes", "stuck_closed",
                            "stuck_refused")}
    threads = []
    for spec in specs:
        protocol, slow, stuck = spec.split(":")
        port = PORTS[protocol]
        for _ in range(int(stuck)):
            threads.append(threading.Thread(target=stuck_client,
                                            args=(card, port, STUCK_REQUEST[protocol], until, stats)))
        for _ in range(int(slow)):
            threads.append(threading.Thread(target=slow_client, args=(card, port, SLOW_REQUEST[protocol], until, stats)))
    for t in threads:
        t.daemon = True
        t.start()
    # Stuck clients first: they are connected when the healthy client starts (tests wait for "hostile up").
    time.sleep(1.5)
    print("hostile up: " + " ".join(specs), flush=True)
    for t in threads:
        t.join(seconds + 5)
    print("hostile done: " + " ".join(f"{k}={v}" for k, v in stats.items()), flush=True)


# ---- healthy -------------------------------------------------------------------------------------

def receive_exact(sock, n):
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise ConnectionError("closed by the card")
        data += chunk
    return data


class Healthy:
    """One client doing request/response round trips; `round_trip` returns the reply bytes."""

    def __init__(self, card, protocol):
        self.protocol = protocol
        self.sock = connect(card, PORTS[protocol])
        self.buffer = b""
        if protocol == "eip":
            self.sock.sendall(struct.pack("<HHII8sIHH", 0x0065, 4, 0, 0, b"healthy!", 0, 1, 0))
            reply = receive_exact(self.sock, 28)
            command, _, self.session, status = struct.unpack_from("<HHII", reply)
            if command != 0x0065 or status != 0:
                raise RuntimeError(f"RegisterSession: {reply.hex()}")
            # SendRRData: Get_Attribute_Single Identity 1/1 attribute 1 (vendor 377).
            mr = bytes.fromhex("0E 03 20 01 24 01 30 01")
            body = struct.pack("<IHH", 0, 0, 2) + struct.pack("<HH", 0, 0) + struct.pack("<HH", 0xB2, len(mr)) + mr
            self.request = struct.pack("<HHII8sI", 0x006F, len(body), self.session, 0, b"healthy!", 0) + body
        elif protocol == "modbus":
            self.request = MODBUS_READ
        else:
            self.request = HTTP_SESSION

    def round_trip(self):
        self.sock.sendall(self.request)
        if self.protocol == "modbus":
            reply = receive_exact(self.sock, 11)
            if reply[:9] != bytes.fromhex("0001 0000 0005 FB 03 02"):
                raise RuntimeError(f"Modbus reply {reply.hex()}")
            return reply
        if self.protocol == "eip":
            header = receive_exact(self.sock, 24)
            length = struct.unpack_from("<H", header, 2)[0]
            body = receive_exact(self.sock, length)
            if not body.endswith(bytes.fromhex("8E 00 00 00 79 01")):
                raise RuntimeError(f"SendRRData reply {(header + body).hex()}")
            return header + body
        while b"\r\n\r\n" not in self.buffer:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("closed by the card")
            self.buffer += chunk
        head, _, rest = self.buffer.partition(b"\r\n\r\n")
        if not head.startswith(b"HTTP/1.1 200"):
            raise RuntimeError(f"HTTP reply {head[:80]!r}")
        length = 0
        for line in head.split(b"\r\n")[1:]:
            name, _, value = line.partition(b":")
            if name.strip().lower() == b"content-length":
                length = int(value)
        while len(rest) < length:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("closed by the card")
            rest += chunk
        self.buffer = rest[length:]
        return head + rest[:length]


def percentile(ordered, p):
    return ordered[min(len(ordered) - 1, int(round(p / 100.0 * (len(ordered) - 1))))]


def healthy(card, protocol, count, p99_limit_ms, label):
    client = Healthy(card, protocol)
    times = []
    deadline = time.monotonic() + 60.0
    for _ in range(count):
        start = time.perf_counter_ns()
        client.round_trip()
        times.append((time.perf_counter_ns() - start) / 1e6)
        if time.monotonic() > deadline:
            print(f"FAIL: {protocol}: {len(times)} of {count} round trips in 60 s", file=sys.stderr)
            return 1
    ordered = sorted(times)
    p50, p90, p99, worst = (percentile(ordered, p) for p in (50, 90, 99, 100))
    print(f"{protocol}: {count} round trips {label}: p50 {p50:.3f} ms, p90 {p90:.3f} ms, "
          f"p99 {p99:.3f} ms, max {worst:.3f} ms (limit p99 < {p99_limit_ms} ms)", flush=True)
    if p99 >= p99_limit_ms:
        print(f"FAIL: {protocol}: p99 {p99:.3f} ms is not below {p99_limit_ms} ms", file=sys.stderr)
        return 1
    return 0


# ---- flood ---------------------------------------------------------------------------------------

def arp_request(source_mac, source_ip, target_ip):
    broadcast = b"\xff" * 6
    return (broadcast + source_mac + b"\x08\x06" + struct.pack(">HHBBH", 1, 0x0800, 6, 4, 1) + source_mac +
            socket.inet_aton(source_ip) + bytes(6) + socket.inet_aton(target_ip))


# What a 100 Mbit/s port can carry at most: 148,809 minimum-size frames a second (64 bytes with the FCS,
# plus 20 of preamble and gap). Our ARP frames are minimum-size, the ListIdentity ones 70 bytes: the flood
# is paced at 140,000 frames/s in all, a broadcast storm at line rate (a TAP has no line rate of its own).
LINE_RATE_FRAMES = 140_000


def flood(card, seconds, iface, rate=LINE_RATE_FRAMES):
    """Half the frames are broadcast ListIdentity requests (UDP to the subnet's broadcast address), half ARP
    requests for the card's address from ever-changing senders of its subnet (without the ArpGuard, each one
    an ARP cache entry the card would make room for). Paced at `rate` frames/s (FLOOD_RATE overrides)."""
    rate = float(os.environ.get("FLOOD_RATE", rate))
    subnet = card.rsplit(".", 1)[0]
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.setsockopt(socket.SOL_SOCKET, socket.SO_BROADCAST, 1)
    raw = socket.socket(socket.AF_PACKET, socket.SOCK_RAW)
    raw.bind((iface, 0))
    list_identity = struct.pack("<HHII8sI", 0x0063, 0, 0, 0, bytes(8), 0)
    rng = random.Random(8)
    frames = []
    for _ in range(256):
        mac = bytes([0x02, 0x66] + [rng.randrange(256) for _ in range(4)])
        frames.append(arp_request(mac, f"{subnet}.{rng.randrange(100, 250)}", card))
    kind = os.environ.get("FLOOD_KIND", "both")  # for experiments: udp, arp, arp-same, both
    if kind == "arp-same":
        frames = frames[:1]
    sent_udp = sent_arp = errors = 0
    begin = time.monotonic()
    until = begin + seconds
    i = 0
    while time.monotonic() < until:
        ahead = (sent_udp + sent_arp + errors) / rate - (time.monotonic() - begin)
        if ahead > 0:
            time.sleep(ahead)
        for _ in range(32):
            try:
                if kind in ("both", "udp"):
                    udp.sendto(list_identity, (f"{subnet}.255", 44818))
                    sent_udp += 1
                if kind != "udp":
                    raw.send(frames[i % len(frames)])
                    sent_arp += 1
            except OSError:
                errors += 1  # the TAP queue is full: the card reads at its own pace
            i += 1
    print(f"flood: {sent_udp} broadcast ListIdentity, {sent_arp} ARP requests in {seconds} s "
          f"({(sent_udp + sent_arp) / seconds:.0f} frames/s), {errors} refused by the kernel", flush=True)


def main(argv):
    if len(argv) >= 4 and argv[1] == "hostile":
        hostile(argv[2], float(argv[3]), argv[4:])
        return 0
    if len(argv) in (6, 7) and argv[1] == "healthy":
        return healthy(argv[2], argv[3], int(argv[4]), float(argv[5]), argv[6] if len(argv) == 7 else "")
    if len(argv) == 5 and argv[1] == "flood":
        flood(argv[2], float(argv[3]), argv[4])
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
