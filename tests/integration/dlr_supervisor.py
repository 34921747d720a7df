#!/usr/bin/python3
"""A scripted DLR ring supervisor for the ring tests (docs/network.md "Ring (DLR)").

Standard library only: raw AF_PACKET sockets on the two host-side ports of the ring (the card's tapL and
tapR), one thread running a select loop. It does what a beacon-based ring supervisor does, as far as a
test needs:

- sends a Beacon out of each of its two ports every `interval_us` (ring state, precedence, interval and
  timeout in the frame), with its own sequence ids;
- watches its own beacons come back on the other port: a beacon not back within the beacon timeout of
  being sent = ring FAULT; beacons sent since the fault back in both directions = NORMAL. Judged by send
  times and after reading what has arrived, so a supervisor thread the host kept waiting does not see a
  fault that is not there. A Link_Status from a node is a fault at once (the fast path);
- on every change of state calls `on_state(state)` (the test blocks or unblocks its second port for
  ordinary traffic there) and sends Flush_Tables (learning update enabled) out of both ports;
- answers the Neighbor_Check requests of its neighbours on the port they came in on (unless told not to,
  to see a node's Neighbor_Status);
- sends Neighbor_Check requests, Locate_Fault and Sign_On on request, and records the DLR frames it
  receives (Neighbor_Check responses, Link_Status/Neighbor_Status, Learning_Update, Sign_On) with the port
  it came in on and the kernel's receive time.

Frames it sends carry an 802.1Q tag (VLAN 0, priority 7). The kernel hands received frames over without
their tag (it keeps tags out of band); `parse` accepts both.

Layouts (after the EtherType 0x80E1): ring subtype 0x02, protocol version 1, frame type, source port,
source IP (4), sequence id (4, big-endian), then the frame type's fields; every message has 30 bytes
after the common header. Destinations: 01-21-6C-00-00-01 Beacon, -02 Neighbor_Check and Sign_On,
-03 Announce, Locate_Fault and Flush_Tables, -05 Learning_Update.
"""
import collections
import ctypes
import queue
import select
import socket
import struct
import sys
import threading
import time

ETH_P_ALL = 0x0003
SO_ATTACH_FILTER = 26
SO_TIMESTAMPNS = 35  # not exported by Python's socket module
ETHERTYPE_DLR = 0x80E1
ETHERTYPE_VLAN = 0x8100
BEACON_MAC = bytes.fromhex("01216c000001")
NEIGHBOR_MAC = bytes.fromhex("01216c000002")
ANNOUNCE_MAC = bytes.fromhex("01216c000003")
LEARNING_MAC = bytes.fromhex("01216c000005")

BEACON, NEIGHBOR_REQUEST, NEIGHBOR_RESPONSE, LINK_STATUS, LOCATE_FAULT, ANNOUNCE, SIGN_ON, ADVERTISE, \
    FLUSH_TABLES, LEARNING_UPDATE = range(1, 11)
NAMES = {BEACON: "beacon", NEIGHBOR_REQUEST: "neighbor_check_request", NEIGHBOR_RESPONSE:
         "neighbor_check_response", LINK_STATUS: "link_status", LOCATE_FAULT: "locate_fault", ANNOUNCE: "announce",
         SIGN_ON: "sign_on", ADVERTISE: "advertise", FLUSH_TABLES: "flush_tables",
         LEARNING_UPDATE: "learning_update"}
RING_NORMAL, RING_FAULT = 1, 2
FLOOD_SOURCE = "02:00:00:ba:d0:01"  # the flood's frames come from this MAC
PAYLOAD_AFTER_HEADER = 30


def mac_text(mac):
    return ":".join(f"{b:02x}" for b in mac)


def mac_bytes(text):
    return bytes.fromhex(text.replace(":", ""))


class DlrFrame:
    """One received DLR frame: the Ethernet addresses, the common header and the raw fields after it."""

    def __init__(self, port, time_ns, destination, source, tagged, kind, source_port, source_ip, sequence, body):
        self.port, self.time_ns = port, time_ns
        self.destination, self.source, self.tagged = destination, source, tagged
        self.kind, self.source_port, self.source_ip, self.sequence, self.body = \
            kind, source_port, source_ip, sequence, body

    def __repr__(self):
        return (f"DlrFrame({NAMES.get(self.kind, self.kind)} on {self.port} from {mac_text(self.source)} "
                f"to {mac_text(self.destination)} port={self.source_port} ip={socket.inet_ntoa(self.source_ip)} "
                f"seq={self.sequence} body={self.body.hex()})")


def parse(frame, port=None, time_ns=0):
    """The DLR frame in `frame` (with or without one 802.1Q tag), or None for any other frame.

    Raises ValueError for a DLR frame too short for its common header and the 30 bytes every message has."""
    if len(frame) < 14:
        return None
    destination, source = frame[0:6], frame[6:12]
    ethertype = struct.unpack_from(">H", frame, 12)[0]
    offset, tagged = 14, False
    if ethertype == ETHERTYPE_VLAN:
        if len(frame) < 18:
            return None
        ethertype = struct.unpack_from(">H", frame, 16)[0]
        offset, tagged = 18, True
    if ethertype != ETHERTYPE_DLR:
        return None
    payload = frame[offset:]
    if len(payload) < 12 + PAYLOAD_AFTER_HEADER:
        raise ValueError(f"DLR frame of {len(payload)} payload bytes: {frame.hex()}")
    subtype, version, kind, source_port = payload[0], payload[1], payload[2], payload[3]
    if subtype != 0x02 or version != 1:
        raise ValueError(f"DLR frame with subtype {subtype} version {version}")
    sequence = struct.unpack_from(">I", payload, 8)[0]
    return DlrFrame(port, time_ns, destination, source, tagged, kind, source_port, payload[4:8], sequence,
                    payload[12:])


def build(destination, source, kind, source_port, source_ip, sequence, fields=b"", tagged=True):
    """A DLR frame: Ethernet header (802.1Q VLAN 0 priority 7 when tagged), common header, fields padded
    with zeros to the 30 bytes every message has (longer fields, a long Sign_On list, are kept)."""
    body = fields + bytes(max(0, PAYLOAD_AFTER_HEADER - len(fields)))
    header = destination + source
    if tagged:
        header += struct.pack(">HH", ETHERTYPE_VLAN, 0xE000)
    header += struct.pack(">H", ETHERTYPE_DLR)
    return header + bytes([0x02, 1, kind, source_port]) + socket.inet_aton(source_ip) + \
        struct.pack(">I", sequence) + body


def _dlr_filter(ignore_source=None):
    """A classic BPF program (and the buffer it lives in) for the supervisor's sockets: DLR frames only
    (EtherType 0x80E1 at offset 12: the kernel hands a tag over out of band); with `ignore_source`, none from
    that MAC and no Neighbor_Check response (frame type 3 at offset 16) either."""
    def op(code, jt, jf, k):
        return struct.pack("HBBI", code, jt, jf, k)
    drop, accept = op(0x06, 0, 0, 0), op(0x06, 0, 0, 0x40000)
    if ignore_source is None:
        program = [op(0x28, 0, 0, 12), op(0x15, 0, 1, ETHERTYPE_DLR), accept, drop]
    else:
        program = [
            op(0x28, 0, 0, 12),                                         # 0: A = EtherType
            op(0x15, 0, 7, ETHERTYPE_DLR),                              # 1: not DLR -> 9 (drop)
            op(0x20, 0, 0, 6),                                          # 2: A = source MAC, high 4 bytes
            op(0x15, 0, 2, int.from_bytes(ignore_source[:4], "big")),   # 3: other -> 6
            op(0x28, 0, 0, 10),                                         # 4: A = source MAC, low 2 bytes
            op(0x15, 3, 0, int.from_bytes(ignore_source[4:], "big")),   # 5: ignored source -> 9 (drop)
            op(0x30, 0, 0, 16),                                         # 6: A = DLR frame type
            op(0x15, 1, 0, NEIGHBOR_RESPONSE),                          # 7: a response -> 9 (drop)
            accept,                                                     # 8
            drop,                                                       # 9
        ]
    code = b"".join(program)
    buffer = ctypes.create_string_buffer(code)
    return struct.pack("HL", len(program), ctypes.addressof(buffer)), buffer


def beacon_fields(ring_state, precedence, interval_us, timeout_us):
    return struct.pack(">BBII", ring_state, precedence, interval_us, timeout_us)


class RingSupervisor:
    """The supervisor on two interfaces, `ports` = (name of port 1, name of port 2)."""

    def __init__(self, ports, mac, ip, interval_us=2000, timeout_us=None, precedence=200, on_state=None,
                 ignore_source=None):
        self.ports = ports
        self.mac = mac_bytes(mac) if isinstance(mac, str) else mac
        self.ip = ip
        self.interval_us = interval_us
        self.timeout_us = timeout_us if timeout_us is not None else 4 * interval_us
        self.precedence = precedence
        self.on_state = on_state
        self.state = RING_FAULT
        self.transitions = []      # (time_ns, state, reason)
        # The latest DLR frames received that the supervisor did not send itself (beacons of others are
        # only counted): bounded, so that a flood cannot grow it.
        self.received = collections.deque(maxlen=4096)
        self.foreign_beacons = 0
        self.answer_neighbor_checks = [True, True]  # per port: answer a node's Neighbor_Check requests
        # True: beacons say FAULT whatever the supervisor sees, and nothing is (un)blocked: a supervisor
        # that has found a partial fault (beacons lost in one direction only) and looks for it.
        self.announce_fault = False
        # True: state changes are recorded, announced and flushed, but the ports are left as they are (a
        # flood that delays beacons in the host's FIFO must not make the test open a loop).
        self.hold_ports = False
        self.beacons_back = [0, 0]  # own beacons that came back in on port i (sent out of the other one)
        self.beacons_sent = 0
        self.max_beacon_gap_us = 0  # the longest time between two beacons out of port 1 (send jitter)
        self.actions = 0
        self._sequence = 1
        # Beacon rounds sent (send time, sequence out of port 1, out of port 2), newest last: bounded, a
        # timeout's worth and more at any interval a test uses.
        self._rounds = collections.deque(maxlen=1024)
        self._sent_ns = {}            # beacon sequence -> its round's send time, for the rounds above
        self._back_sent_ns = [0, 0]   # send time of the newest own beacon back in on port i
        self._fault_ns = 0            # when the ring last went to FAULT
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._sockets = []
        # Every frame of the port (a socket for one protocol would not see what a bridge port takes in),
        # filtered in the kernel to DLR frames, and with `ignore_source` without that MAC's frames and
        # Neighbor_Check responses: in the flood test the supervisor must not spend the machine's CPU (nor
        # the card's, which pays for each copy when it writes) on the flood.
        self._filter = _dlr_filter(mac_bytes(ignore_source) if ignore_source else None)
        for name in ports:
            s = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETH_P_ALL))
            s.setsockopt(socket.SOL_SOCKET, SO_ATTACH_FILTER, self._filter[0])
            s.bind((name, 0))
            s.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMPNS, 1)
            s.setblocking(False)
            self._sockets.append(s)
        self._thread = threading.Thread(target=self._run, name="dlr-supervisor", daemon=True)
        # on_state runs in a thread of its own: blocking a port takes a few milliseconds of `ip` commands,
        # which must not hold the beacons back.
        self._actions = queue.Queue()
        self._worker = threading.Thread(target=self._act, name="dlr-supervisor-actions", daemon=True)

    # --- control ----------------------------------------------------------------------------------
    def start(self):
        self._worker.start()
        self._thread.start()
        return self

    def stop(self):
        self._stop.set()
        self._thread.join(5)
        self._actions.put(None)
        self._worker.join(10)
        for s in self._sockets:
            s.close()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()

    def next_sequence(self):
        with self._lock:
            self._sequence += 1
            return self._sequence

    def send(self, port, destination, kind, fields=b"", source_port=None, tagged=True):
        """Sends one DLR frame out of port index `port` (0 or 1); returns its sequence id."""
        sequence = self.next_sequence()
        frame = build(destination, self.mac, kind, port + 1 if source_port is None else source_port, self.ip,
                      sequence, fields, tagged)
        self._sockets[port].send(frame)
        return sequence

    def flush_tables(self, learning_update=True):
        for port in (0, 1):
            self.send(port, ANNOUNCE_MAC, FLUSH_TABLES, bytes([1 if learning_update else 0]))

    def frames(self, kind=None, port=None, since_ns=0):
        with self._lock:
            return [f for f in list(self.received) if (kind is None or f.kind == kind) and
                    (port is None or f.port == port) and f.time_ns >= since_ns]

    def wait_frame(self, kind, port=None, since_ns=0, limit=2.0, match=None):
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            for f in self.frames(kind, port, since_ns):
                if match is None or match(f):
                    return f
            time.sleep(0.002)
        return None

    def wait_state(self, state, limit=2.0):
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            if self.state == state:
                return True
            time.sleep(0.002)
        return False

    # --- the loop ---------------------------------------------------------------------------------
    def _set_state(self, state, reason):
        if state == self.state:
            return
        self.state = state
        now = time.monotonic_ns()
        if state == RING_FAULT:
            self._fault_ns = now  # the ring closes again only with beacons sent since
        self.transitions.append((now, state, reason))
        self._actions.put(state)

    def _act(self):
        while True:
            state = self._actions.get()
            if state is None:
                return
            if self.on_state is not None and not self.hold_ports:
                self.on_state(state)
            # After the port is (un)blocked: the nodes forget where stations were and learn them anew.
            self.flush_tables(True)

    def _send_beacons(self):
        state = RING_FAULT if self.announce_fault else self.state
        fields = beacon_fields(state, self.precedence, self.interval_us, self.timeout_us)
        now = time.monotonic_ns()
        sequences = []
        for port in (0, 1):
            try:
                sequences.append(self.send(port, BEACON_MAC, BEACON, fields))
            except OSError:
                sequences.append(None)  # a port without carrier: the beacon is lost, as on a cut cable
        if len(self._rounds) == self._rounds.maxlen:
            for old in self._rounds[0][1:]:
                self._sent_ns.pop(old, None)
        self._rounds.append((now, *sequences))
        for sequence in sequences:
            if sequence is not None:
                self._sent_ns[sequence] = now
        self.beacons_sent += 1

    def _receive(self, port):
        s = self._sockets[port]
        for _ in range(64):  # bounded per pass
            try:
                data, ancillary, _, address = s.recvmsg(2048, 64)
            except BlockingIOError:
                return
            if address[2] == socket.PACKET_OUTGOING:
                continue  # our own transmission, looped back to the packet socket
            time_ns = time.time_ns()
            for level, kind, value in ancillary:
                if level == socket.SOL_SOCKET and kind == SO_TIMESTAMPNS:
                    seconds, nanos = struct.unpack("qq", value[:16])
                    time_ns = seconds * 1_000_000_000 + nanos
            frame = parse(data, port, time_ns)
            if frame is None:
                continue
            if frame.kind == BEACON:
                if frame.source != self.mac:
                    self.foreign_beacons += 1
                elif frame.source_port == (2 if port == 0 else 1):
                    self.beacons_back[port] += 1
                    sent = self._sent_ns.get(frame.sequence)
                    if sent is not None:
                        self._back_sent_ns[port] = max(self._back_sent_ns[port], sent)
                continue
            if frame.source == self.mac:
                continue  # our own Flush_Tables etc. forwarded round the ring
            with self._lock:
                self.received.append(frame)
            if frame.kind == NEIGHBOR_REQUEST and self.answer_neighbor_checks[port]:
                self._sockets[port].send(build(NEIGHBOR_MAC, self.mac, NEIGHBOR_RESPONSE, port + 1, self.ip,
                                               frame.sequence, bytes([frame.source_port])))
            # A node reporting a port down (a status bit clear) is a fault at once; one reporting its
            # port up again is not (the ring closes when the beacons come back round).
            if frame.kind == LINK_STATUS and frame.body[0] & 0x03 != 0x03 and self.state == RING_NORMAL:
                self._set_state(RING_FAULT, f"link_status from {mac_text(frame.source)} on {port}")

    def _evaluate(self):
        """Ring state from the beacons: called after the sockets have been read."""
        deadline = time.monotonic_ns() - self.timeout_us * 1000
        # The newest round sent a whole timeout ago: its beacons (or later ones) must be back by now.
        due = next((r[0] for r in reversed(self._rounds) if r[0] <= deadline), None)
        overdue = due is not None and any(t < due for t in self._back_sent_ns)
        if self.state == RING_NORMAL and overdue:
            self._set_state(RING_FAULT, "beacon timeout")
        elif self.state == RING_FAULT and not overdue and all(t > self._fault_ns for t in self._back_sent_ns):
            self._set_state(RING_NORMAL, "own beacons back on both ports")

    def _run(self):
        interval_ns = self.interval_us * 1000
        next_beacon = time.monotonic_ns()
        last_beacon = None
        while not self._stop.is_set():
            now = time.monotonic_ns()
            if now >= next_beacon:
                # What came back while this thread waited counts before the ring is judged.
                for port in (0, 1):
                    self._receive(port)
                self._evaluate()
                if last_beacon is not None:
                    self.max_beacon_gap_us = max(self.max_beacon_gap_us, (now - last_beacon) // 1000)
                last_beacon = now
                self._send_beacons()
                next_beacon += interval_ns
                if next_beacon < now:  # fell behind (a slow pass): no burst of beacons to catch up
                    next_beacon = now + interval_ns
            wait = max(0, next_beacon - time.monotonic_ns()) / 1e9
            readable, _, _ = select.select(self._sockets, [], [], wait)
            for s in readable:
                self._receive(self._sockets.index(s))


def flood(iface, seconds, rate):
    """Ring frames at `rate` frames/s out of `iface` for `seconds`: Neighbor_Check requests (each asks for an
    answer), Locate_Fault (each starts neighbour checks), beacons of a second supervisor of lower precedence
    (forwarded), Flush_Tables without learning update, and malformed DLR frames (wrong version, truncated,
    a Sign_On whose count runs past its end). Prints what it sent."""
    raw = socket.socket(socket.AF_PACKET, socket.SOCK_RAW)
    raw.bind((iface, 0))
    rogue = mac_bytes(FLOOD_SOURCE)
    frames = [
        build(NEIGHBOR_MAC, rogue, NEIGHBOR_REQUEST, 1, "10.0.0.9", 7),
        build(ANNOUNCE_MAC, rogue, LOCATE_FAULT, 1, "10.0.0.9", 8),
        build(BEACON_MAC, rogue, BEACON, 1, "10.0.0.9", 9, beacon_fields(RING_NORMAL, 1, 400, 1960)),
        build(ANNOUNCE_MAC, rogue, FLUSH_TABLES, 1, "10.0.0.9", 10, bytes([0])),
        build(NEIGHBOR_MAC, rogue, NEIGHBOR_REQUEST, 1, "10.0.0.9", 11)[:24],           # truncated
        build(BEACON_MAC, rogue, BEACON, 1, "10.0.0.9", 12).replace(b"\x80\xe1\x02\x01", b"\x80\xe1\x02\x07"),
        build(NEIGHBOR_MAC, rogue, SIGN_ON, 1, "10.0.0.9", 13, struct.pack(">H", 400)),  # count past its end
    ]
    sent = errors = 0
    begin = time.monotonic()
    until = begin + seconds
    while time.monotonic() < until:
        ahead = (sent + errors) / rate - (time.monotonic() - begin)
        if ahead > 0:
            time.sleep(ahead)
        for i in range(32):
            try:
                raw.send(frames[(sent + errors + i) % len(frames)])
                sent += 1
            except OSError:
                errors += 1  # the TAP queue is full: the card reads at its own pace
    print(f"dlr flood: {sent} ring frames in {seconds} s ({sent / seconds:.0f} frames/s), {errors} refused by the "
          "kernel", flush=True)


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "flood":
        flood(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    else:
        print("usage: dlr_supervisor.py flood IFACE SECONDS FRAMES_PER_SECOND", file=sys.stderr)
        sys.exit(2)
