"""Connection Manager cases (docs/conformance.md "Forward_Open"): the rejection matrix of docs/connections.md
("Forward_Open: rules and their status"), the limits, Forward_Close, ownership; then the health checks of
the whole EtherNet/IP suite (a healthy client from HOST_IP: explicit messages, class 1 I/O, class 3).

The matrix needs state (an exclusive owner to collide with, a multicast production to join, full tables),
so it is a sequence: each step is reported as one case, in order. Requests come from NEG_IP; the I/O
endpoint (UDP 2222) feeds the exclusive owner so that it stays open while the refusals run.
"""
import time

from conformance import Failure, card_alive, hexs
from eip_io import (CLASS1_CYCLIC, CLASS3_SERVER_APPLICATION, FORWARD_CLOSE, FORWARD_OPEN, LARGE_FORWARD_OPEN,
                    ROUTER_PATH, TYPE_MULTICAST, TYPE_NULL, TYPE_P2P, TYPE_RESERVED,
                    ExplicitConnection, IoConnection, IoEndpoint, Triad, close_success_bytes, decode_open_success,
                    decode_sockaddr, electronic_key, forward_close, forward_open, io_path, net_params,
                    open_connection, refused_bytes, rpi_refusal_words, sequence_steps)
from eip_originator import Client, epath, logical_segment, mr_request
from eip_suite import CARD, HOST, NEG, VENDOR_REPLY

GET_VENDOR = mr_request(0x0E, epath(0x01, 1, 1))
AREA = "Forward_Open matrix"
LIMITS = "connection limits and ownership"
CLOSE = "Forward_Close"

_endpoint = []


def endpoint():
    """The one UDP 2222 socket (bound to 0.0.0.0: it receives the productions to NEG_IP and HOST_IP)."""
    if not _endpoint:
        _endpoint.append(IoEndpoint(CARD))
    return _endpoint[0]


class Opener:
    """Builds Forward_Open requests around one exclusive-owner shape (21/71, RPI 10 ms) with overrides."""

    def __init__(self):
        self.serial = 0x0800

    def triad(self):
        self.serial += 1
        return Triad(self.serial)

    def request(self, triad, path=None, o_t_rpi=10000, o_t_size=10, t_o_rpi=10000, t_o_size=6, o_t_kind=TYPE_P2P,
                t_o_kind=TYPE_P2P, transport=CLASS1_CYCLIC, multiplier=2, large=False, redundant=False, t_o_id=None):
        path = io_path(21, 71) if path is None else path
        return forward_open(triad, path, o_t_rpi, net_params(o_t_size, o_t_kind, redundant=redundant, large=large),
                            t_o_rpi, net_params(t_o_size, t_o_kind, large=large), transport=transport,
                            t_o_id=0x70000000 + triad.serial if t_o_id is None else t_o_id, multiplier=multiplier,
                            large=large)


def expect_raw(client, request, want, what=""):
    _, raw, items = open_connection(client, request)
    if raw != want or items:
        raise Failure(f"{what}got      {hexs(raw)} {items if items else ''}\n      expected {hexs(want)}")


def open_ok(client, request, triad, rpi=(10000, 10000), multicast=False):
    """Sends a Forward_Open that must succeed; returns (O->T ID, T->O ID). Checks the triad, the APIs
    (= the RPIs), the reply's size and, for multicast, the T->O socket address item (port 2222, a group)."""
    mr, raw, items = open_connection(client, request)
    if mr.general != 0:
        raise Failure(f"refused: {hexs(raw)}")
    reply = decode_open_success(mr.data)
    if reply["triad"] != triad.bytes() or (reply["o_t_api"], reply["t_o_api"]) != rpi or \
            reply["application_size"] != 0 or reply["reserved"] != 0:
        raise Failure(f"success reply fields {reply}")
    if multicast:
        if len(items) != 1 or items[0][0] != 0x8001:
            raise Failure(f"multicast reply items {items}")
        family, port, group = decode_sockaddr(items[0][1])
        if family != 2 or port != 2222 or not 224 <= int(group.split(".")[0]) <= 239:
            raise Failure(f"T->O socket address {family} {port} {group}")
    elif items:
        raise Failure(f"unexpected items after a point-to-point reply: {items}")
    return reply["o_t_id"], reply["t_o_id"]


def close_ok(client, triad, path):
    expect_raw(client, forward_close(triad, path), close_success_bytes(triad))


def matrix_rows(o):
    """(name, triad, request, expected reply bytes) of the refusals that need no other connection."""
    rows = []

    def refusal(name, words, remaining=0, service=FORWARD_OPEN, **kw):
        t = o.triad()
        rows.append((name, o.request(t, **kw), refused_bytes(t, words, remaining, service)))

    def path_refusal(name, extended, path):
        refusal(name, [extended], len(path) // 2, path=path)

    t = o.triad()
    full = o.request(t)
    rows.append(("fixed part cut (35 of 36 bytes): 0x13, no data", full[:6 + 35], bytes([0xD4, 0, 0x13, 0])))
    t = o.triad()
    large = o.request(t, large=True)
    rows.append(("Large_Forward_Open fixed part cut (39 of 40): 0x13", large[:6 + 39], bytes([0xDB, 0, 0x13, 0])))
    rows.append(("no data at all: 0x13", mr_request(FORWARD_OPEN, epath(0x06, 1)), bytes([0xD4, 0, 0x13, 0])))
    t = o.triad()
    rows.append(("path size past the data: 0x13 with the triad", o.request(t)[:-4],
                 bytes([0xD4, 0, 0x13, 0]) + t.bytes() + b"\x00\x00"))
    t = o.triad()
    rows.append(("bytes after the path: 0x15 with the triad", o.request(t) + b"\x00\x00",
                 bytes([0xD4, 0, 0x15, 0]) + t.bytes() + b"\x00\x00"))
    refusal("null Forward_Open (both types null): 0x0132", [0x0132], o_t_kind=TYPE_NULL, t_o_kind=TYPE_NULL)
    for name, transport in (("class 1 change of state", 0x11), ("class 1 application triggered", 0x21),
                            ("class 1 reserved trigger 3", 0x31), ("class 0", 0x00), ("class 2", 0x02),
                            ("class 4", 0x04), ("class 3 to an assembly", 0x83)):
        refusal(f"{name}: 0x0103", [0x0103], transport=transport)
    refusal("class 1 to the Message Router: 0x0103", [0x0103], path=ROUTER_PATH)
    refusal("O->T multicast: 0x0123", [0x0123], o_t_kind=TYPE_MULTICAST)
    refusal("O->T null, T->O point-to-point: 0x0123", [0x0123], o_t_kind=TYPE_NULL)
    refusal("O->T reserved type: 0x0123", [0x0123], o_t_kind=TYPE_RESERVED)
    refusal("T->O null: 0x0124", [0x0124], t_o_kind=TYPE_NULL)
    refusal("T->O reserved type: 0x0124", [0x0124], t_o_kind=TYPE_RESERVED)
    refusal("class 3 with T->O multicast: 0x0124", [0x0124], path=ROUTER_PATH, transport=CLASS3_SERVER_APPLICATION,
            o_t_size=504, t_o_size=504, t_o_kind=TYPE_MULTICAST)
    refusal("O->T redundant owner: 0x0125", [0x0125], redundant=True)
    refusal("Large_Forward_Open with the redundant owner bit: 0x0125", [0x0125], service=LARGE_FORWARD_OPEN,
            large=True, redundant=True)
    refusal("timeout multiplier 8: 0x0133", [0x0133], multiplier=8)
    refusal("timeout multiplier 255: 0x0133", [0x0133], multiplier=255)
    cls, cfg = logical_segment(0, 0x04), logical_segment(1, 1)
    pt = lambda n: logical_segment(3, n)  # noqa: E731
    path_refusal("route to port 1 slot 2 in front: 0x0312", 0x0312, bytes([0x01, 0x02]) + io_path(21, 71))
    path_refusal("route out of port 2: 0x0312", 0x0312, bytes([0x02, 0x07]) + io_path(21, 71))
    path_refusal("route via port 3: 0x0311", 0x0311, bytes([0x03, 0x00]) + io_path(21, 71))
    path_refusal("an attribute segment in the path: 0x0315", 0x0315, cls + cfg + pt(21) + pt(71) + bytes([0x30, 0x03]))
    path_refusal("a third connection point: 0x0315", 0x0315, cls + cfg + pt(21) + pt(71) + pt(70))
    path_refusal("class 0x01 (neither 0x02 nor 0x04): 0x0315", 0x0315, logical_segment(0, 0x01) + cfg + pt(21) + pt(71))
    path_refusal("a symbolic segment: 0x0315", 0x0315, cls + bytes([0x91, 0x02]) + b"ab" + pt(21) + pt(71))
    path_refusal("a cut 16-bit segment at the end: 0x0315", 0x0315, cls + cfg + pt(21) + bytes([0x2D, 0x00]))
    path_refusal("a data segment before the points: 0x0315", 0x0315, cls + cfg + bytes([0x80, 0x00]) + pt(21) + pt(71))
    path_refusal("the key after the class: 0x0315", 0x0315, cls + electronic_key() + cfg + pt(21) + pt(71))
    path_refusal("two keys: 0x0315", 0x0315, electronic_key() + electronic_key() + cls + cfg + pt(21) + pt(71))
    path_refusal("a point before the class: 0x0315", 0x0315, pt(21) + cls + cfg + pt(71))
    path_refusal("a port segment after the class: 0x0315", 0x0315, cls + bytes([0x01, 0x00]) + cfg + pt(21) + pt(71))
    path_refusal("32-bit class segment: 0x0315", 0x0315, bytes([0x22, 0, 4, 0, 0, 0]) + cfg + pt(21) + pt(71))
    path_refusal("a data segment claiming 255 words (OpENer #570): 0x0315", 0x0315,
                 cls + cfg + pt(21) + pt(71) + bytes([0x80, 0xFF, 0x01, 0x02]))
    for name, key, extended in (("vendor 378", electronic_key(vendor=378), 0x0114),
                                ("product code 32001 (a VF-S15) on a VF-MB1", electronic_key(product=32001), 0x0114),
                                ("device type 12", electronic_key(device_type=12), 0x0115),
                                ("revision 1.9", electronic_key(minor=9), 0x0116),
                                ("revision 2.8", electronic_key(major=2), 0x0116),
                                ("compatible revision 1.9", electronic_key(minor=9, compatible=True), 0x0116),
                                ("compatible revision 1.0", electronic_key(minor=0, compatible=True), 0x0116),
                                ("compatible revision 2.1", electronic_key(major=2, minor=1, compatible=True), 0x0116)):
        refusal(f"electronic key {name}: 0x{extended:04X}", [extended], path=io_path(21, 71, key=key))
    refusal("class 3 to Message Router instance 2: 0x0315", [0x0315], len(epath(0x02, 2)) // 2, path=epath(0x02, 2),
            transport=CLASS3_SERVER_APPLICATION, o_t_size=504, t_o_size=504)
    refusal("O->T RPI 500 us: 0x0111, type 2 with the 1 ms floor", rpi_refusal_words(0x0111, 2, 0, 1000, 10000),
            o_t_rpi=500)
    refusal("T->O RPI 999 us: 0x0111, type 2 with the floor", rpi_refusal_words(0x0111, 0, 2, 10000, 1000), t_o_rpi=999)
    refusal("T->O RPI 0: 0x0111", rpi_refusal_words(0x0111, 0, 2, 10000, 1000), t_o_rpi=0)
    refusal("O->T RPI 10.000001 s: 0x0111, type 3 with the 10 s maximum",
            rpi_refusal_words(0x0111, 3, 0, 10_000_000, 10000), o_t_rpi=10_000_001)
    refusal("configuration point only: 0x012A", [0x012A], path=cls + cfg)
    refusal("no produced point: 0x012B", [0x012B], path=cls + cfg + pt(21))
    refusal("configuration instance 5: 0x0129", [0x0129], path=io_path(21, 71, configuration=5))
    refusal("consumed point 22: 0x012A", [0x012A], path=io_path(22, 71))
    refusal("produced point 72: 0x012B", [0x012B], path=io_path(21, 72))
    refusal("input 70 as the consumed point: 0x012F", [0x012F], path=io_path(70, 71))
    refusal("O->T size 8 for 21 (needs 10): 0x0127 naming 10", [0x0127, 10], o_t_size=8)
    refusal("T->O size 4 for 71 (needs 6): 0x0128 naming 6", [0x0128, 6], t_o_size=4)
    refusal("100 with an odd O->T size: 0x0127 naming the largest (22)", [0x0127, 22], path=io_path(100, 150),
            o_t_size=11, t_o_size=6)
    refusal("150 of 18 bytes: 0x0128 naming the largest (18)", [0x0128, 18], path=io_path(100, 150), o_t_size=10,
            t_o_size=20)
    refusal("input only 199 with O->T size 4: 0x0127 naming 2", [0x0127, 2], path=io_path(199, 70), o_t_size=4)
    refusal("Large_Forward_Open O->T size 600 for 21: 0x0127 naming 10", [0x0127, 10], service=LARGE_FORWARD_OPEN,
            large=True, o_t_size=600)
    refusal("configuration data for instance 1 (size 0): 0x0126 naming 0", [0x0126, 0],
            path=io_path(21, 71, data=b"\x01\x02"))
    refusal("configuration data without a configuration point: 0x0129", [0x0129],
            path=cls + pt(21) + pt(71) + bytes([0x80, 0x01, 0x01, 0x02]))
    return rows


def sequence(protocol):
    """[(area, name, callable)] in order: setup, matrix, ownership, limits, Forward_Close, teardown."""
    o = Opener()
    state = {}
    steps = []

    def step(area, name):
        def register(fn):
            steps.append((area, name, fn))
            return fn
        return register

    @step(AREA, "(setup) an exclusive owner 21/71 from NEG_IP opens and is fed at its RPI")
    def setup():
        state["client"] = c = Client(CARD, source=NEG)
        c.register_session()
        t = state["owner"] = o.triad()
        o_t, t_o = open_ok(c, o.request(t), t)
        state["owner_io"] = endpoint().add(IoConnection(o_t, t_o, 10000, data=bytes(4), name="owner"))

    for name, request, want in matrix_rows(o):
        steps.append((AREA, name, lambda r=request, w=want: expect_raw(state["client"], r, w)))

    @step(LIMITS, "the same triad again: 0x0100")
    def duplicate():
        t = state["owner"]
        expect_raw(state["client"], o.request(t, t_o_id=0x7100FFFF), refused_bytes(t, [0x0100]))

    @step(LIMITS, "a second exclusive owner of 21: 0x0106")
    def second_owner():
        t = o.triad()
        expect_raw(state["client"], o.request(t, path=io_path(21, 70)), refused_bytes(t, [0x0106]))

    @step(LIMITS, "listen only 198/70 without a connection producing 70: 0x0119")
    def lonely_listener():
        t = o.triad()
        expect_raw(state["client"], o.request(t, path=io_path(198, 70), o_t_size=2), refused_bytes(t, [0x0119]))

    @step(LIMITS, "listen only 198/71 joins the owner's point-to-point production (OpENer #279), then closes")
    def listener_on_p2p():
        t = o.triad()
        open_ok(state["client"], o.request(t, path=io_path(198, 71), o_t_size=2, t_o_size=6), t)
        close_ok(state["client"], t, io_path(198, 71))

    @step(LIMITS, "explicit Set of output 21 while the owner holds it: 0x10")
    def owned_assembly():
        got = state["client"].cip(mr_request(0x10, epath(0x04, 21, 3), bytes(4))).raw()
        if got != bytes([0x90, 0, 0x10, 0]):
            raise Failure(f"got {hexs(got)}")

    @step(LIMITS, "Control Supervisor Run1 = 1 while 21 is owned: 0x10 (nothing runs)")
    def owned_supervisor():
        got = state["client"].cip(mr_request(0x10, epath(0x29, 1, 3), b"\x01")).raw()
        if got != bytes([0x90, 0, 0x10, 0]):
            raise Failure(f"got {hexs(got)}")

    def multicast(t, **changes):
        """Input only 199/151 with a multicast T->O at 100 ms (a heartbeat O->T with the run/idle header)."""
        shape = dict(path=io_path(199, 151), o_t_size=6, t_o_size=10, t_o_kind=TYPE_MULTICAST, o_t_rpi=100000,
                     t_o_rpi=100000, multiplier=7, t_o_id=0)
        shape.update(changes)
        return o.request(t, **shape)

    state["opened"] = []  # (triad, path) to close at the end

    for n in range(4):
        @step(LIMITS, f"(setup) input only 199/151 with multicast T->O, {n + 1} of 4 sharing the production "
                      "(the group in a socket address item)")
        def multicast_join():
            t = o.triad()
            open_ok(state["client"], multicast(t), t, (100000, 100000), multicast=True)
            state["opened"].append((t, io_path(199, 151)))

        if n == 0:
            @step(LIMITS, "joining the multicast production with another T->O RPI: 0x0112 with the production's RPI")
            def multicast_rpi():
                t = o.triad()
                expect_raw(state["client"], multicast(t, t_o_rpi=50000),
                           refused_bytes(t, rpi_refusal_words(0x0112, 0, 4, 100000, 100000)))

            @step(LIMITS, "joining it with another T->O size: 0x0128 naming the production's size (10)")
            def multicast_size():
                t = o.triad()
                expect_raw(state["client"], multicast(t, t_o_size=8), refused_bytes(t, [0x0128, 10]))

    @step(LIMITS, "a 5th class 1 connection on point 151: 0x011A")
    def per_point():
        t = o.triad()
        expect_raw(state["client"], multicast(t), refused_bytes(t, [0x011A]))

    def set_groups(data):
        got = state["client"].cip(mr_request(0x10, epath(0xF5, 1, 9), bytes.fromhex(data))).raw()
        if got != bytes([0x90, 0, 0, 0]):
            raise Failure(f"Set TCP/IP 9 {data}: {hexs(got)}")

    steps.append((LIMITS, "(setup) TCP/IP 9: one multicast group (239.192.1.0), the one 151's production has",
                  lambda: set_groups("01 00 01 00 00 01 C0 EF")))

    @step(LIMITS, "a new multicast production (199/150) without a group left: 0x0113")
    def no_group():
        t = o.triad()
        expect_raw(state["client"], multicast(t, path=io_path(199, 150), t_o_size=6), refused_bytes(t, [0x0113]))

    steps.append((LIMITS, "(restore) TCP/IP 9: allocation control 0 (the CIP default)",
                  lambda: set_groups("00 00 00 00 00 00 00 00")))

    explicit = lambda t: o.request(t, path=ROUTER_PATH, transport=CLASS3_SERVER_APPLICATION, o_t_size=504,  # noqa: E731
                                   t_o_size=504, o_t_rpi=1_000_000, t_o_rpi=1_000_000, multiplier=7)
    for n in range(6):
        @step(LIMITS, f"(setup) class 3 connection {n + 1} of 6")
        def class3_open():
            t = o.triad()
            o_t, t_o = open_ok(state["client"], explicit(t), t, (1_000_000, 1_000_000))
            state["opened"].append((t, ROUTER_PATH))
            state["class3"] = (o_t, t_o)

    @step(LIMITS, "a 7th class 3 connection: 0x011A")
    def class3_limit():
        t = o.triad()
        expect_raw(state["client"], explicit(t), refused_bytes(t, [0x011A]))

    @step(LIMITS, "class 3 request on another session: no reply")
    def class3_foreign():
        o_t, t_o = state["class3"]
        if ExplicitConnection(protocol.other_client(), o_t, t_o).request(1, GET_VENDOR, wait=0.3) is not None:
            raise Failure("the other session was answered")

    for n, (produced, size) in enumerate(((70, 6), (70, 6), (70, 6), (70, 6), (150, 6))):
        @step(LIMITS, f"(setup) input only 199/{produced} ({n + 12} of 16 connections)")
        def fill(produced=produced, size=size):
            t = o.triad()
            open_ok(state["client"], o.request(t, path=io_path(199, produced), o_t_size=6, t_o_size=size,
                                               o_t_rpi=100000, t_o_rpi=100000, multiplier=7), t, (100000, 100000))
            state["opened"].append((t, io_path(199, produced)))

    @step(LIMITS, "a 17th connection (the table holds 16): 0x0113")
    def table_full():
        t = o.triad()
        request = o.request(t, path=io_path(199, 152), o_t_size=6, t_o_size=14, o_t_rpi=100000, t_o_rpi=100000,
                            multiplier=7)
        expect_raw(state["client"], request, refused_bytes(t, [0x0113]))

    @step(CLOSE, "Forward_Close of a triad nobody opened: 0x0107")
    def close_unknown():
        t = o.triad()
        expect_raw(state["client"], forward_close(t, io_path(21, 71)), refused_bytes(t, [0x0107], service=FORWARD_CLOSE))

    @step(CLOSE, "Forward_Close of the owner from another IP address (HOST_IP): 0x0107")
    def close_foreign():
        t = state["owner"]
        with Client(CARD, source=HOST) as other:
            other.register_session()
            expect_raw(other, forward_close(t, io_path(21, 71)), refused_bytes(t, [0x0107], service=FORWARD_CLOSE))

    @step(CLOSE, "Forward_Close cut inside the triad: 0x13, no data")
    def close_short():
        expect_raw(state["client"], forward_close(o.triad(), b"")[:6 + 8], bytes([0xCE, 0, 0x13, 0]))

    @step(CLOSE, "Forward_Close with bytes after the path: 0x15 with the triad")
    def close_long():
        t = o.triad()
        expect_raw(state["client"], forward_close(t, io_path(21, 71)) + b"\x00\x00",
                   bytes([0xCE, 0, 0x15, 0]) + t.bytes() + b"\x00\x00")

    @step(CLOSE, "(teardown) every connection of the matrix closes with Forward_Close")
    def teardown():
        for t, path in state["opened"]:
            close_ok(state["client"], t, path)
        close_ok(state["client"], state["owner"], io_path(21, 71))
        endpoint().remove(state["owner_io"])

    @step(CLOSE, "Forward_Close of the owner again: 0x0107")
    def close_twice():
        t = state["owner"]
        expect_raw(state["client"], forward_close(t, io_path(21, 71)), refused_bytes(t, [0x0107], service=FORWARD_CLOSE))
        state["client"].close()

    return steps


# ---- Health: a healthy client from HOST_IP after everything above --------------------------------------

def health(protocol):
    checks = []

    def check(name):
        def register(fn):
            checks.append((name, fn))
            return fn
        return register

    state = {}

    @check("a new client registers a session and reads the vendor ID")
    def session():
        protocol.close_all()
        state["c"] = c = Client(CARD, source=HOST)
        if c.register_session().status != 0:
            raise Failure("RegisterSession refused")
        got = c.get_attribute_single(0x01, 1, 1).raw()
        if got != VENDOR_REPLY:
            raise Failure(f"got {hexs(got)}")

    @check("a Set of TCP/IP TTL is stored and read back, then restored")
    def ttl():
        c = state["c"]
        before = c.get_attribute_single(0xF5, 1, 8).raw()
        if before[:4] != bytes([0x8E, 0, 0, 0]) or len(before) != 5:
            raise Failure(f"Get TTL: {hexs(before)}")
        new = 1 + before[4] % 200
        for value in (new, before[4]):
            got = c.set_attribute_single(0xF5, 1, 8, bytes([value])).raw()
            back = c.get_attribute_single(0xF5, 1, 8).raw()
            if got != bytes([0x90, 0, 0, 0]) or back != bytes([0x8E, 0, 0, 0, value]):
                raise Failure(f"Set TTL {value}: {hexs(got)}, read back {hexs(back)}")

    @check("an exclusive owner 21/71 opens, I/O runs at 10 ms, Forward_Close stops it")
    def io():
        c, o = state["c"], Opener()
        o.serial = 0x0900
        t = o.triad()
        o_t, t_o = open_ok(c, o.request(t), t)
        ep = endpoint()
        conn = ep.add(IoConnection(o_t, t_o, 10000, data=bytes(4), name="healthy owner"))
        start = ep.count(t_o)
        if not ep.wait_count(t_o, start + 30, 3.0):
            raise Failure(f"{ep.count(t_o) - start} T->O datagrams in 3 s at RPI 10 ms")
        received = ep.since(t_o, start)
        if any(len(r.data) != 4 for r in received):
            raise Failure(f"T->O data sizes {[len(r.data) for r in received][:10]}")
        encap, cip = sequence_steps(received)
        if set(encap) != {1} or set(cip) != {1}:
            raise Failure(f"sequence steps {sorted(set(encap))} / {sorted(set(cip))}")
        close_ok(c, t, io_path(21, 71))
        ep.remove(conn)
        time.sleep(0.1)
        settled = ep.count(t_o)
        time.sleep(0.2)
        if ep.count(t_o) != settled:
            raise Failure("T->O datagrams after Forward_Close")

    @check("a class 3 connection answers Get over SendUnitData (and a repeated count with the stored reply)")
    def class3():
        c, o = state["c"], Opener()
        o.serial = 0x0A00
        t = o.triad()
        request = o.request(t, path=ROUTER_PATH, transport=CLASS3_SERVER_APPLICATION, o_t_size=504, t_o_size=504,
                            o_t_rpi=1_000_000, t_o_rpi=1_000_000, multiplier=2)
        o_t, t_o = open_ok(c, request, t, (1_000_000, 1_000_000))
        x = ExplicitConnection(c, o_t, t_o)
        for sequence_count in (1, 1, 2):
            got = x.request(sequence_count, GET_VENDOR)
            if got != (t_o, sequence_count, VENDOR_REPLY):
                raise Failure(f"class 3 sequence {sequence_count}: {got}")
        close_ok(c, t, ROUTER_PATH)

    @check("UnRegisterSession closes the healthy client's connection")
    def unregister():
        if not state["c"].unregister_session():
            raise Failure("the card did not close")
        state["c"].close()

    @check("the card process is alive")
    def alive():
        card_alive()
        if _endpoint:
            _endpoint[0].close()
            if _endpoint[0].errors:
                raise Failure(f"T->O datagrams that did not decode: {_endpoint[0].errors[:3]}")

    return checks
