#!/usr/bin/python3
"""CIP connections for the integration tests: what eip_originator.py lacks to be a scanner.

Standard library only, built on eip_originator (encapsulation, SendRRData, message router requests):

- Forward_Open 0x54 / Large_Forward_Open 0x5B / Forward_Close 0x4E request encoders (network connection
  parameters, transport class/trigger, connection paths with an electronic key, configuration, consumed
  and produced points), the success and failure reply layouts of docs/connections.md as exact bytes, and
  `open_connection` which sends one over SendRRData and returns every CPF item of the reply (the T->O
  socket address item 0x8001 of a multicast connection included).
- `IoEndpoint`: class 1 I/O on UDP 2222. One socket bound to 0.0.0.0:2222 and one thread running a select
  loop: every `IoConnection` it holds sends its O->T datagram at its RPI (sequenced address item with the
  32-bit encapsulation sequence number, connected data item with the 16-bit CIP sequence count, the
  32-bit run/idle header unless it is a heartbeat without one, and the data); every T->O datagram is
  recorded with the kernel's receive time (SO_TIMESTAMPNS), its destination address (IP_PKTINFO: a
  multicast group or our address), both sequence numbers and the data. Productions of a multicast group
  are received after `join(group)`.
- `ExplicitConnection`: class 3 requests over SendUnitData (connected address + connected data items).
- `SimControl`: one persistent connection to the card's control socket (the simulated inverter's `get`,
  `set`, `trip`, `status` and the card's `stats`), fast enough to poll the drive every millisecond.

Every decoder reads through eip_originator.Reader (ProtocolError rather than read past the end).
"""
import json
import re
import select
import socket
import struct
import threading
import time

from eip_originator import (ITEM_CONNECTED_ADDRESS, ITEM_CONNECTED_DATA, ITEM_NULL, ITEM_SOCKADDR_T_O,
                            ITEM_UNCONNECTED_DATA, SEND_RR_DATA, SEND_UNIT_DATA, ENCAP_SUCCESS, ProtocolError,
                            Reader, decode_cpf, decode_mr_reply, decode_send_rr_data, encode, encode_cpf, epath,
                            hexs, logical_segment, mr_request, send_rr_data_body)

IO_PORT = 2222
FORWARD_OPEN = 0x54
LARGE_FORWARD_OPEN = 0x5B
FORWARD_CLOSE = 0x4E
ITEM_SEQUENCED_ADDRESS = 0x8002

# Network connection parameters: connection types and priorities.
TYPE_NULL, TYPE_MULTICAST, TYPE_P2P, TYPE_RESERVED = 0, 1, 2, 3
PRIORITY_LOW, PRIORITY_HIGH, PRIORITY_SCHEDULED, PRIORITY_URGENT = 0, 1, 2, 3

# Transport class/trigger bytes.
CLASS1_CYCLIC = 0x01
CLASS3_SERVER_APPLICATION = 0xA3  # direction server, application object trigger, class 3 (as Logix sends)

ROUTER_PATH = bytes.fromhex("20 02 24 01")

# Linux socket options Python does not name.
SO_TIMESTAMPNS = 35
IP_PKTINFO = 8


def net_params(size, kind=TYPE_P2P, priority=PRIORITY_SCHEDULED, variable=False, redundant=False, large=False):
    """Network connection parameters: 16-bit (Forward_Open) or 32-bit (Large_Forward_Open)."""
    if large:
        return (redundant << 31) | (kind << 29) | (priority << 26) | (variable << 25) | (size & 0xFFFF)
    return (redundant << 15) | (kind << 13) | (priority << 10) | (variable << 9) | (size & 0x1FF)


def electronic_key(vendor=377, device_type=2, product=32000, major=1, minor=8, compatible=False):
    """Electronic key segment, format 4."""
    return bytes([0x34, 0x04]) + struct.pack("<HHH", vendor, device_type, product) + bytes(
        [major | (0x80 if compatible else 0), minor])


def io_path(consumed, produced, configuration=1, key=b"", data=None):
    """Connection path of a class 1 connection: [key] class 4, configuration instance, the consumed (O->T)
    and produced (T->O) connection points, [simple data segment]."""
    path = bytes(key) + logical_segment(0, 0x04)
    if configuration is not None:
        path += logical_segment(1, configuration)
    path += logical_segment(3, consumed) + logical_segment(3, produced)
    if data is not None:
        path += bytes([0x80, len(data) // 2]) + bytes(data)
    return path


class Triad:
    """Connection serial number, originator vendor ID, originator serial number."""

    def __init__(self, serial, vendor=0x1234, originator=0x0A0B0C0D):
        self.serial, self.vendor, self.originator = serial, vendor, originator

    def bytes(self):
        return struct.pack("<HHI", self.serial, self.vendor, self.originator)

    def __repr__(self):
        return f"Triad(0x{self.serial:04X}, 0x{self.vendor:04X}, 0x{self.originator:08X})"


def forward_open(triad, path, o_t_rpi, o_t_params, t_o_rpi, t_o_params, transport=CLASS1_CYCLIC, t_o_id=0,
                 o_t_id=0, multiplier=0, large=False, priority_tick=0x0A, timeout_ticks=0x0E):
    """The message router request of a Forward_Open (or Large_Forward_Open) to the Connection Manager."""
    params = "<I" if large else "<H"
    data = struct.pack("<BBII", priority_tick, timeout_ticks, o_t_id, t_o_id) + triad.bytes()
    data += struct.pack("<B3x", multiplier)
    data += struct.pack("<I", o_t_rpi) + struct.pack(params, o_t_params)
    data += struct.pack("<I", t_o_rpi) + struct.pack(params, t_o_params)
    data += bytes([transport, len(path) // 2]) + bytes(path)
    return mr_request(LARGE_FORWARD_OPEN if large else FORWARD_OPEN, epath(0x06, 1), data)


def forward_close(triad, path, priority_tick=0x0A, timeout_ticks=0x0E):
    data = bytes([priority_tick, timeout_ticks]) + triad.bytes() + bytes([len(path) // 2, 0]) + bytes(path)
    return mr_request(FORWARD_CLOSE, epath(0x06, 1), data)


def open_success_bytes(o_t_id, t_o_id, triad, o_t_api, t_o_api, service=FORWARD_OPEN):
    """The whole message router reply of a successful Forward_Open (26 bytes of data)."""
    return bytes([service | 0x80, 0, 0, 0]) + struct.pack("<II", o_t_id, t_o_id) + triad.bytes() + struct.pack(
        "<II", o_t_api, t_o_api) + b"\x00\x00"


def refused_bytes(triad, additional_words, remaining_words=0, service=FORWARD_OPEN):
    """A refused Forward_Open/Forward_Close: general status 0x01, the additional status words (the extended
    status first), the triad, remaining path size, reserved."""
    words = list(additional_words)
    return bytes([service | 0x80, 0, 0x01, len(words)]) + b"".join(struct.pack("<H", w) for w in words) + \
        triad.bytes() + bytes([remaining_words, 0])


def rpi_refusal_words(extended, o_t_type, t_o_type, o_t_rpi, t_o_rpi):
    """Additional status of 0x0111/0x0112: types word (O->T low byte), then both RPIs (two words each)."""
    return [extended, o_t_type | (t_o_type << 8), o_t_rpi & 0xFFFF, o_t_rpi >> 16, t_o_rpi & 0xFFFF,
            t_o_rpi >> 16]


def close_success_bytes(triad):
    return bytes([FORWARD_CLOSE | 0x80, 0, 0, 0]) + triad.bytes() + b"\x00\x00"


def decode_open_success(data):
    r = Reader(data, "Forward_Open reply")
    reply = {"o_t_id": r.u32(), "t_o_id": r.u32(), "triad": r.take(8), "o_t_api": r.u32(), "t_o_api": r.u32(),
             "application_size": r.u8(), "reserved": r.u8()}
    r.end()
    return reply


def decode_sockaddr(data):
    """A socket address item (big-endian): (family, port, address text); the 8 zero bytes must be zero."""
    r = Reader(data, "socket address item")
    family = struct.unpack(">H", r.take(2))[0]
    port = struct.unpack(">H", r.take(2))[0]
    address = socket.inet_ntoa(r.take(4))
    zero = r.take(8)
    r.end()
    if zero != bytes(8):
        raise ProtocolError(f"socket address item: sin_zero {hexs(zero)}")
    return family, port, address


def open_connection(client, request):
    """Sends a Forward_Open/Forward_Close (or any request) over SendRRData. Returns (message router reply,
    raw reply bytes, items after the unconnected data item) and checks the first two items' types."""
    reply = client.request(SEND_RR_DATA, send_rr_data_body(request))
    if reply.status != ENCAP_SUCCESS:
        raise ProtocolError(f"SendRRData answered with encapsulation status 0x{reply.status:04X}")
    _, _, items = decode_send_rr_data(reply.data)
    if len(items) < 2 or items[0] != (ITEM_NULL, b"") or items[1][0] != ITEM_UNCONNECTED_DATA:
        raise ProtocolError(f"SendRRData reply items {items}")
    mr = decode_mr_reply(items[1][1])
    return mr, items[1][1], items[2:]


# ---- Class 1 datagrams ---------------------------------------------------------------------------

def encode_io(connection_id, encap_sequence, cip_sequence, data, header=None):
    payload = struct.pack("<H", cip_sequence & 0xFFFF)
    if header is not None:
        payload += struct.pack("<I", header)
    payload += bytes(data)
    return encode_cpf([(ITEM_SEQUENCED_ADDRESS, struct.pack("<II", connection_id, encap_sequence & 0xFFFFFFFF)),
                       (ITEM_CONNECTED_DATA, payload)])


def decode_io(datagram):
    """(connection ID, encapsulation sequence, CIP sequence count, data) of a T->O datagram (modeless)."""
    items = decode_cpf(datagram)
    if len(items) != 2 or items[0][0] != ITEM_SEQUENCED_ADDRESS or items[1][0] != ITEM_CONNECTED_DATA:
        raise ProtocolError(f"class 1 datagram items {[(hex(t), hexs(d)) for t, d in items]}")
    r = Reader(items[0][1], "sequenced address item")
    connection_id, sequence = r.u32(), r.u32()
    r.end()
    r = Reader(items[1][1], "connected data item")
    count = r.u16()
    return connection_id, sequence, count, r.rest()


class Received:
    __slots__ = ("time_ns", "encap_sequence", "cip_sequence", "data", "destination", "source")

    def __init__(self, time_ns, encap_sequence, cip_sequence, data, destination, source):
        self.time_ns, self.encap_sequence, self.cip_sequence = time_ns, encap_sequence, cip_sequence
        self.data, self.destination, self.source = data, destination, source


class IoConnection:
    """The originator's side of one class 1 connection: what it sends and at which RPI."""

    def __init__(self, o_t_id, t_o_id, rpi_us, data=b"", run=True, header=True, name="connection"):
        self.o_t_id, self.t_o_id, self.rpi_ns = o_t_id, t_o_id, rpi_us * 1000
        self.data, self.run, self.header, self.name = bytes(data), run, header, name
        self.sending = True
        self.encap_sequence = 0
        self.cip_sequence = 0
        self.next_ns = None
        self.sent = 0
        self.last_sent = None       # time.monotonic() just before the last O->T datagram was sent
        self.changed_sent = None    # time.monotonic() before the first datagram sent after the last set()
        self.changed = False


class IoEndpoint:
    """UDP 2222: sends the O->T data of every connection at its RPI and records every T->O datagram."""

    def __init__(self, card_ip, bind="0.0.0.0", port=IO_PORT):
        self.card = (card_ip, port)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        self.sock.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMPNS, 1)
        self.sock.setsockopt(socket.IPPROTO_IP, IP_PKTINFO, 1)
        self.sock.bind((bind, port))
        self.sock.setblocking(False)
        self.lock = threading.Lock()
        self.connections = []
        self.received = {}          # T->O connection ID -> [Received]
        self.errors = []            # datagrams that did not decode
        self.stop_flag = False
        self.send_errors = 0
        self.thread = threading.Thread(target=self._run, name="io-endpoint", daemon=True)
        self.thread.start()

    def close(self):
        self.stop_flag = True
        self.thread.join(2.0)
        self.sock.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- connections

    def add(self, connection):
        with self.lock:
            self.received.setdefault(connection.t_o_id, [])
            self.connections.append(connection)
        return connection

    def remove(self, connection):
        with self.lock:
            if connection in self.connections:
                self.connections.remove(connection)

    def set(self, connection, data=None, run=None):
        """New O->T data / run-idle state, sent from the next RPI slot on (with a new CIP sequence count)."""
        with self.lock:
            if data is not None:
                connection.data = bytes(data)
            if run is not None:
                connection.run = run
            connection.changed = True

    def stop_sending(self, connection):
        """Stops the O->T datagrams; returns time.monotonic() of the last one sent."""
        with self.lock:
            connection.sending = False
            return connection.last_sent

    def join(self, group, interface):
        mreq = socket.inet_aton(group) + socket.inet_aton(interface)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, mreq)

    def leave(self, group, interface):
        mreq = socket.inet_aton(group) + socket.inet_aton(interface)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_DROP_MEMBERSHIP, mreq)

    # -- what arrived

    def count(self, t_o_id):
        with self.lock:
            return len(self.received.get(t_o_id, []))

    def since(self, t_o_id, start=0):
        with self.lock:
            return list(self.received.get(t_o_id, [])[start:])

    def latest(self, t_o_id):
        with self.lock:
            got = self.received.get(t_o_id, [])
            return got[-1] if got else None

    def wait_data(self, t_o_id, want, limit):
        """Waits until the newest T->O data of t_o_id is `want`; returns (True, data) or (False, newest)."""
        deadline = time.monotonic() + limit
        while True:
            newest = self.latest(t_o_id)
            if newest is not None and newest.data == want:
                return True, newest.data
            if time.monotonic() > deadline:
                return False, None if newest is None else newest.data
            time.sleep(0.002)

    def wait_count(self, t_o_id, count, limit):
        deadline = time.monotonic() + limit
        while self.count(t_o_id) < count:
            if time.monotonic() > deadline:
                return False
            time.sleep(0.005)
        return True

    # -- the loop

    def _send(self, c):
        if c.changed:
            c.changed = False
            c.changed_sent = None
        c.encap_sequence = (c.encap_sequence + 1) & 0xFFFFFFFF
        c.cip_sequence = (c.cip_sequence + 1) & 0xFFFF
        header = (1 if c.run else 0) if c.header else None
        datagram = encode_io(c.o_t_id, c.encap_sequence, c.cip_sequence, c.data, header)
        before = time.monotonic()  # taken before the send: the card cannot have the datagram earlier
        try:
            self.sock.sendto(datagram, self.card)
        except OSError:
            self.send_errors += 1
            return
        c.sent += 1
        c.last_sent = before
        if c.changed_sent is None:
            c.changed_sent = c.last_sent

    def _receive_all(self):
        while True:
            try:
                data, ancillary, _, source = self.sock.recvmsg(2048, 256)
            except BlockingIOError:
                return
            except OSError:
                return
            stamp, destination = time.time_ns(), None
            for level, kind, value in ancillary:
                if level == socket.SOL_SOCKET and kind == SO_TIMESTAMPNS and len(value) >= 16:
                    seconds, nanoseconds = struct.unpack_from("<qq", value)
                    stamp = seconds * 1_000_000_000 + nanoseconds
                elif level == socket.IPPROTO_IP and kind == IP_PKTINFO and len(value) >= 12:
                    destination = socket.inet_ntoa(value[8:12])
            try:
                connection_id, sequence, count, payload = decode_io(data)
            except ProtocolError as error:
                with self.lock:
                    self.errors.append((source, hexs(data), str(error)))
                continue
            with self.lock:
                self.received.setdefault(connection_id, []).append(
                    Received(stamp, sequence, count, payload, destination, source))

    def _run(self):
        while not self.stop_flag:
            now = time.monotonic_ns()
            wake = now + 20_000_000
            with self.lock:
                for c in self.connections:
                    if not c.sending:
                        continue
                    if c.next_ns is None:
                        c.next_ns = now
                    if now >= c.next_ns:
                        self._send(c)
                        c.next_ns += c.rpi_ns
                        if c.next_ns <= now:  # late by a whole period: the next slot after now
                            c.next_ns = now + c.rpi_ns - (now - c.next_ns) % c.rpi_ns
                    wake = min(wake, c.next_ns)
            timeout = max(0, wake - time.monotonic_ns()) / 1e9
            try:
                ready, _, _ = select.select([self.sock], [], [], timeout)
            except (OSError, ValueError):
                return
            if ready:
                self._receive_all()


def interval_stats(received):
    """Intervals (µs) between consecutive T->O datagrams, and their mean, p50, p99, max."""
    times = [r.time_ns for r in received]
    intervals = [(b - a) / 1000.0 for a, b in zip(times, times[1:])]
    if not intervals:
        return intervals, {"n": 0}
    ordered = sorted(intervals)

    def pct(p):
        return ordered[min(len(ordered) - 1, int(round(p / 100.0 * (len(ordered) - 1))))]

    return intervals, {"n": len(intervals), "mean": sum(intervals) / len(intervals), "p50": pct(50),
                       "p99": pct(99), "max": ordered[-1], "min": ordered[0]}


def sequence_steps(received):
    """The steps between consecutive encapsulation sequence numbers and CIP sequence counts."""
    encap = [(b.encap_sequence - a.encap_sequence) & 0xFFFFFFFF for a, b in zip(received, received[1:])]
    cip = [(b.cip_sequence - a.cip_sequence) & 0xFFFF for a, b in zip(received, received[1:])]
    return encap, cip


# ---- Class 3 ---------------------------------------------------------------------------------------

class ExplicitConnection:
    """Class 3 messages over SendUnitData on an eip_originator.Client with a session."""

    def __init__(self, client, o_t_id, t_o_id):
        self.client, self.o_t_id, self.t_o_id = client, o_t_id, t_o_id

    def body(self, sequence, request, connection_id=None):
        cid = self.o_t_id if connection_id is None else connection_id
        return struct.pack("<IH", 0, 0) + encode_cpf([(ITEM_CONNECTED_ADDRESS, struct.pack("<I", cid)),
                                                      (ITEM_CONNECTED_DATA, struct.pack("<H", sequence) + request)])

    def request(self, sequence, request, wait=None, connection_id=None):
        """(T->O connection ID, sequence count, message router reply bytes), or None when nothing comes."""
        self.client.send(encode(SEND_UNIT_DATA, self.body(sequence, request, connection_id), self.client.session,
                                self.client.context))
        reply = self.client.receive(wait)
        if reply is None:
            return None
        if reply.command != SEND_UNIT_DATA or reply.status != ENCAP_SUCCESS:
            raise ProtocolError(f"SendUnitData reply {reply}")
        r = Reader(reply.data, "SendUnitData reply")
        handle, timeout = r.u32(), r.u16()
        items = decode_cpf(r.rest())
        if handle != 0 or timeout != 0 or len(items) != 2 or items[0][0] != ITEM_CONNECTED_ADDRESS or \
                items[1][0] != ITEM_CONNECTED_DATA or len(items[0][1]) != 4:
            raise ProtocolError(f"SendUnitData reply items {items}")
        connection_id = struct.unpack("<I", items[0][1])[0]
        r = Reader(items[1][1], "connected data item")
        count = r.u16()
        return connection_id, count, r.rest()


# ---- The simulated inverter's control socket ------------------------------------------------------

class SimControl:
    """One connection to the card's control socket; every command answers lines ending in ok/error."""

    def __init__(self, path, timeout=10.0):
        self.path = path
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.settimeout(timeout)
        self.sock.connect(path)
        self.buffer = b""

    def close(self):
        self.sock.close()

    def command(self, line, check=True):
        self.sock.sendall(line.encode() + b"\n")
        lines = []
        while True:
            while b"\n" not in self.buffer:
                chunk = self.sock.recv(65536)
                if not chunk:
                    raise ProtocolError(f"control socket closed during '{line}'")
                self.buffer += chunk
            text, self.buffer = self.buffer.split(b"\n", 1)
            text = text.decode(errors="replace")
            if text == "ok":
                return lines
            if text.startswith("error"):
                if check:
                    raise ProtocolError(f"control '{line}': {text}")
                return lines + [text]
            lines.append(text)

    def status(self):
        lines = self.command("status")
        return json.loads(lines[0])

    def get(self, name):
        lines = self.command(f"get {name}")
        m = re.match(r"\S+ = (-?\d+) ", lines[0])
        if not m:
            raise ProtocolError(f"get {name}: {lines}")
        return int(m.group(1))

    def set(self, name, value):
        return self.command(f"set {name} {value}")

    def stats(self):
        out = {}
        for line in self.command("stats"):
            if "=" in line:
                key, value = line.split("=", 1)
                out[key] = value
        return out

    def config(self):
        out = {}
        for line in self.command("config"):
            if "=" in line:
                key, value = line.split("=", 1)
                out.setdefault(key, value)
        return out
