#!/usr/bin/python3
"""The load tools/soak puts on one card, run inside the card's namespace (docs/robustness.md "Soak").

usage: soak_load.py eip|modbus SECONDS REPORT_SECONDS        (CARD_IP, CARD_CONTROL from tools/netns)

eip     class 1 exclusive owner 21/71 at RPI 10 ms (multiplier 2: timeout 160 ms) and an input-only 199/152
        at RPI 20 ms; explicit messages (UCMM Gets, Parameter 0x65 Get/Set with deferred replies, a Multiple
        Service Packet, a class 3 connection); the web API.
modbus  an IO scanner (FC 23 on unit 255 every 10 ms, c604 = 1); a second client reading drive registers,
        the option board and the identity, writing acc every 5 s; the web API.
Both    cable pulls ('link L down' for 2 s every 20 s from second 8), inverter trips (E, code 17, every 30 s
        from second 15, reset by the master's fault-reset edge: assembly 21 bit 2 / FA06 bit 13) and damaged
        serial replies ('inject corrupt 2' every 15 s from second 5).

Every REPORT_SECONDS the request loops pause (I/O keeps running), the card's pools are read at rest and one
report line is printed: lwIP memp "used", the heap, any pool.* line, the I/O figures of the interval, the
request counts. Exit status 1 (with the reasons) when:
  - a production is missed: two consecutive T->O datagrams of a connection more than its timeout apart,
    the interval not overlapping a cable pull (eip); an IO scan failing outside a pull (modbus);
  - a pool is above its baseline (read at rest 3 s after the start) at the end, load stopped and 10 s allowed
    to settle, or in 3 reports in a row; TCP PCBs not back to their value before any connection once every
    client has closed;
  - a trip is not reset within 10 s outside a pull.
Every loop is bounded by SECONDS; only the card's address and its control socket are used.
"""
import http.client
import json
import os
import socket
import struct
import sys
import threading
import time

from eip_originator import ENCAP_SUCCESS, Client, epath, hexs, mr_request, msp_request
from eip_io import (CLASS3_SERVER_APPLICATION, ROUTER_PATH, ExplicitConnection, IoConnection, IoEndpoint, SimControl,
                    Triad, decode_open_success, forward_close, forward_open, io_path, net_params, open_connection)

CARD = os.environ["CARD_IP"]
PULL_FIRST, PULL_EVERY, PULL_SECONDS = 8.0, 20.0, 2.0
TRIP_FIRST, TRIP_EVERY, TRIP_CODE = 15.0, 30.0, 17
INJECT_FIRST, INJECT_EVERY = 5.0, 15.0
SETTLE_AFTER_PULL = 1.0  # a connection is judged again this long after the cable is back
RPI, MULTIPLIER = 10000, 2
TIMEOUT_US = RPI * 4 << MULTIPLIER


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(p / 100.0 * (len(ordered) - 1))))] if ordered else 0.0


class Pulls:
    """The cable pulls so far: [(down, up or None)] in time.monotonic() seconds."""

    def __init__(self):
        self.lock = threading.Lock()
        self.windows = []

    def down(self, t):
        with self.lock:
            self.windows.append([t, None])

    def up(self, t):
        with self.lock:
            self.windows[-1][1] = t

    def overlaps(self, start, end):
        """Whether [start, end] touches a pull (extended by the settle time after the cable is back)."""
        with self.lock:
            for down, up in self.windows:
                if start <= (up if up is not None else float("inf")) + SETTLE_AFTER_PULL and end >= down:
                    return True
        return False


class Worker(threading.Thread):
    """A request loop that can be paused (for the pool snapshot at rest) and counts what it did."""

    def __init__(self, name, step, period):
        super().__init__(name=name, daemon=True)
        self.step, self.period = step, period
        self.stop_flag = False
        self.pause = threading.Event()
        self.idle = threading.Event()
        self.done = self.errors = 0
        self.last_error = ""

    def run(self):
        while not self.stop_flag:
            if self.pause.is_set():
                self.idle.set()
                time.sleep(0.01)
                continue
            self.idle.clear()
            try:
                self.step()
                self.done += 1
            except Exception as error:  # noqa: BLE001 - a failed request is counted, the loop goes on
                self.errors += 1
                self.last_error = f"{type(error).__name__}: {error}"
                time.sleep(0.5)  # a cable pull: try again shortly (the step reconnects)
            time.sleep(self.period)
        self.idle.set()


class Web:
    """The web API as the page uses it: login, then /api/session and /api/monitor on one connection."""

    def __init__(self):
        self.conn = None
        self.cookie = None
        self.turn = 0

    def call(self, method, path, body=None):
        if self.conn is None:
            self.conn = http.client.HTTPConnection(CARD, 80, timeout=5)
            self.cookie = None
        headers = {"Cookie": self.cookie} if self.cookie else {}
        if body is not None:
            headers["Content-Type"] = "application/json"
        try:
            self.conn.request(method, path, body=body, headers=headers)
            response = self.conn.getresponse()
            data = response.read()
        except (OSError, http.client.HTTPException):
            self.conn.close()
            self.conn = None
            raise
        return response, data

    def step(self):
        if self.cookie is None:
            response, data = self.call("POST", "/api/login", json.dumps({"password": "USER"}))
            if response.status != 200:
                raise RuntimeError(f"login: {response.status} {data[:60]!r}")
            self.cookie = response.getheader("Set-Cookie").split(";")[0]
        self.turn += 1
        response, data = self.call("GET", "/api/monitor" if self.turn % 2 else "/api/session")
        if response.status != 200:
            self.cookie = None if response.status == 401 else self.cookie
            raise RuntimeError(f"web: {response.status} {data[:60]!r}")

    def close(self):
        if self.conn is not None:
            self.conn.close()


# ---- EtherNet/IP ---------------------------------------------------------------------------------

class Explicit:
    """UCMM and class 3 requests on one session; reconnects after a failure."""

    REQUESTS = [
        mr_request(0x0E, epath(0x01, 1, 1)),                  # Identity vendor
        mr_request(0x0E, epath(0xF5, 1, 5)),                  # TCP/IP configuration
        mr_request(0x0E, epath(0xF6, 1, 4)),                  # Ethernet Link counters
        mr_request(0x0E, epath(0x65, 0x0009, 3)),             # acc over the drive link (deferred)
        msp_request([mr_request(0x0E, epath(0x29, 1, 6)), mr_request(0x0E, epath(0x2A, 1, 7))]),
    ]

    def __init__(self):
        self.client = None
        self.class3 = None
        self.turn = 0
        self.sequence = 0
        self.serial = 0x3000

    def connect(self):
        self.client = Client(CARD, timeout=5.0)
        if self.client.register_session().status != ENCAP_SUCCESS:
            raise RuntimeError("RegisterSession refused")
        self.serial += 1
        request = forward_open(Triad(self.serial), ROUTER_PATH, 2000000, net_params(500, variable=True), 2000000,
                               net_params(500, variable=True), transport=CLASS3_SERVER_APPLICATION,
                               t_o_id=0x3C000000 + self.serial, multiplier=3)
        mr, raw, _ = open_connection(self.client, request)
        if mr.general != 0:
            raise RuntimeError(f"class 3 Forward_Open refused: {hexs(raw)}")
        self.class3 = ExplicitConnection(self.client, decode_open_success(mr.data)["o_t_id"], 0x3C000000 + self.serial)

    def step(self):
        try:
            if self.client is None:
                self.connect()
            self.turn += 1
            if self.turn % 3 == 0:
                self.sequence = (self.sequence + 1) & 0xFFFF
                got = self.class3.request(self.sequence, self.REQUESTS[0], wait=5.0)
                if got is None or got[2][:4] != bytes.fromhex("8E 00 00 00"):
                    raise RuntimeError(f"class 3 reply {got}")
                return
            if self.turn % 50 == 0:  # a parameter write now and then (acc 10.0 s or 10.1 s)
                request = mr_request(0x10, epath(0x65, 0x0009, 3), struct.pack("<H", 100 + self.turn // 50 % 2))
            else:
                request = self.REQUESTS[self.turn % len(self.REQUESTS)]
            reply = self.client.cip(request)
            if reply.general not in (0x00,):
                raise RuntimeError(f"explicit reply {hexs(reply.raw())}")
        except Exception:
            self.close()
            raise

    def close(self):
        if self.client is not None:
            self.client.close()
        self.client = None


class EipIo:
    """The exclusive owner 21/71 and an input-only 199/152, reopened after every cable pull."""

    def __init__(self, pulls):
        self.pulls = pulls
        self.endpoint = IoEndpoint(CARD)
        self.client = None
        self.serial = 0x1000
        self.owner = None    # (triad, path, IoConnection)
        self.watcher = None
        self.fault_reset = False
        self.opened_at = 0.0
        self.reopens = 0
        self.rpi_of, self.timeout_of = {}, {}  # T->O connection ID -> RPI, timeout (µs)

    def _open(self, consumed, produced, o_t_size, t_o_size, rpi, data):
        self.serial += 1
        triad, path = Triad(self.serial), io_path(consumed, produced)
        t_o_id = 0x10000000 + self.serial
        mr, raw, _ = open_connection(self.client, forward_open(triad, path, rpi, net_params(o_t_size), rpi,
                                                               net_params(t_o_size), t_o_id=t_o_id,
                                                               multiplier=MULTIPLIER))
        if mr.general != 0:
            raise RuntimeError(f"Forward_Open {consumed}/{produced} refused: {hexs(raw)}")
        connection = IoConnection(decode_open_success(mr.data)["o_t_id"], t_o_id, rpi, data, header=o_t_size > 2,
                                  name=f"{consumed}/{produced}")
        self.rpi_of[t_o_id], self.timeout_of[t_o_id] = rpi, rpi * 4 << MULTIPLIER
        self.endpoint.add(connection)
        return triad, path, connection

    def open(self):
        for old in (self.owner, self.watcher):
            if old is not None:
                self.endpoint.stop_sending(old[2])
        if self.client is not None:
            self.client.close()
        self.client = Client(CARD, timeout=5.0)
        if self.client.register_session().status != ENCAP_SUCCESS:
            raise RuntimeError("RegisterSession refused")
        self.owner = self._open(21, 71, 2 + 4 + 4, 2 + 4, RPI, bytes(4))
        self.watcher = self._open(199, 152, 2, 2 + 12, 2 * RPI, b"")
        self.opened_at = time.monotonic()
        self.reopens += 1

    def alive(self):
        """Whether the owner's T->O still comes (else the card closed it: timeout after a pull)."""
        newest = self.endpoint.latest(self.owner[2].t_o_id) if self.owner else None
        if newest is None:
            return time.monotonic() - self.opened_at < 1.0
        return time.time_ns() - newest.time_ns < 0.5e9

    def set_fault_reset(self, on):
        self.endpoint.set(self.owner[2], data=bytes([0x04 if on else 0x00, 0, 0, 0]))

    def connections(self):
        return [c for c in (self.owner, self.watcher) if c is not None]

    def close(self):
        for triad, path, connection in self.connections():
            self.endpoint.stop_sending(connection)
            try:
                open_connection(self.client, forward_close(triad, path))
            except Exception:  # the card may have closed it already
                pass
        if self.client is not None:
            self.client.close()
        self.endpoint.close()


def io_intervals(endpoint, connection_ids, pulls, start_ns, end_ns, timeout_us):
    """(intervals in µs of the window not touching a pull, gaps beyond timeout_us) over the connections."""
    intervals, gaps = [], []
    offset = time.monotonic() - time.time_ns() / 1e9  # kernel stamps are wall-clock: map them to monotonic
    for t_o_id in connection_ids:
        received = endpoint.since(t_o_id)
        for a, b in zip(received, received[1:]):
            if b.time_ns < start_ns or b.time_ns > end_ns:
                continue
            if pulls.overlaps(a.time_ns / 1e9 + offset, b.time_ns / 1e9 + offset):
                continue
            interval = (b.time_ns - a.time_ns) / 1000.0
            intervals.append(interval)
            if interval > timeout_us:
                gaps.append((t_o_id, interval))
    return intervals, gaps


# ---- Modbus --------------------------------------------------------------------------------------

class ModbusClient:
    def __init__(self):
        self.sock = None
        self.transaction = 0

    def exchange(self, unit, pdu):
        if self.sock is None:
            self.sock = socket.create_connection((CARD, 502), timeout=5.0)
            self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.transaction = (self.transaction + 1) & 0xFFFF
        try:
            self.sock.sendall(struct.pack(">HHHB", self.transaction, 0, len(pdu) + 1, unit) + pdu)
            header = self._exact(7)
            transaction, _, length, _ = struct.unpack(">HHHB", header)
            body = self._exact(length - 1)
        except OSError:
            self.close()
            raise
        if transaction != self.transaction:
            self.close()
            raise RuntimeError(f"Modbus transaction {transaction} for {self.transaction}")
        if body[0] & 0x80:
            raise RuntimeError(f"Modbus exception {body.hex()}")
        return body

    def _exact(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            if not chunk:
                raise ConnectionError("closed by the card")
            data += chunk
        return data

    def close(self):
        if self.sock is not None:
            self.sock.close()
        self.sock = None


class Scanner:
    """The IO scanner: FC 23 (write words 0-6, read words 0-6) every 10 ms; FA06 is word 1."""

    def __init__(self, pulls):
        self.pulls = pulls
        self.client = ModbusClient()
        self.fa06 = 0
        self.round_trips = []   # (monotonic start, end, µs)
        self.failures = []      # (monotonic, text) outside pulls
        self.stop_flag = False
        self.pause = threading.Event()  # set: no scan (a short pause, well below c523)
        self.thread = threading.Thread(target=self.run, name="scanner", daemon=True)

    def run(self):
        next_t = time.monotonic()
        while not self.stop_flag:
            if self.pause.is_set():
                time.sleep(0.005)
                next_t = time.monotonic()
                continue
            words = [0, self.fa06, 0, 0, 0, 0, 0]
            pdu = struct.pack(">BHHHHB", 0x17, 0, 7, 0, 7, 14) + struct.pack(">7H", *words)
            start = time.monotonic()
            try:
                body = self.client.exchange(255, pdu)
                if body[:2] != bytes([0x17, 14]) or len(body) != 16:
                    raise RuntimeError(f"FC 23 answer {body.hex()}")
                finished = time.monotonic()
                self.round_trips.append((start, finished, (finished - start) * 1e6))
            except (OSError, ConnectionError, RuntimeError) as error:
                if not self.pulls.overlaps(start, time.monotonic()):
                    self.failures.append((start, f"{type(error).__name__}: {error}"))
                time.sleep(0.2)
            next_t += 0.01
            time.sleep(max(0.0, next_t - time.monotonic()))
            if next_t < time.monotonic() - 0.1:
                next_t = time.monotonic()


class ModbusMisc:
    """Drive registers (over the serial link), the option board, the identity, acc written every 5 s."""

    def __init__(self):
        self.client = ModbusClient()
        self.turn = 0

    def step(self):
        self.turn += 1
        if self.turn % 100 == 0:
            self.client.exchange(1, struct.pack(">BHH", 0x06, 0x0009, 100 + self.turn // 100 % 2))
        elif self.turn % 4 == 0:
            self.client.exchange(1, struct.pack(">BHH", 0x03, 0x0009, 2))
        elif self.turn % 4 == 1:
            self.client.exchange(251, struct.pack(">BHH", 0x03, 0, 50))
        elif self.turn % 4 == 2:
            self.client.exchange(255, bytes([0x2B, 0x0E, 0x01, 0x00]))
        else:
            self.client.exchange(0, struct.pack(">BHH", 0x03, 0xFD00, 2))


# ---- The run -------------------------------------------------------------------------------------

def pool_usage(stats):
    """Usage counters that must not grow: lwIP memp "used", the heap, and every pool.* usage line."""
    usage = {}
    for key, value in stats.items():
        if (key.startswith("lwip.memp.") and key.endswith(".used")) or key == "lwip.mem.used" or \
                (key.startswith("pool.") and (key.endswith(".used") or key.endswith(".in_use"))):
            usage[key] = int(value)
    return usage


def short(key):
    return key.replace("lwip.memp.", "").replace(".used", "").replace("lwip.mem", "heap")


class Soak:
    """One card's run: the load, the fault schedule, the reports and the verdict."""

    def __init__(self, mode, seconds, report_every):
        self.mode, self.tag, self.report_every = mode, f"[{mode}]", report_every
        self.sim = SimControl(os.environ["CARD_CONTROL"])
        self.pulls = Pulls()
        self.problems = []
        self.web = Web()
        self.workers = [Worker("web", self.web.step, 0.1)]
        self.io = self.scanner = self.explicit = self.misc = None
        self.tcp_pcbs_idle = pool_usage(self.sim.stats()).get("lwip.memp.TCP_PCB.used", 0)
        if mode == "eip":
            self.io = EipIo(self.pulls)
            self.io.open()
            self.explicit = Explicit()
            self.workers.append(Worker("explicit", self.explicit.step, 0.02))
        else:
            self.scanner = Scanner(self.pulls)
            self.scanner.thread.start()
            self.misc = ModbusMisc()
            self.workers.append(Worker("modbus", self.misc.step, 0.02))
        for w in self.workers:
            w.start()
        self.start = time.monotonic()
        self.end = self.start + seconds
        self.next_pull = self.start + PULL_FIRST
        self.next_trip = self.start + TRIP_FIRST
        self.next_inject = self.start + INJECT_FIRST
        self.next_report = self.start + report_every
        self.pull_up_at = None
        self.trip = None  # [tripped at, last reset pulse at] while a trip waits for its reset
        self.counts = {"pulls": 0, "trips": 0, "resets": 0, "injects": 0}
        self.baseline = None
        self.above = {}
        self.reports = 0
        self.report_start_ns = time.time_ns()
        self.report_start = self.start
        self.missed_before = int(self.sim.stats().get("cip.missed_productions", 0))

    def at_rest(self):
        """The pools with the request loops paused: class 1 I/O keeps running (UDP holds nothing between
        passes); the IO scanner, a TCP client, pauses for the last 0.15 s only (c523 is 1 s), long enough for
        its last answer's acknowledgement."""
        for w in self.workers:
            w.pause.set()
        for w in self.workers:
            w.idle.wait(10.0)
        time.sleep(0.4)
        if self.scanner is not None:
            self.scanner.pause.set()
        time.sleep(0.15)
        usage = pool_usage(self.sim.stats())
        if self.scanner is not None:
            self.scanner.pause.clear()
        for w in self.workers:
            w.pause.clear()
        return usage

    def pulse_reset(self, on):
        if self.io is not None:
            self.io.set_fault_reset(on)
        else:
            self.scanner.fa06 = 0x2000 if on else 0

    def faults(self, now):
        """Cable pulls, trips and their resets, damaged serial replies, on their schedule."""
        if self.pull_up_at is None and now >= self.next_pull and now + PULL_SECONDS < self.end - 1:
            self.sim.command("link L down")
            self.pulls.down(time.monotonic())
            self.pull_up_at = now + PULL_SECONDS
            self.counts["pulls"] += 1
            self.next_pull += PULL_EVERY
        if self.pull_up_at is not None and now >= self.pull_up_at:
            self.sim.command("link L up")
            self.pulls.up(time.monotonic())
            self.pull_up_at = None
        if self.io is not None and self.pull_up_at is None and not self.io.alive():
            try:
                self.io.open()  # the card closed the connections when their O->T stopped
            except Exception as error:  # noqa: BLE001 - the link may need a moment: next turn
                print(f"{self.tag} reopen failed: {error}", flush=True)
                time.sleep(0.2)
        if self.trip is None and now >= self.next_trip:
            self.sim.command(f"trip {TRIP_CODE}", check=False)
            self.trip = [now, 0.0]
            self.counts["trips"] += 1
            self.next_trip += TRIP_EVERY
        if self.trip is not None and now - self.trip[0] >= 0.3:
            if now - self.trip[1] >= 1.5:
                self.pulse_reset(True)
                self.trip[1] = now
            elif now - self.trip[1] >= 0.2:
                self.pulse_reset(False)
            if int(self.sim.status()["trip"]) == 0:
                self.pulse_reset(False)
                self.trip = None
                self.counts["resets"] += 1
            elif now - self.trip[0] > 10.0 and not self.pulls.overlaps(self.trip[0], now):
                self.problems.append(f"trip of second {self.trip[0] - self.start:.0f} not reset within 10 s")
                self.trip = None
        if now >= self.next_inject:
            self.sim.command("inject corrupt 2")
            self.counts["injects"] += 1
            self.next_inject += INJECT_EVERY

    def io_line(self, stats, end_ns):
        if self.io is not None:
            with self.io.endpoint.lock:
                ids = set(self.io.endpoint.received.keys())
            owner_rpi, gaps_all, owner = RPI, [], []
            for t_o_id in ids:
                intervals, gaps = io_intervals(self.io.endpoint, [t_o_id], self.pulls, self.report_start_ns, end_ns,
                                               self.io.timeout_of.get(t_o_id, TIMEOUT_US))
                gaps_all += gaps
                if self.io.rpi_of.get(t_o_id) == owner_rpi:
                    owner += intervals
            for t_o_id, gap in gaps_all:
                self.problems.append(f"T->O gap of {gap:.0f} us on 0x{t_o_id:08X} beyond its timeout "
                                     f"{self.io.timeout_of.get(t_o_id)} us with the link up (report {self.reports})")
            missed_now = int(stats.get("cip.missed_productions", 0))
            line = (f"io 21/71 {len(owner)} T->O intervals p50 {percentile(owner, 50):.0f} us p99 "
                    f"{percentile(owner, 99):.0f} us max {max(owner, default=0):.0f} us (RPI {RPI}, jitter p99 "
                    f"{percentile(owner, 99) - RPI:+.0f} us), gaps beyond the timeout {len(gaps_all)}, card skipped "
                    f"slots +{missed_now - self.missed_before}, reopens {self.io.reopens - 1}")
            self.missed_before = missed_now
            return line
        window = [rt for t0, t1, rt in self.scanner.round_trips
                  if t0 >= self.report_start and not self.pulls.overlaps(t0, t1)]
        return (f"scans {len(window)} round trip p50 {percentile(window, 50):.0f} us p99 "
                f"{percentile(window, 99):.0f} us max {max(window, default=0):.0f} us (pulls left out), failed with "
                f"the link up {len(self.scanner.failures)}")

    def report(self, final=False):
        self.reports += 1
        usage = self.at_rest()
        for key, value in usage.items():
            self.above[key] = self.above.get(key, 0) + 1 if value > self.baseline.get(key, 0) else 0
            if self.above[key] == 3:
                self.problems.append(f"{key} above its baseline {self.baseline.get(key, 0)} in 3 reports in a row "
                                     f"({value})")
        pools = " ".join(f"{short(k)} {v}{'+' if v > self.baseline.get(k, 0) else ''}" for k, v in sorted(usage.items())
                         if v or self.baseline.get(k, 0))
        end_ns = time.time_ns()
        line = self.io_line(self.sim.stats(), end_ns)
        requests = " ".join(f"{w.name} {w.done}/{w.errors} err" for w in self.workers)
        print(f"{self.tag} {'final report' if final else 'report'} {self.reports} at "
              f"{time.monotonic() - self.start:.0f} s: pools {pools or 'all 0'} | {line} | {requests} | "
              + " ".join(f"{k} {v}" for k, v in self.counts.items()), flush=True)
        self.report_start_ns, self.report_start = end_ns, time.monotonic()

    def run(self):
        while time.monotonic() < self.end:
            now = time.monotonic()
            self.faults(now)
            if self.baseline is None and now >= self.start + 3.0:
                self.baseline = self.at_rest()  # before the first cable pull, trip or damaged reply
                print(f"{self.tag} baseline at rest: " +
                      " ".join(f"{short(k)} {v}" for k, v in sorted(self.baseline.items()) if v), flush=True)
            if self.baseline is not None and now >= self.next_report and self.pull_up_at is None and self.trip is None:
                self.report()
                self.next_report += self.report_every
            time.sleep(0.01)
        if self.pull_up_at is not None:
            self.sim.command("link L up")
            self.pulls.up(time.monotonic())
        if self.baseline is not None:
            self.report(final=True)
        self.finish()

    def finish(self):
        """The load stops (pools back to the baseline?), then every client closes (TCP PCBs back?)."""
        for w in self.workers:
            w.stop_flag = True
        for w in self.workers:
            w.join(10.0)
        if self.scanner is not None:
            self.scanner.stop_flag = True
            self.scanner.thread.join(5.0)
            for t, text in self.scanner.failures:
                self.problems.append(f"IO scan failed at second {t - self.start:.1f} with the link up: {text}")
        grown = {}
        deadline = time.monotonic() + 10.0
        while self.baseline is not None:
            usage = pool_usage(self.sim.stats())
            grown = {k: (self.baseline.get(k, 0), v) for k, v in usage.items() if v > self.baseline.get(k, 0)}
            if not grown or time.monotonic() > deadline:
                break
            time.sleep(0.5)
        for key, (was, value) in grown.items():
            self.problems.append(f"{key} {value} above its baseline {was} at the end")
        if self.io is not None:
            self.io.close()
            self.explicit.close()
        else:
            self.scanner.client.close()
            self.misc.client.close()
        self.web.close()
        pcbs, deadline = 0, time.monotonic() + 10.0
        while time.monotonic() < deadline:
            pcbs = pool_usage(self.sim.stats()).get("lwip.memp.TCP_PCB.used", 0)
            if pcbs <= self.tcp_pcbs_idle:
                break
            time.sleep(0.5)
        else:
            self.problems.append(f"TCP PCBs {pcbs} after every client closed, {self.tcp_pcbs_idle} before the load")
        errors = "; ".join(f"{w.name}: {w.last_error}" for w in self.workers if w.errors)
        print(f"{self.tag} done after {time.monotonic() - self.start:.0f} s: " +
              " ".join(f"{k} {v}" for k, v in self.counts.items()) +
              (f"; request errors (during pulls and trips): {errors}" if errors else ""), flush=True)
        for problem in self.problems:
            print(f"{self.tag} FAIL: {problem}", file=sys.stderr, flush=True)
        return 1 if self.problems else 0


def main(argv):
    if len(argv) != 4 or argv[1] not in ("eip", "modbus"):
        print(__doc__, file=sys.stderr)
        return 2
    soak = Soak(argv[1], float(argv[2]), float(argv[3]))
    soak.run()
    return 1 if soak.problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
