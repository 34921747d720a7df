#!/usr/bin/python3
"""Exhaustion of the card's pools over TAP (docs/robustness.md "Exhaustion"). Run by tools/netns (CARD_IP,
CARD_CONTROL, HOST_IP); the protocol under test is the one the card speaks (c500, read from `config`):

c500 = 0, Modbus TCP (and the web server, open with either protocol):
  1. 16 clients (twice the 8 slots): the first 8 are served (exact answer of unit 251's version register),
     the other 8 complete the handshake and are reset (RST, never FIN, never a byte); the pool counters say
     8 used, 8 refused.
  2. 10,000 connect/close cycles on port 502: every fourth with a request and its exact answer, every
     fourth another with a drive read the client does not wait for (the proxy's access must be freed).
  3. 6 HTTP connections (twice the 3 slots), each of the first 3 with a request under way: the other 3
     get exactly the 503 answer, then FIN (the card closes those first: 3 PCBs in TIME_WAIT, counted).
c500 = 1, EtherNet/IP:
  1. 16 TCP connections to 44818 (twice the 8 sessions): 9 accepted, 7 reset; RegisterSession on the 9:
     8 sessions, 1 answered status 0x0002 (handle 0, exact bytes).
  2. 32 class 1 Forward_Opens (twice the 16 entries of the connection table, input only to 70, 71, 150,
     151): 16 open, 16 refused 0x01/0x0113 (exact bytes), and with the table full /api/eip-scanner (the
     web API's largest answer) is 200 with all 16; 12 class 3 (twice the 6 reply stores): 6 open,
     6 refused 0x01/0x011A. All closed with Forward_Close.
  3. 10,000 cycles: TCP connect/close; RegisterSession + UnRegisterSession; RegisterSession + close (every
     second one after sending a Get whose reply waits for the drive: the deferred request must be
     freed); and Forward_Open + Forward_Close (class 1 and class 3) on one long-lived session.
Then, once the card has settled, every lwIP pool (lwip.memp.*.used), the heap (lwip.mem.used) and every
pool of ours (pool.*.used) must be exactly where it was before, and no PCB of the card may be in
TIME_WAIT: the test's client always closes first (an UnRegisterSession goes out with the client's FIN in
one segment), so the TIME_WAIT state stays on the host.
Every loop is bounded in count and in time.
"""
import http.client
import json
import os
import socket
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from eip_io import (CLASS1_CYCLIC, CLASS3_SERVER_APPLICATION, ROUTER_PATH, Triad, forward_close,  # noqa: E402
                    forward_open, io_path, net_params, open_connection, refused_bytes)
from eip_originator import (EIP_PORT, LIST_SERVICES, REGISTER_SESSION, SEND_RR_DATA, UNREGISTER_SESSION,  # noqa: E402
                            Client, decode_encap, encode, hexs, send_rr_data_body)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CTL = os.path.join(ROOT, "tools", "card-ctl")
CARD_IP = os.environ["CARD_IP"]
HOST_IP = os.environ["HOST_IP"]
CONTROL = os.environ["CARD_CONTROL"]

CYCLES = 10_000
CYCLE_TIME_LIMIT = 60.0  # seconds for all cycles together
SETTLE_LIMIT = 15.0      # for the card's PCBs in LAST_ACK to go after the last cycle

MODBUS_PORT = 502
MODBUS_CLIENTS = 8
READ_VERSION = bytes.fromhex("0001 0000 0006 FB 03 0000 0001")
READ_ACC = bytes.fromhex("0002 0000 0006 01 03 0009 0001")  # a drive register: through the proxy
VERSION_ANSWER = bytes.fromhex("0001 0000 0005 FB 03 02 0106")

HTTP_PORT = 80
HTTP_CLIENTS = 3
HTTP_BUSY = (b"HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nRetry-After: 1\r\n"
             b"Content-Length: 23\r\nConnection: close\r\n\r\n{\"error\":\"server busy\"}")

EIP_TCP_CONNECTIONS = 9
EIP_SESSIONS = 8
CIP_CONNECTIONS = 16
CIP_EXPLICIT = 6
CONTEXT = b"ipe-exh!"
GET_ACC = bytes.fromhex("0E 04 20 64 25 00 09 40 30 03")  # Parameter object 0x64: a deferred reply


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def ok(message):
    print(f"ok: {message}")


def same(what, got, expected):
    if got != expected:
        fail(f"{what}: got {got!r}, expected {expected!r}")


def same_bytes(what, got, expected):
    if got != expected:
        fail(f"{what}:\n  got      {hexs(got) if got is not None else None}\n  expected {hexs(expected)}")


def ctl(command):
    answer = subprocess.run([CTL, CONTROL, command], capture_output=True, text=True, timeout=10)
    if answer.returncode != 0:
        fail(f"card-ctl {command}: {answer.stdout}{answer.stderr}")
    values = {}
    for line in answer.stdout.splitlines():
        name, eq, value = line.partition("=")
        if eq:
            values[name] = int(value) if value.isdigit() else value
    return values


def watched(stats):
    """What must come back to its baseline: the use of every lwIP pool, the heap, every pool of ours, and
    the TCP PCBs by list."""
    return {name: value for name, value in stats.items()
            if (name.startswith("lwip.memp.") and name.endswith(".used")) or name == "lwip.mem.used"
            or (name.startswith("pool.") and name.endswith(".used")) or name.startswith("lwip.tcp_pcbs.")}


def expect_pool(stats, name, used, high_water, refused):
    got = tuple(stats[f"pool.{name}.{k}"] for k in ("used", "high_water", "refused"))
    same(f"pool.{name} (used, high_water, refused)", got, (used, high_water, refused))


def settle_to(baseline, what, more=None):
    """Waits until the watched values are back at `baseline` (plus `more`, by name); fails naming every one
    that is not."""
    baseline = dict(baseline)
    for name, delta in (more or {}).items():
        baseline[name] += delta
    deadline = time.monotonic() + SETTLE_LIMIT
    while True:
        now = watched(ctl("stats"))
        differ = {k: (baseline.get(k), v) for k, v in now.items() if baseline.get(k) != v}
        if not differ:
            return
        if time.monotonic() > deadline:
            lines = "\n".join(f"  {k}: baseline {b}, now {v}" for k, (b, v) in sorted(differ.items()))
            hint = ""
            if "lwip.tcp_pcbs.time_wait" in differ:
                hint = "\n  (PCBs in TIME_WAIT: the card closed first; the client must close first)"
            fail(f"{what}: not back at the baseline after {SETTLE_LIMIT:.0f} s:\n{lines}{hint}")
        time.sleep(0.2)


def connect(port, timeout=3.0):
    sock = socket.create_connection((CARD_IP, port), timeout)
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return sock


def connect_refused(port, what):
    """A connection the card refuses: lwIP completes the handshake, then the accept callback resets it. The
    RST may reach the client before connect() returns (ECONNRESET there) or after (ECONNRESET on the first
    recv); either way after a SYN-ACK (a port without a listener gives ECONNREFUSED), never a byte or FIN."""
    try:
        sock = connect(port)
    except ConnectionResetError:
        return
    try:
        data = sock.recv(64)
    except ConnectionResetError:
        sock.close()
        return
    except socket.timeout:
        fail(f"{what}: neither reset nor closed within the timeout")
    fail(f"{what}: expected a reset, got {'FIN' if data == b'' else hexs(data)}")


def connect_beyond(port, capacity, count, what):
    """`count` connections at once: the first `capacity` are accepted (returned), the rest refused."""
    accepted = [connect(port) for _ in range(capacity)]
    for i in range(capacity, count):
        connect_refused(port, f"{what} {i + 1} of {count}")
    return accepted


def exchange(sock, request, size):
    sock.sendall(request)
    data = b""
    while len(data) < size:
        chunk = sock.recv(size - len(data))
        if not chunk:
            break
        data += chunk
    return data


def expect_counted(before, after, deltas):
    """The card counted exactly what the cycles did (so none of them was a no-op)."""
    for name, delta in deltas.items():
        same(f"{name} moved by", after[name] - before[name], delta)


def run_cycles(name, cycle):
    start = time.monotonic()
    for i in range(CYCLES):
        cycle(i)
        if time.monotonic() - start > CYCLE_TIME_LIMIT:
            fail(f"{name}: only {i + 1} of {CYCLES} cycles in {CYCLE_TIME_LIMIT:.0f} s")
    elapsed = time.monotonic() - start
    ok(f"{CYCLES} {name} cycles in {elapsed:.1f} s ({CYCLES / elapsed:.0f}/s)")


# ---- HTTP ------------------------------------------------------------------------------------------

def http_slots():
    """Twice the 3 HTTP slots, each taken by a request under way: the other 3 get 503 and FIN (an idle
    connection would be closed to make room instead: docs/web.md)."""
    baseline = watched(ctl("stats"))
    busy = []
    for _ in range(HTTP_CLIENTS):
        sock = connect(HTTP_PORT)
        sock.sendall(b"GET /api/session HTTP/1.1\r\nHost: card\r\n")  # no blank line yet: under way
        busy.append(sock)
    time.sleep(0.1)  # the card has taken each request's first bytes
    for i in range(HTTP_CLIENTS):
        sock = connect(HTTP_PORT)
        same_bytes(f"HTTP connection {HTTP_CLIENTS + i + 1}", receive_until_closed(sock), HTTP_BUSY)
    stats = ctl("stats")
    expect_pool(stats, "http_tcp_slots", HTTP_CLIENTS, HTTP_CLIENTS, HTTP_CLIENTS)
    expect_pool(stats, "http_clients", HTTP_CLIENTS, HTTP_CLIENTS, HTTP_CLIENTS)
    for sock in busy:
        sock.close()
    # The card closed the refused connections (503, then FIN): their PCBs wait in TIME_WAIT (2 x TCP_MSL,
    # lwIP reclaims them early when the pool runs out), and lwIP's TCP timer (one sys_timeout) runs while
    # they do; everything else is back where it was.
    settle_to(baseline, "after the HTTP connections",
              {"lwip.tcp_pcbs.time_wait": HTTP_CLIENTS, "lwip.memp.TCP_PCB.used": HTTP_CLIENTS,
               "lwip.memp.SYS_TIMEOUT.used": 1})
    ok(f"{2 * HTTP_CLIENTS} HTTP connections with a request under way: {HTTP_CLIENTS} kept, "
       f"{HTTP_CLIENTS} answered 503 and closed; the card's pools back at their baseline, its {HTTP_CLIENTS} "
       f"closes in TIME_WAIT")


def receive_until_closed(sock):
    data = b""
    while True:
        chunk = sock.recv(4096)
        if not chunk:
            sock.close()
            return data
        data += chunk


# ---- Modbus TCP ------------------------------------------------------------------------------------

def modbus():
    baseline = watched(ctl("stats"))
    served = connect_beyond(MODBUS_PORT, MODBUS_CLIENTS, 2 * MODBUS_CLIENTS, "Modbus client")
    for i, sock in enumerate(served):
        same_bytes(f"Modbus client {i + 1} served", exchange(sock, READ_VERSION, len(VERSION_ANSWER)), VERSION_ANSWER)
    stats = ctl("stats")
    expect_pool(stats, "modbus_tcp_slots", MODBUS_CLIENTS, MODBUS_CLIENTS, MODBUS_CLIENTS)
    expect_pool(stats, "modbus_clients", MODBUS_CLIENTS, MODBUS_CLIENTS, MODBUS_CLIENTS)
    for sock in served:
        sock.close()
    ok(f"{2 * MODBUS_CLIENTS} Modbus clients: {MODBUS_CLIENTS} served, {MODBUS_CLIENTS} reset after the handshake")
    settle_to(baseline, "after the Modbus clients")

    def cycle(i):
        sock = connect(MODBUS_PORT)
        if i % 4 == 0:
            same_bytes(f"cycle {i}: answer", exchange(sock, READ_VERSION, len(VERSION_ANSWER)), VERSION_ANSWER)
        elif i % 4 == 2:
            sock.sendall(READ_ACC)  # and gone before the drive answers: the proxy's access must be freed
        sock.close()

    before = ctl("stats")
    run_cycles("Modbus connect/close", cycle)
    settle_to(baseline, f"after {CYCLES} Modbus cycles")
    expect_counted(before, ctl("stats"), {"modbus.accepted": CYCLES,
                                          "modbus.refused": 0, "modbus.lost": 0})
    ok("every lwIP pool, the heap and every pool of the card at their baseline; no PCB in TIME_WAIT")


# ---- EtherNet/IP -----------------------------------------------------------------------------------

def register_reply(status, handle):
    return struct.pack("<HHII8sI", REGISTER_SESSION, 4, handle, status, CONTEXT, 0) + struct.pack("<HH", 1, 0)


def register(sock):
    reply = exchange(sock, encode(REGISTER_SESSION, struct.pack("<HH", 1, 0), 0, CONTEXT), 28)
    return decode_encap(reply).session, reply


def unregister_with_fin(sock, handle):
    """UnRegisterSession and the client's FIN in one segment: the card closes a connection whose peer has
    already closed, so the TIME_WAIT state is the client's (docs/robustness.md "Exhaustion")."""
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_CORK, 1)
    sock.sendall(encode(UNREGISTER_SESSION, b"", handle, CONTEXT))
    sock.close()


def input_only(serial, point, t_o_size):
    triad = Triad(serial)
    request = forward_open(triad, io_path(199, point), 1_000_000, net_params(2), 1_000_000, net_params(t_o_size),
                           transport=CLASS1_CYCLIC, t_o_id=0x1900_0000 + serial, multiplier=3)
    return triad, io_path(199, point), request


def explicit(serial):
    triad = Triad(serial)
    request = forward_open(triad, ROUTER_PATH, 2_000_000, net_params(500), 2_000_000, net_params(500),
                           transport=CLASS3_SERVER_APPLICATION, t_o_id=0x3300_0000 + serial, multiplier=3)
    return triad, ROUTER_PATH, request


def open_or_refuse(client, triad, request, refusal, what):
    mr, raw, _ = open_connection(client, request)
    if refusal is None:
        if mr.general != 0:
            fail(f"{what}: refused: {hexs(raw)}")
    else:
        same_bytes(what, raw, refused_bytes(triad, [refusal]))


def open_twice(client, capacity, refusal, make):
    """2 x `capacity` Forward_Opens, `make(n)` -> (triad, path, request, what): the first `capacity` open,
    the others get exactly 0x01 with `refusal`. Returns the (triad, path) of those open."""
    opened = []
    for n in range(2 * capacity):
        triad, path, request, what = make(n)
        open_or_refuse(client, triad, request, None if n < capacity else refusal, what)
        if n < capacity:
            opened.append((triad, path))
    return opened


def close_connection(client, triad, path, what):
    mr, raw, _ = open_connection(client, forward_close(triad, path))
    if mr.general != 0:
        fail(f"{what}: Forward_Close refused: {hexs(raw)}")


def ethernet_ip():
    # Productions to us go to HOST_IP:2222; a bound socket takes them (no ICMP back to the card).
    sink = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sink.bind((HOST_IP, 2222))
    baseline = watched(ctl("stats"))

    accepted = connect_beyond(EIP_PORT, EIP_TCP_CONNECTIONS, 2 * EIP_SESSIONS, "EtherNet/IP TCP connection")
    handles = []
    for i, sock in enumerate(accepted):
        handle, reply = register(sock)
        if i < EIP_SESSIONS:
            same_bytes(f"RegisterSession {i + 1}", reply, register_reply(0, handle))
            if handle == 0 or handle in handles:
                fail(f"RegisterSession {i + 1}: handle 0x{handle:08X}")
            handles.append(handle)
        else:
            same_bytes(f"RegisterSession {i + 1} beyond the sessions", reply, register_reply(0x0002, 0))
    stats = ctl("stats")
    tcp_refused = 2 * EIP_SESSIONS - EIP_TCP_CONNECTIONS
    expect_pool(stats, "eip_tcp_slots", EIP_TCP_CONNECTIONS, EIP_TCP_CONNECTIONS, tcp_refused)
    expect_pool(stats, "eip_connections", EIP_TCP_CONNECTIONS, EIP_TCP_CONNECTIONS, 0)
    expect_pool(stats, "eip_sessions", EIP_SESSIONS, EIP_SESSIONS, EIP_TCP_CONNECTIONS - EIP_SESSIONS)
    for sock in accepted:
        sock.close()
    ok(f"{2 * EIP_SESSIONS} sessions asked for: {EIP_SESSIONS} registered, {EIP_TCP_CONNECTIONS - EIP_SESSIONS} "
       f"answered 0x0002, {2 * EIP_SESSIONS - EIP_TCP_CONNECTIONS} TCP connections reset")
    settle_to(baseline, "after the sessions")

    client = Client(CARD_IP, timeout=3.0)
    same("RegisterSession", client.register_session().status, 0)
    points = [(70, 6), (71, 6), (150, 6), (151, 10)]  # four connections each (the per-point limit)
    beyond = [(152, 14), (155, 20)]                    # free points: only the table's limit refuses them

    def class1(n):
        point, size = points[n // 4] if n < CIP_CONNECTIONS else beyond[n % 2]
        return input_only(0x100 + n, point, size) + (f"class 1 Forward_Open {n + 1} (input only 199/{point})",)

    opened = open_twice(client, CIP_CONNECTIONS, 0x0113, class1)
    stats = ctl("stats")
    expect_pool(stats, "cip_connections", CIP_CONNECTIONS, CIP_CONNECTIONS, CIP_CONNECTIONS)
    expect_pool(stats, "cip_productions", CIP_CONNECTIONS, CIP_CONNECTIONS, 0)
    eip_scanner_with_every_connection()
    for triad, path in opened:
        close_connection(client, triad, path, "class 1")
    opened = open_twice(client, CIP_EXPLICIT, 0x011A,
                        lambda n: explicit(0x200 + n) + (f"class 3 Forward_Open {n + 1}",))
    stats = ctl("stats")
    expect_pool(stats, "cip_explicit_connections", CIP_EXPLICIT, CIP_EXPLICIT, CIP_EXPLICIT)
    expect_pool(stats, "cip_connections", CIP_EXPLICIT, CIP_CONNECTIONS, CIP_CONNECTIONS)
    for triad, path in opened:
        close_connection(client, triad, path, "class 3")
    ok(f"{2 * CIP_CONNECTIONS} class 1 Forward_Opens: {CIP_CONNECTIONS} open, {CIP_CONNECTIONS} refused 0x0113; "
       f"{2 * CIP_EXPLICIT} class 3: {CIP_EXPLICIT} open, {CIP_EXPLICIT} refused 0x011A; all closed")

    def cycle(i):
        kind = i % 4
        if kind == 0:
            connect(EIP_PORT).close()
        elif kind == 1:
            sock = connect(EIP_PORT)
            handle, reply = register(sock)
            same_bytes(f"cycle {i}: RegisterSession", reply, register_reply(0, handle))
            unregister_with_fin(sock, handle)
        elif kind == 2:
            sock = connect(EIP_PORT)
            handle, reply = register(sock)
            same_bytes(f"cycle {i}: RegisterSession", reply, register_reply(0, handle))
            if i % 8 == 2:  # a Get of acc, whose reply waits for the drive, and gone before it comes
                sock.sendall(encode(SEND_RR_DATA, send_rr_data_body(GET_ACC), handle, CONTEXT))
            sock.close()
        else:
            serial = 0x1000 + (i // 4) % 0x1000
            triad, path, request = (input_only(serial, 71, 6) if (i // 4) % 2 == 0 else explicit(serial))
            open_or_refuse(client, triad, request, None, f"cycle {i}: Forward_Open")
            close_connection(client, triad, path, f"cycle {i}")

    before = ctl("stats")
    run_cycles("EtherNet/IP (TCP, sessions, Forward_Open/Forward_Close)", cycle)
    same("the long-lived session still answers ListServices", client.request(LIST_SERVICES).status, 0)
    client.close()
    settle_to(baseline, f"after {CYCLES} EtherNet/IP cycles")
    # Not eip.lost: while the drive works through earlier Gets, the proxy's pool is full and a Get is
    # answered at once (0x02), which can reach the client after its close; Linux then resets.
    expect_counted(before, ctl("stats"), {"eip.accepted": CYCLES * 3 // 4, "eip.refused": 0,
                                          "cip.open_requests": CYCLES // 4, "cip.close_requests": CYCLES // 4})
    sink.close()
    ok("every lwIP pool, the heap and every pool of the card at their baseline; no PCB in TIME_WAIT")


def eip_scanner_with_every_connection():
    """The web API's largest answer, /api/eip-scanner with the whole connection table in use, fits the web
    server's response buffer (docs/web.md "Connections"): 200 with every connection, not 500. The session
    is logged out again, so the pools come back to their baseline."""
    web = http.client.HTTPConnection(CARD_IP, HTTP_PORT, timeout=5)
    web.request("POST", "/api/login", body=json.dumps({"password": "USER"}),
                headers={"Content-Type": "application/json"})
    answer = web.getresponse()
    login = json.loads(answer.read())
    same("POST /api/login", answer.status, 200)
    cookie = answer.getheader("Set-Cookie").split(";")[0]
    web.request("GET", "/api/eip-scanner", headers={"Cookie": cookie})
    answer = web.getresponse()
    body = answer.read()
    same(f"GET /api/eip-scanner with {CIP_CONNECTIONS} connections", answer.status, 200)
    same("connections listed", len(json.loads(body)["connections"]), CIP_CONNECTIONS)
    web.request("POST", "/api/logout", headers={"Cookie": cookie, "X-CSRF-Token": login["csrf"]})
    answer = web.getresponse()
    answer.read()
    same("POST /api/logout", answer.status, 204)
    web.close()
    ok(f"/api/eip-scanner with {CIP_CONNECTIONS} connections: 200, {len(body)} bytes of JSON")


def wait_listening(counter):
    deadline = time.monotonic() + 10
    while ctl("stats").get(counter) != 1:
        if time.monotonic() > deadline:
            fail(f"{counter} is not 1 after 10 s")
        time.sleep(0.1)


def main():
    protocol = ctl("config").get("c500")
    wait_listening("modbus.listening" if protocol == 0 else "eip.listening")
    if protocol == 0:
        modbus()
        http_slots()
    elif protocol == 1:
        ethernet_ip()
    else:
        fail(f"c500 = {protocol!r}: neither Modbus TCP nor EtherNet/IP")
    return 0


if __name__ == "__main__":
    sys.exit(main())
