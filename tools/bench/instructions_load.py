#!/usr/bin/python3
"""The load of tools/bench/instructions: a fixed count of each operation, each batch between two callgrind
dumps of the card, so that one dump holds one batch (and the idle work of its window).

usage: instructions_load.py --pid PID --host ADDR --phases eip|modbus [--scale F] [--http-password PW]

For every phase it prints one line `phase NAME ops=N seconds=S` after the phase's closing dump; the dumps
are numbered in the same order (tools/bench/instructions reads both). Phase `idle` sends nothing. Every
reply is checked (status, length); a wrong one ends the run with status 1, so no figure is printed for
work that did not happen. Bounded: each batch has a fixed count and a time limit (60 s), the I/O windows
a fixed length.
"""
import argparse
import http.client
import json
import os
import socket
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "integration"))
from eip_originator import Client, mr_request, epath, GET_ATTRIBUTE_SINGLE  # noqa: E402
from eip_io import (IoConnection, IoEndpoint, Triad, forward_close, forward_open, io_path,  # noqa: E402
                    net_params, open_connection, decode_open_success)

BATCH_LIMIT_S = 60.0


class Bench:
    def __init__(self, pid):
        self.pid = pid
        self.dumps = 0

    def dump(self):
        """One callgrind dump of the card: its counters restart from zero. Returns the instant (midpoint of the
        call: the dump happens somewhere inside it)."""
        start = time.monotonic()
        subprocess.run(["callgrind_control", "-d", str(self.pid)], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, timeout=60)
        self.dumps += 1
        return (start + time.monotonic()) / 2

    def phase(self, name, ops, body):
        """Dumps, runs body() (which returns the operation count it did), dumps; prints the phase line."""
        begin = self.dump()
        done = body()
        end = self.dump()
        if ops is not None and done != ops:
            sys.exit(f"instructions_load: phase {name}: {done} operations of {ops}")
        print(f"phase {name} ops={done} seconds={end - begin:.3f}", flush=True)


def bounded(count, one):
    deadline = time.monotonic() + BATCH_LIMIT_S
    for i in range(count):
        if time.monotonic() > deadline:
            return i
        one()
    return count


def expect(condition, what):
    if not condition:
        sys.exit(f"instructions_load: {what}")


# ---- EtherNet/IP ----------------------------------------------------------------------------------------

def eip_phases(bench, host, scale, password):
    gas = mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1, 1))
    with Client(host, timeout=10.0) as c:
        c.register_session()
        # Warm the paths once (first-use work is not per-operation work).
        expect(c.cip(gas).general == 0, "GAS Identity 1/1/1 failed")

        def one_gas():
            reply = c.cip(gas)
            expect(reply.general == 0 and len(reply.data) == 2, f"GAS reply {reply}")

        def one_msp():
            reply, members = c.multiple_service_packet([gas] * 4)
            expect(reply.general == 0 and len(members) == 4 and all(m.general == 0 for m in members),
                   f"MSP reply {reply}")

        serial = [0x4000]

        def one_open_close():
            serial[0] += 1
            triad, path = Triad(serial[0]), io_path(199, 71)
            mr, _, _ = open_connection(c, forward_open(triad, path, 100_000, net_params(2), 100_000,
                                                       net_params(2 + 4), t_o_id=0x7100_0000 + serial[0]))
            expect(mr.general == 0, f"Forward_Open (input only 199/71) refused: {mr}")
            mr, _, _ = open_connection(c, forward_close(triad, path))
            expect(mr.general == 0, f"Forward_Close refused: {mr}")

        bench.phase("idle", None, lambda: (time.sleep(5.0 * scale), 0)[1])
        n = int(2000 * scale)
        bench.phase("gas", n, lambda: bounded(n, one_gas))
        n = int(1000 * scale)
        bench.phase("msp4", n, lambda: bounded(n, one_msp))
        n = int(300 * scale)
        bench.phase("open_close", n, lambda: bounded(n, one_open_close))

        for rpi_us in (1000, 10_000):
            serial[0] += 1
            triad, path = Triad(serial[0]), io_path(21, 71)
            mr, _, _ = open_connection(c, forward_open(triad, path, rpi_us, net_params(2 + 4 + 4), rpi_us,
                                                       net_params(2 + 4), t_o_id=0x7100_0000 + serial[0],
                                                       multiplier=7))
            # Timeout multiplier x512: the card runs ~50 times slower under callgrind, and a dump stops it.
            expect(mr.general == 0, f"Forward_Open 21/71 at RPI {rpi_us} refused: {mr}")
            opened = decode_open_success(mr.data)
            with IoEndpoint(host) as ep:
                ep.add(IoConnection(opened["o_t_id"], opened["t_o_id"], rpi_us, bytes(4), name="21/71"))
                time.sleep(1.0)  # the first productions and the drive's first answers are not steady state
                window = []

                def io_window():
                    first = ep.count(opened["t_o_id"])
                    time.sleep(5.0 * scale)
                    window.append(ep.count(opened["t_o_id"]) - first)
                    return window[0]

                bench.phase(f"class1_rpi{rpi_us // 1000}ms", None, io_window)
            mr, _, _ = open_connection(c, forward_close(triad, path))
            expect(mr.general == 0, f"Forward_Close 21/71 refused: {mr}")

    # HTTP: one login (PBKDF2: not per request), then GET /api/monitor on one kept-alive connection.
    conn = http.client.HTTPConnection(host, 80, timeout=10)
    conn.request("POST", "/api/login", body=json.dumps({"password": password}),
                 headers={"Content-Type": "application/json"})
    reply = conn.getresponse()
    body = reply.read()
    expect(reply.status == 200, f"login: {reply.status} {body!r}")
    cookie = reply.getheader("Set-Cookie").split(";")[0]

    def one_get():
        conn.request("GET", "/api/monitor", headers={"Cookie": cookie})
        r = conn.getresponse()
        data = r.read()
        expect(r.status == 200 and data.startswith(b'{"link":'), f"GET /api/monitor: {r.status} {data[:80]!r}")

    one_get()
    n = int(500 * scale)
    bench.phase("http_get", n, lambda: bounded(n, one_get))
    conn.close()


# ---- Modbus TCP -----------------------------------------------------------------------------------------

class ModbusClient:
    def __init__(self, host, port):
        self.sock = socket.create_connection((host, port), timeout=10)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.tid = 0

    def exchange(self, unit, pdu):
        self.tid = (self.tid + 1) & 0xFFFF
        self.sock.sendall(struct.pack(">HHHB", self.tid, 0, len(pdu) + 1, unit) + pdu)
        head = self._exact(7)
        tid, proto, length, unit_back = struct.unpack(">HHHB", head)
        body = self._exact(length - 1)
        expect(tid == self.tid and proto == 0 and unit_back == unit, f"Modbus header {head.hex()}")
        return body

    def _exact(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            expect(chunk, "Modbus connection closed")
            data += chunk
        return data


def modbus_phases(bench, host, port, scale, units):
    client = ModbusClient(host, port)
    fc03 = struct.pack(">BHH", 0x03, 0, 10)
    # FC23: write scanner words 0-6, read words 0-6 (IO scanning, seed 000 §9.2).
    fc23 = struct.pack(">BHHHHB", 0x17, 0, 7, 0, 7, 14) + bytes(14)
    unit03, unit23 = units

    def one_fc03():
        body = client.exchange(unit03, fc03)
        expect(body[0] == 0x03 and body[1] == 20 and len(body) == 22, f"FC03 reply {body.hex()}")

    def one_fc23():
        body = client.exchange(unit23, fc23)
        expect(body[0] == 0x17 and body[1] == 14 and len(body) == 16, f"FC23 reply {body.hex()}")

    one_fc03()
    one_fc23()
    bench.phase("idle", None, lambda: (time.sleep(5.0 * scale), 0)[1])
    n = int(2000 * scale)
    bench.phase("fc03", n, lambda: bounded(n, one_fc03))
    bench.phase("fc23", n, lambda: bounded(n, one_fc23))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pid", type=int, required=True)
    parser.add_argument("--host", required=True)
    parser.add_argument("--port", type=int, default=502)
    parser.add_argument("--phases", choices=["eip", "modbus", "modbus-reference"], required=True)
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--http-password", default="USER")
    args = parser.parse_args()
    expect(0.05 <= args.scale <= 4, "--scale between 0.05 and 4")
    bench = Bench(args.pid)
    bench.dump()  # start-up and configuration load: not part of any phase
    if args.phases == "eip":
        eip_phases(bench, args.host, args.scale, args.http_password)
    elif args.phases == "modbus":
        modbus_phases(bench, args.host, args.port, args.scale, (251, 255))
    else:
        modbus_phases(bench, args.host, args.port, args.scale, (251, 255))  # libmodbus over TCP answers any unit


if __name__ == "__main__":
    main()
