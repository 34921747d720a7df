"""EtherNet/IP negative conformance suite (docs/conformance.md "EtherNet/IP"): the protocol side of the
runner, the encapsulation cases over TCP and UDP, and the session rules. The message router and object
cases are in eip_cip_cases.py, the Connection Manager's in eip_connection_cases.py.

The card runs with c500 = 1, c101 = 1 (a closed exclusive owner leaves the drive alone) and acc = 50. Every
negative case comes from NEG_IP; the health checks at the end come from HOST_IP. Expected bytes follow
docs/ethernetip.md ("Encapsulation", "Common Packet Format") exactly: an error reply echoes command,
session handle and sender context with length 0 (RegisterSession's carry the 4 data bytes).
"""
import os
import select
import socket
import struct
import time

from conformance import CLOSED, Case, Chunk, Failure, Link, Protocol, Quiet, hexs, unhex
from eip_originator import (HEADER, ITEM_CONNECTED_ADDRESS, ITEM_CONNECTED_DATA, ITEM_NULL, ITEM_UNCONNECTED_DATA,
                            LIST_IDENTITY, LIST_INTERFACES, LIST_SERVICES, NOP, REGISTER_SESSION, SEND_RR_DATA,
                            SEND_UNIT_DATA, UNREGISTER_SESSION, encode, encode_cpf, epath, mr_request,
                            send_rr_data_body)

CARD = os.environ.get("CARD_IP", "127.0.0.1")
HOST = os.environ.get("HOST_IP", "127.0.0.1")
NEG = os.environ.get("NEG_IP", HOST)
PORT = 44818
CTX = b"conform!"

OK, INVALID_COMMAND, NO_MEMORY, INCORRECT_DATA = 0x0000, 0x0001, 0x0002, 0x0003
INVALID_SESSION, INVALID_LENGTH, UNSUPPORTED_PROTOCOL = 0x0064, 0x0065, 0x0069

OWN, OTHER = "own session", "another connection's session"
GET_VENDOR = mr_request(0x0E, epath(0x01, 1, 1))
VENDOR_REPLY = unhex("8E 00 00 00 79 01")
LIST_SERVICES_DATA = unhex("01 00 00 01 14 00 01 00 20 01") + b"Communications\x00\x00"


def H(value):
    return unhex(value) if isinstance(value, str) else bytes(value)


def session_of(spec, link):
    return link.session if spec == OWN else link.other_session if spec == OTHER else spec


class Msg:
    """An encapsulation message; `session` may be OWN or OTHER, resolved on the case's connection."""

    def __init__(self, command, data=b"", session=0, status=0, options=0, length=None, context=CTX):
        self.command, self.data, self.session = command, H(data), session
        self.status, self.options, self.length, self.context = status, options, length, context

    def __call__(self, link):
        return encode(self.command, self.data, session_of(self.session, link), self.context, self.status,
                      self.options, self.length)


def error(command, session=0, status=INVALID_COMMAND, data=b""):
    """An error reply: the request's command, session and context, the status, no data (or `data`)."""
    return Msg(command, data, session, status)


def rr(request, extra_items=()):
    return send_rr_data_body(H(request), extra_items)


def rr_reply(mr_reply):
    """The whole SendRRData reply carrying one message router reply, on the case's own session."""
    body = struct.pack("<IH", 0, 0) + encode_cpf([(ITEM_NULL, b""), (ITEM_UNCONNECTED_DATA, H(mr_reply))])
    return Msg(SEND_RR_DATA, body, OWN)


def send_data(packet, interface=0, timeout=0):
    """The data of SendRRData/SendUnitData: interface handle, timeout, then the CPF bytes as given."""
    return struct.pack("<IH", interface, timeout) + H(packet)


def framer(buffer):
    if len(buffer) < 24:
        return None
    return 24 + struct.unpack_from("<H", buffer, 2)[0]


def register(link):
    """RegisterSession on `link`; sets link.session."""
    link.send(encode(REGISTER_SESSION, H("01 00 00 00"), 0, CTX))
    reply = link.receive()
    if reply is None or len(reply) != 28:
        raise Failure(f"RegisterSession: {hexs(reply)}")
    command, length, handle, status, _, _ = HEADER.unpack_from(reply)
    if status != OK or handle == 0:
        raise Failure(f"RegisterSession refused: {hexs(reply)}")
    link.session = handle
    return handle


# ---- Encapsulation over TCP -----------------------------------------------------------------------

def encapsulation_cases():
    area = "encapsulation command"
    cases = []
    for command in (0x0001, 0x0002, 0x0003, 0x0005, 0x0062, 0x0067, 0x006E, 0x0071, 0x0072, 0x0073, 0x00C8,
                    0x0100, 0xFFFF):
        cases.append(Case(area, f"unknown or unsupported command 0x{command:04X} with 2 data bytes: 0x0001",
                          Msg(command, "AA BB", 0x1234), error(command, 0x1234)))
    cases.append(Case(area, "unknown command with a session: 0x0001, session echoed", Msg(0x00C8, b"", OWN),
                      error(0x00C8, OWN), on="session"))

    area = "encapsulation length"
    for size in (0, 2, 3, 5, 8):
        cases.append(Case(area, f"RegisterSession with {size} data bytes: 0x0065",
                          Msg(REGISTER_SESSION, bytes([1] + [0] * (size - 1)) if size else b""),
                          error(REGISTER_SESSION, 0, INVALID_LENGTH)))
    for command, name, size in ((LIST_IDENTITY, "ListIdentity", 1), (LIST_SERVICES, "ListServices", 4),
                                (LIST_INTERFACES, "ListInterfaces", 2)):
        cases.append(Case(area, f"{name} with {size} data bytes: 0x0065", Msg(command, bytes(size)),
                          error(command, 0, INVALID_LENGTH)))
    for size in (0, 6, 7):
        cases.append(Case(area, f"SendRRData of {size} bytes: 0x0065", Msg(SEND_RR_DATA, bytes(size), OWN),
                          error(SEND_RR_DATA, OWN, INVALID_LENGTH), on="session"))
    cases.append(Case(area, "SendUnitData of 6 bytes: 0x0065", Msg(SEND_UNIT_DATA, bytes(6), OWN),
                      error(SEND_UNIT_DATA, OWN, INVALID_LENGTH), on="session"))
    # The buffer holds 600 bytes of data (docs/ethernetip.md "Stream framing and limit").
    # SendRRData data: handle and timeout (6), item count (2), two item headers (8), then the request:
    # service, path size and a 6-byte path (8) and its data.
    big = rr(mr_request(0x0E, epath(0x01, 1, 1), bytes(600 - 24)))
    assert len(big) == 600
    cases.append(Case(area, "SendRRData of exactly 600 bytes is taken (a Get with data: 0x15)",
                      Msg(SEND_RR_DATA, big, OWN), rr_reply("8E 00 15 00"), on="session"))
    cases.append(Case(area, "SendRRData of 601 bytes: 0x0002, the body skipped, the stream in step",
                      Msg(SEND_RR_DATA, rr(mr_request(0x0E, epath(0x01, 1, 1), bytes(601 - 24))), OWN),
                      error(SEND_RR_DATA, OWN, NO_MEMORY), on="session"))
    cases.append(Case(area, "ListIdentity announcing 1000 bytes: 0x0002", Msg(LIST_IDENTITY, bytes(1000)),
                      error(LIST_IDENTITY, 0, NO_MEMORY)))
    cases.append(Case(area, "SendRRData announcing 65535 bytes, sent in two writes: 0x0002 once",
                      [lambda k: Msg(SEND_RR_DATA, bytes(65535), OWN)(k)[:40000],
                       Chunk(lambda k: Msg(SEND_RR_DATA, bytes(65535), OWN)(k)[40000:], 0.05)],
                      error(SEND_RR_DATA, OWN, NO_MEMORY), on="session"))
    cases.append(Case(area, "NOP announcing 2000 bytes: no reply", Msg(NOP, bytes(2000)), []))
    cases.append(Case(area, "header announcing 8 bytes, 4 sent: nothing until the rest comes, then 0x0065",
                      [lambda k: Msg(LIST_SERVICES, bytes(8))(k)[:28], Quiet(0.3), Chunk(bytes(4))],
                      error(LIST_SERVICES, 0, INVALID_LENGTH)))
    cases.append(Case(area, "a header cut after 12 bytes: nothing comes, the connection stays open",
                      [lambda k: Msg(LIST_SERVICES)(k)[:12], Quiet(0.3)], [], probe=False))

    area = "encapsulation version/options"
    for version, options in ((0, 0), (2, 0), (0xFFFF, 0), (1, 1), (1, 0x8000)):
        cases.append(Case(area, f"RegisterSession version {version} options 0x{options:04X}: 0x0069 naming version 1",
                          Msg(REGISTER_SESSION, struct.pack("<HH", version, options)),
                          error(REGISTER_SESSION, 0, UNSUPPORTED_PROTOCOL, struct.pack("<HH", 1, options))))
    for command, name in ((REGISTER_SESSION, "RegisterSession"), (LIST_SERVICES, "ListServices"),
                          (LIST_IDENTITY, "ListIdentity")):
        data = "01 00 00 00" if command == REGISTER_SESSION else ""
        cases.append(Case(area, f"{name} with header options 1: dropped", Msg(command, data, options=1), []))
    cases.append(Case(area, "SendRRData with header options 0x80000000: dropped",
                      Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN, options=0x80000000), [], on="session"))
    cases.append(Case(area, "NOP with options and data: dropped", Msg(NOP, "01 02", options=4), []))
    cases.append(Case(area, "ListServices with status 1 in the request: answered (the field is ignored)",
                      Msg(LIST_SERVICES, status=1), Msg(LIST_SERVICES, LIST_SERVICES_DATA)))
    cases.append(Case(area, "ListServices with a made-up session handle: answered, handle echoed",
                      Msg(LIST_SERVICES, session=0xDEADBEEF), Msg(LIST_SERVICES, LIST_SERVICES_DATA, 0xDEADBEEF)))
    cases.append(Case(area, "NOP with 3 data bytes and a made-up handle: no reply", Msg(NOP, "01 02 03", 0x55), []))

    area = "encapsulation stream"
    services = Msg(LIST_SERVICES, context=b"stream-1")
    cases.append(Case(area, "ListServices one byte per segment",
                      [Chunk(lambda k, i=i: services(k)[i:i + 1], 0.01) for i in range(24)],
                      Msg(LIST_SERVICES, LIST_SERVICES_DATA, context=b"stream-1")))
    cases.append(Case(area, "SendRRData split inside the header and inside the CPF",
                      [lambda k: Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN)(k)[:10],
                       Chunk(lambda k: Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN)(k)[10:31]),
                       Chunk(lambda k: Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN)(k)[31:])],
                      rr_reply(VENDOR_REPLY), on="session"))
    cases.append(Case(area, "four messages in one segment (good, unknown, NOP, bad length): three replies in order",
                      lambda k: b"".join(m(k) for m in (Msg(LIST_SERVICES), Msg(0x00C8), Msg(NOP, "00"),
                                                          Msg(LIST_INTERFACES, "00 00"))),
                      [Msg(LIST_SERVICES, LIST_SERVICES_DATA), error(0x00C8), error(LIST_INTERFACES, 0, INVALID_LENGTH)]))
    cases.append(Case(area, "20 SendRRData in one segment: 20 replies in order",
                      lambda k: Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN)(k) * 20, [rr_reply(VENDOR_REPLY)] * 20,
                      on="session"))
    cases.append(Case(area, "a message and a half, then the rest: two replies",
                      [lambda k: Msg(LIST_SERVICES)(k) + Msg(LIST_INTERFACES)(k)[:20],
                       Chunk(lambda k: Msg(LIST_INTERFACES)(k)[20:])],
                      [Msg(LIST_SERVICES, LIST_SERVICES_DATA), Msg(LIST_INTERFACES, "00 00")]))
    cases.append(Case(area, "an oversized message followed by a good one in the same segment: 0x0002, then the reply",
                      lambda k: Msg(LIST_IDENTITY, bytes(700))(k) + Msg(LIST_SERVICES)(k),
                      [error(LIST_IDENTITY, 0, NO_MEMORY), Msg(LIST_SERVICES, LIST_SERVICES_DATA)]))
    return cases


# ---- Common Packet Format --------------------------------------------------------------------------

def cpf_cases():
    area = "common packet format"
    null, data = (ITEM_NULL, b""), (ITEM_UNCONNECTED_DATA, GET_VENDOR)
    sockaddr = struct.pack(">HH4s8x", 2, 2222, socket.inet_aton(NEG))

    def item(kind, payload):
        return struct.pack("<HH", kind, len(payload)) + payload

    rows = [
        ("item count 0", struct.pack("<H", 0)),
        ("item count 1 (null address only)", encode_cpf([null])),
        ("item count 3 with 2 items", struct.pack("<H", 3) + item(*null) + item(*data)),
        ("item count 5 (more than 4)", struct.pack("<H", 5) + item(*null) + item(*data) + item(*null) * 3),
        ("item count 2 with 1 item", struct.pack("<H", 2) + item(*null)),
        ("second item's length runs past the end", struct.pack("<H", 2) + item(*null) +
         struct.pack("<HH", ITEM_UNCONNECTED_DATA, 40) + GET_VENDOR),
        ("a byte after the last item", encode_cpf([null, data]) + b"\x00"),
        ("unconnected data before the null address", encode_cpf([data, null])),
        ("null address item with 2 bytes", encode_cpf([(ITEM_NULL, b"\x00\x00"), data])),
        ("connected address instead of the null address", encode_cpf([(ITEM_CONNECTED_ADDRESS, bytes(4)), data])),
        ("connected data item instead of unconnected data", encode_cpf([null, (ITEM_CONNECTED_DATA, GET_VENDOR)])),
        ("a third item of unknown type 0x1234", encode_cpf([null, data, (0x1234, b"")])),
        ("socket address item of 8 bytes", encode_cpf([null, data, (0x8000, sockaddr[:8])])),
        ("two O->T socket address items", encode_cpf([null, data, (0x8000, sockaddr), (0x8000, sockaddr)])),
    ]
    cases = [Case(area, f"SendRRData, {name}: 0x0003", Msg(SEND_RR_DATA, send_data(packet), OWN),
                  error(SEND_RR_DATA, OWN, INCORRECT_DATA), on="session") for name, packet in rows]
    unit_rows = [
        ("item count 1", encode_cpf([(ITEM_CONNECTED_ADDRESS, bytes(4))])),
        ("connected address of 2 bytes", encode_cpf([(ITEM_CONNECTED_ADDRESS, bytes(2)), (ITEM_CONNECTED_DATA, b"\x01\x00")])),
        ("connected data of 1 byte", encode_cpf([(ITEM_CONNECTED_ADDRESS, bytes(4)), (ITEM_CONNECTED_DATA, b"\x01")])),
        ("null address and unconnected data", encode_cpf([null, data])),
    ]
    cases += [Case(area, f"SendUnitData, {name}: 0x0003", Msg(SEND_UNIT_DATA, send_data(packet), OWN),
                   error(SEND_UNIT_DATA, OWN, INCORRECT_DATA), on="session") for name, packet in unit_rows]
    cases.append(Case(area, "SendUnitData to a connection that does not exist: no reply",
                      Msg(SEND_UNIT_DATA, send_data(encode_cpf([(ITEM_CONNECTED_ADDRESS, b"\x78\x56\x34\x12"),
                                                                (ITEM_CONNECTED_DATA, b"\x01\x00" + GET_VENDOR)])), OWN),
                      [], on="session"))
    cases.append(Case(area, "SendRRData with an empty unconnected data item: the router's 0x04 (request shorter "
                      "than service + path size)", Msg(SEND_RR_DATA, rr(b""), OWN), rr_reply("80 00 04 00"),
                      on="session"))
    cases.append(Case(area, "SendRRData with a non-zero interface handle and timeout: answered (both ignored)",
                      Msg(SEND_RR_DATA, send_data(encode_cpf([null, data]), 0x12345678, 0xFFFF), OWN),
                      rr_reply(VENDOR_REPLY), on="session"))
    return cases


# ---- Sessions --------------------------------------------------------------------------------------

def session_cases():
    area = "session"
    return [
        Case(area, "SendRRData without a session (handle 0): 0x0064", Msg(SEND_RR_DATA, rr(GET_VENDOR)),
             error(SEND_RR_DATA, 0, INVALID_SESSION)),
        Case(area, "SendRRData without a session, made-up handle: 0x0064", Msg(SEND_RR_DATA, rr(GET_VENDOR), 0x12345678),
             error(SEND_RR_DATA, 0x12345678, INVALID_SESSION)),
        Case(area, "SendRRData with another connection's handle, no own session: 0x0064",
             Msg(SEND_RR_DATA, rr(GET_VENDOR), OTHER), error(SEND_RR_DATA, OTHER, INVALID_SESSION)),
        Case(area, "SendRRData with another connection's handle on a registered connection: 0x0064",
             Msg(SEND_RR_DATA, rr(GET_VENDOR), OTHER), error(SEND_RR_DATA, OTHER, INVALID_SESSION), on="session"),
        Case(area, "SendRRData with the own handle + 1: 0x0064",
             lambda k: Msg(SEND_RR_DATA, rr(GET_VENDOR), (k.session + 1) & 0xFFFFFFFF)(k),
             lambda k: error(SEND_RR_DATA, (k.session + 1) & 0xFFFFFFFF, INVALID_SESSION)(k), on="session"),
        Case(area, "SendUnitData with another connection's handle: 0x0064",
             Msg(SEND_UNIT_DATA, send_data(encode_cpf([(ITEM_CONNECTED_ADDRESS, bytes(4)),
                                                       (ITEM_CONNECTED_DATA, b"\x01\x00" + GET_VENDOR)])), OTHER),
             error(SEND_UNIT_DATA, OTHER, INVALID_SESSION), on="session"),
        Case(area, "SendUnitData without a session: 0x0064", Msg(SEND_UNIT_DATA, send_data(b"")),
             error(SEND_UNIT_DATA, 0, INVALID_SESSION)),
        Case(area, "UnRegisterSession with another connection's handle: 0x0064, nothing closed",
             Msg(UNREGISTER_SESSION, b"", OTHER), error(UNREGISTER_SESSION, OTHER, INVALID_SESSION), on="session"),
        Case(area, "UnRegisterSession without a session: 0x0064", Msg(UNREGISTER_SESSION, b"", 0),
             error(UNREGISTER_SESSION, 0, INVALID_SESSION)),
        Case(area, "a second RegisterSession: 0x0001 with the existing handle",
             Msg(REGISTER_SESSION, "01 00 00 00"), error(REGISTER_SESSION, OWN, INVALID_COMMAND, "01 00 00 00"),
             on="session"),
        Case(area, "RegisterSession version 2 on a registered connection: 0x0069, the session kept",
             [Msg(REGISTER_SESSION, "02 00 00 00"), Chunk(Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN))],
             [error(REGISTER_SESSION, 0, UNSUPPORTED_PROTOCOL, "01 00 00 00"), rr_reply(VENDOR_REPLY)], on="session"),
        Case(area, "UnRegisterSession with the own handle: no reply, the card closes",
             Msg(UNREGISTER_SESSION, b"", OWN), [CLOSED], on="session"),
        Case(area, "UnRegisterSession with the own handle and 4 data bytes: no reply, closed (decided)",
             Msg(UNREGISTER_SESSION, bytes(4), OWN), [CLOSED], on="session"),
        Case(area, "requests after UnRegisterSession in the same segment are not answered",
             lambda k: Msg(UNREGISTER_SESSION, b"", OWN)(k) + Msg(LIST_SERVICES)(k), [CLOSED], on="session"),
    ]


# ---- UDP -------------------------------------------------------------------------------------------

def udp_rows():
    broadcast = CARD.rsplit(".", 1)[0] + ".255"
    e = lambda command, status, data=b"", session=0: encode(command, H(data), session, CTX, status)  # noqa: E731
    get = rr(GET_VENDOR)
    unicast = [
        ("RegisterSession over unicast UDP: 0x0001", encode(REGISTER_SESSION, H("01 00 00 00"), 0, CTX),
         [e(REGISTER_SESSION, INVALID_COMMAND)]),
        ("UnRegisterSession over unicast UDP: 0x0001", encode(UNREGISTER_SESSION, b"", 7, CTX),
         [e(UNREGISTER_SESSION, INVALID_COMMAND, session=7)]),
        ("SendRRData over unicast UDP: 0x0001", encode(SEND_RR_DATA, get, 7, CTX), [e(SEND_RR_DATA, INVALID_COMMAND, session=7)]),
        ("SendUnitData over unicast UDP: 0x0001", encode(SEND_UNIT_DATA, get, 7, CTX),
         [e(SEND_UNIT_DATA, INVALID_COMMAND, session=7)]),
        ("unknown command 0x00C8 over unicast UDP: 0x0001", encode(0x00C8, b"", 0, CTX), [e(0x00C8, INVALID_COMMAND)]),
        ("ListIdentity with data over unicast UDP: 0x0065", encode(LIST_IDENTITY, b"\x00", 0, CTX),
         [e(LIST_IDENTITY, INVALID_LENGTH)]),
        ("ListServices with data over unicast UDP: 0x0065", encode(LIST_SERVICES, b"\x00\x00", 0, CTX),
         [e(LIST_SERVICES, INVALID_LENGTH)]),
        ("ListInterfaces with data over unicast UDP: 0x0065", encode(LIST_INTERFACES, b"\x00", 0, CTX),
         [e(LIST_INTERFACES, INVALID_LENGTH)]),
        ("NOP over unicast UDP: no reply", encode(NOP, b"\x01", 0, CTX), []),
        ("ListServices with options over unicast UDP: dropped", encode(LIST_SERVICES, b"", 0, CTX, options=1), []),
        ("a datagram shorter than the header: dropped", encode(LIST_SERVICES, b"", 0, CTX)[:20], []),
        ("a datagram longer than its header says: dropped", encode(LIST_SERVICES, b"", 0, CTX) + b"\x00\x00", []),
        ("a datagram shorter than its header says: dropped", encode(LIST_SERVICES, b"", 0, CTX, length=4), []),
        ("two ListServices in one datagram: dropped", encode(LIST_SERVICES, b"", 0, CTX) * 2, []),
        ("a datagram of 700 bytes: dropped", encode(LIST_IDENTITY, bytes(676), 0, CTX), []),
    ]
    to_broadcast = [
        ("RegisterSession to the broadcast address: no reply", encode(REGISTER_SESSION, H("01 00 00 00"), 0, CTX), []),
        ("unknown command to the broadcast address: no reply", encode(0x00C8, b"", 0, CTX), []),
        ("ListServices with data to the broadcast address: no reply", encode(LIST_SERVICES, b"\x00", 0, CTX), []),
        ("SendRRData to the broadcast address: no reply", encode(SEND_RR_DATA, get, 7, CTX), []),
        ("ListIdentity with data to the broadcast address: no reply", encode(LIST_IDENTITY, b"\x00", 0, CTX), []),
    ]
    return [(name, CARD, data, want) for name, data, want in unicast] + \
           [(name, broadcast, data, want) for name, data, want in to_broadcast]


def udp_case(destination, datagram, want):
    """Sends the datagram, then a unicast probe (ListInterfaces); every reply before the probe's must be `want`."""
    probe_context = b"udpprobe"
    probe = encode(LIST_INTERFACES, b"", 0, probe_context)
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_BROADCAST, 1)
        sock.bind((NEG, 0))
        sock.sendto(datagram, (destination, PORT))
        time.sleep(0.01)
        sock.sendto(probe, (CARD, PORT))
        got, deadline = [], time.monotonic() + 2.0
        while True:
            left = deadline - time.monotonic()
            ready = select.select([sock], [], [], max(0, left))[0] if left > 0 else []
            if not ready:
                raise Failure(f"no reply to the probe within 2 s; before it: {[hexs(g) for g in got]}")
            data, _ = sock.recvfrom(2048)
            if data == encode(LIST_INTERFACES, b"\x00\x00", 0, probe_context):
                break
            got.append(data)
    if got != want:
        raise Failure(f"replies {[hexs(g) for g in got]}, expected {[hexs(w) for w in want]}")


# ---- The protocol ----------------------------------------------------------------------------------

class EipProtocol(Protocol):
    name = "EtherNet/IP conformance"

    def __init__(self):
        self.other = Link(CARD, PORT, framer, source=NEG)
        register(self.other)
        self.shared = None

    def _new(self, with_session):
        link = Link(CARD, PORT, framer, source=NEG)
        link.other_session = self.other.session
        if with_session:
            register(link)
        return link

    def connect(self, case):
        if case.on == "shared":
            if self.shared is None:
                self.shared = self._new(True)
            return self.shared
        return self._new(case.on == "session")

    def release(self, case, link, failed):
        if case.on == "shared" and not failed and not link.eof:
            return
        if link is self.shared:
            self.shared = None
        link.close()

    def probe(self, link):
        context = b"probe..."
        return (encode(LIST_INTERFACES, b"", link.session, context),
                encode(LIST_INTERFACES, b"\x00\x00", link.session, context))

    def other_cases(self):
        import eip_connection_cases
        out = [("UDP", name, lambda d=destination, g=datagram, w=want: udp_case(d, g, w))
               for name, destination, datagram, want in udp_rows()]
        out.append(("session", "the other connection's session survived every foreign-handle attempt",
                    self.check_other))
        out.append(("session", "a client that closes with a drive read (deferred reply) pending: the next is served",
                    self.close_while_pending))
        out += eip_connection_cases.sequence(self)
        return out

    def check_other(self):
        self.other.send(Msg(SEND_RR_DATA, rr(GET_VENDOR), OWN)(self.other))
        got = self.other.receive()
        want = rr_reply(VENDOR_REPLY)(self.other)
        if got != want:
            raise Failure(f"got {hexs(got)}, expected {hexs(want)}")

    def other_client(self):
        """A client with its own session on another connection (eip_originator.Client)."""
        from eip_originator import Client
        client = Client(CARD, source=NEG)
        client.register_session()
        return client

    def close_all(self):
        for link in (self.other, self.shared):
            if link is not None:
                link.close()
        self.shared = None

    def close_while_pending(self):
        # Parameter acc (0x65/0009) is read over the serial link: its reply is deferred.
        link = self._new(True)
        link.send(Msg(SEND_RR_DATA, rr(mr_request(0x0E, epath(0x65, 0x0009, 3))), OWN)(link))
        link.close()
        link = self._new(True)
        try:
            link.send(Msg(SEND_RR_DATA, rr(mr_request(0x0E, epath(0x65, 0x0009, 3))), OWN)(link))
            got, want = link.receive(), rr_reply("8E 00 00 00 32 00")(link)
            if got != want:
                raise Failure(f"parameter acc: got {hexs(got)}, expected {hexs(want)}")
        finally:
            link.close()

    def health(self):
        import eip_connection_cases
        return eip_connection_cases.health(self)


def cases():
    import eip_cip_cases
    return encapsulation_cases() + cpf_cases() + session_cases() + eip_cip_cases.cases()


def protocol():
    return EipProtocol()
