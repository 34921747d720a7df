#!/usr/bin/env bash
# CIP connections end to end over TAP in a namespace (tools/netns): the Connection Manager, class 1 I/O on
# UDP 2222, class 3 over SendUnitData, the drive assemblies against the simulated inverter, the loss
# supervision (c100/c101) and deferred replies of the drive objects. Our scanner side is eip_io.py (on
# eip_originator.py). Expected bytes and codes come from docs/connections.md, docs/drive-profile.md and
# docs/drive-objects.md; docs/eip-tests.md "integration.eip_io" describes every check.
#
# Card started with c500=1 c101=1 acc=5 dec=5 sr3=2500 (integration.eip_io, --pcap):
#   io     exclusive owner 21/71 at RPI 2 ms and 1 ms (reply bytes, T->O sequence and jitter, run, at
#          reference, stop, trip, fault reset); 100/150 (4 and 16 bytes), 102/152; multicast T->O shared by
#          two connections; input only and listen only; class 3; the Forward_Open refusal matrix (from a
#          second address, NEG_IP); deferred replies of 0x64/0x65 (Get, Set, MSP, missing instances),
#          0x28/0x29/0x2A
#   loss   c101 = 0..5 (set in the inverter, then f899 = 1 through the Parameter object: the card reloads),
#          the reaction time of the inverter after the O->T datagrams stop (RPI 10 ms, multiplier 0:
#          timeout 40 ms), c100 = 1.0 s, idle; a new connection in run mode restores
#   tshark no malformed frame and no expert warning in the card's traffic; every UDP 2222 frame is CIP I/O
# The card runs with SCHED_FIFO priority and the checks one step below (chrt), so that a shared host's load
# does not enter the timing checks.
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CARD_IP HOST_IP CARD_MAC CARD_CONTROL CARD_LOG
export NEG_IP="${HOST_IP%.*}.3"
PY=/usr/bin/python3

read -r -d '' CHECKS <<'PY' || true
import os, socket, struct, sys, time
from eip_originator import *
from eip_io import *

sys.setswitchinterval(0.0005)  # the I/O thread gets the interpreter quickly while the checks run
CARD = os.environ["CARD_IP"]
HOST = os.environ["HOST_IP"]
NEG_IP = os.environ["NEG_IP"]
HOST_ID = int(CARD.rsplit(".", 1)[1])  # the /24 host ID: the card's multicast block (docs/connections.md)
GROUP = socket.inet_ntoa(struct.pack(">I", 0xEFC00100 + ((HOST_ID - 1) & 0x3FF) * 32))
checks = 0
sim = SimControl(os.environ["CARD_CONTROL"])


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def ok(message):
    print(f"ok: {message}", flush=True)


def show(value):
    return hexs(value) if isinstance(value, (bytes, bytearray)) else repr(value)


def same(what, got, want):
    global checks
    checks += 1
    if got != want:
        fail(f"{what}:\n  got      {show(got)}\n  expected {show(want)}")


def check(what, condition, detail=""):
    global checks
    checks += 1
    if not condition:
        fail(f"{what} {detail}")


def H(text):
    return bytes.fromhex(text.replace("|", " "))


def ask(c, request, want, what):
    """One unconnected message router request; the whole reply must be `want`."""
    got = c.cip(H(request) if isinstance(request, str) else request).raw()
    same(f"{what} (request {hexs(H(request) if isinstance(request, str) else request)})", got,
         H(want) if isinstance(want, str) else want)
    return got


def get(class_id, instance, attribute):
    return mr_request(GET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute))


def set_(class_id, instance, attribute, value):
    return mr_request(SET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute), value)


def u16(value):
    return struct.pack("<H", value & 0xFFFF)


def stat(name):
    return int(sim.stats()[name])


def wait_until(what, predicate, limit, step=0.01):
    deadline = time.monotonic() + limit
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            fail(f"{what}: not within {limit} s")
        time.sleep(step)


def wait_drive(what, limit=3.0, **fields):
    """The simulated inverter's status reaches every field given (status JSON names)."""
    global checks
    checks += 1
    last = {}

    def reached():
        nonlocal last
        last = sim.status()
        return all(last.get(k) == v for k, v in fields.items())

    deadline = time.monotonic() + limit
    while not reached():
        if time.monotonic() > deadline:
            fail(f"{what}: inverter status {last}, expected {fields} within {limit} s")
        time.sleep(0.01)
    return last


def wait_t_o(ep, t_o_id, want, what, limit=3.0):
    global checks
    checks += 1
    reached, newest = ep.wait_data(t_o_id, H(want) if isinstance(want, str) else want, limit)
    if not reached:
        fail(f"{what}: T->O data {show(newest)}, expected {want} within {limit} s")


def open_ok(c, triad, path, rpi, o_t_size, t_o_size, t_o_id, what, multiplier=2, t_o_kind=TYPE_P2P, large=False,
            transport=CLASS1_CYCLIC, o_t_variable=False, t_o_variable=False, t_o_rpi=None):
    """A Forward_Open that must succeed: the reply is exactly the success layout with API = RPI; the card's
    O->T ID is new and not 0; point-to-point T->O uses our ID. Returns (O->T ID, T->O ID, extra items)."""
    t_o_rpi = rpi if t_o_rpi is None else t_o_rpi
    request = forward_open(triad, path, rpi, net_params(o_t_size, variable=o_t_variable, large=large), t_o_rpi,
                           net_params(t_o_size, kind=t_o_kind, variable=t_o_variable, large=large),
                           transport=transport, t_o_id=t_o_id, multiplier=multiplier, large=large)
    mr, raw, extra = open_connection(c, request)
    if mr.general != 0:
        fail(f"{what}: Forward_Open refused: {hexs(raw)}")
    reply = decode_open_success(mr.data)
    check(f"{what}: O->T connection ID chosen by the card", reply["o_t_id"] not in (0, t_o_id), hex(reply["o_t_id"]))
    expected_t_o = t_o_id if t_o_kind == TYPE_P2P else reply["t_o_id"]
    if t_o_kind != TYPE_P2P:
        check(f"{what}: multicast T->O ID chosen by the card", reply["t_o_id"] not in (0, t_o_id, reply["o_t_id"]))
    same(f"{what}: Forward_Open reply", raw,
         open_success_bytes(reply["o_t_id"], expected_t_o, triad, rpi, t_o_rpi,
                            LARGE_FORWARD_OPEN if large else FORWARD_OPEN))
    if t_o_kind == TYPE_P2P:
        same(f"{what}: no T->O socket address item point-to-point", extra, [])
    return reply["o_t_id"], reply["t_o_id"], extra


def close_ok(c, triad, path, what):
    mr, raw, extra = open_connection(c, forward_close(triad, path))
    same(f"{what}: Forward_Close reply", (raw, extra), (close_success_bytes(triad), []))


def refused(c, request, triad, words, what, remaining=0, service=FORWARD_OPEN):
    mr, raw, extra = open_connection(c, request)
    same(what, raw, refused_bytes(triad, words, remaining, service))


def finish(c, ep, conn, triad, path, what, check_stop=True):
    """Stops our O->T datagrams, then Forward_Close (so that no datagram of ours follows the close)."""
    ep.stop_sending(conn)
    close_ok(c, triad, path, what)
    if check_stop:
        stopped_sending(ep, conn.t_o_id, what)
    ep.remove(conn)


def stopped_sending(ep, t_o_id, what, settle=0.15, window=0.3):
    """After a close, the productions stop (one may still be on its way)."""
    time.sleep(settle)
    before = ep.count(t_o_id)
    time.sleep(window)
    same(f"{what}: no T->O datagram after the close", ep.count(t_o_id), before)


def check_sequence(received, what):
    """Encapsulation sequence number and CIP sequence count +1 from each T->O datagram to the next: every
    production is new data, and none was lost on the way."""
    encap, cip = sequence_steps(received)
    bad = [i for i, (e, s) in enumerate(zip(encap, cip)) if e != 1 or s != 1]
    check(f"{what}: encapsulation sequence and CIP sequence count advance by 1 per datagram", len(received) > 1 and not bad,
          f"({len(received)} datagrams, {len(bad)} steps differ: {[(encap[i], cip[i]) for i in bad[:5]]})")


def stream_line(s, rpi_us):
    return (f"{s['n']} intervals, mean {s['mean']:.1f} us, p50 {s['p50']:.1f}, p99 {s['p99']:.1f}, max {s['max']:.1f}, "
            f"min {s['min']:.1f} (RPI {rpi_us} us)")


def check_stream(received, rpi_us, what):
    """One window: sequence +1 throughout; the intervals are printed (timing is measure_stream's)."""
    check_sequence(received, what)
    intervals, s = interval_stats(received)
    print(f"   {what}: {stream_line(s, rpi_us)}", flush=True)
    return s


def measure_stream(ep, t_o_id, rpi_us, what, seconds=1.5, windows=3):
    """T->O timing over windows of `seconds`: every window must have its sequence numbers +1 throughout
    and a median interval within 5 % of the RPI. The jitter (intervals above 4 x RPI, the card's missed
    slots) is printed, not asserted: the host is shared (other tests, builds, fuzzers on 2 CPUs), and a
    window the kernel did not schedule the card in says nothing about the firmware. tools/bench/eip-io
    measures the jitter itself. Returns the window with the fewest late intervals."""
    best = None
    for k in range(1, windows + 1):
        missed = stat("cip.missed_productions")
        start = ep.count(t_o_id)
        time.sleep(seconds)
        received = ep.since(t_o_id, start)
        check_sequence(received, f"{what} window {k}")
        intervals, s = interval_stats(received)
        missed = stat("cip.missed_productions") - missed
        late = [x for x in intervals if x > 4 * rpi_us]
        print(f"   {what} window {k}: {stream_line(s, rpi_us)}; {len(late)} above 4 x RPI; card: {missed} missed slots",
              flush=True)
        check(f"{what} window {k}: median interval within 5 % of the RPI", abs(s["p50"] - rpi_us) <= 0.05 * rpi_us, f"{s}")
        if best is None or len(late) < best[0]:
            best = (len(late), s)
        if not late:
            break
    return best[1]


# ---- io: connections, drive assemblies, class 3, refusals, deferred replies -------------------------------

def exclusive_owner_21_71(c, ep):
    path = io_path(21, 71)
    triad = Triad(0x0101)
    t_o_id = 0x71000001
    o_t_id, _, _ = open_ok(c, triad, path, 2000, 2 + 4 + 4, 2 + 4, t_o_id, "21/71 RPI 2 ms", multiplier=5)
    conn = ep.add(IoConnection(o_t_id, t_o_id, 2000, H("60 00 00 00"), name="21/71"))
    wait_t_o(ep, t_o_id, "70 03 00 00", "71 of a stopped drive with NetCtrl/NetRef: Ready, state 3 Ready")
    same("Identity status with an I/O connection in run mode (bits 4-7 = 0110)",
         c.get_attribute_single(0x01, 1, 5).data[0] & 0xF0, 0x60)
    ok("Forward_Open 21/71 through configuration instance 1 at RPI 2 ms: exact reply, API = RPI, T->O to us")

    ep.set(conn, H("61 00 08 07"))
    wait_drive("21 61 00 08 07 reaches the inverter", 2.0, fa06="0xC400", fa07=6000, command_priority="fa06",
               frequency_priority="fa06")
    ramp = []
    deadline = time.monotonic() + 3.0
    while True:
        hz = sim.status()["output_hz"]
        ramp.append(hz)
        if hz == 60.0 or time.monotonic() > deadline:
            break
        time.sleep(0.02)
    rising = [v for v in ramp if 0 < v < 60]
    check("output frequency ramps up to 60 Hz", ramp[-1] == 60.0 and ramp == sorted(ramp) and len(set(rising)) >= 3,
          f"{ramp}")
    wait_t_o(ep, t_o_id, "F4 04 08 07", "71 at speed: At Reference, Ref/Ctrl From Net, Ready, Running1, Enabled, 1800 rpm")
    accelerating = [r.data for r in ep.since(t_o_id) if r.data[:2] == H("74 04")]
    speeds = [struct.unpack_from("<H", d, 2)[0] for d in accelerating]
    check("71 while accelerating: 74 04 (Running1, Enabled) with the actual speed rising below 1800 rpm",
          speeds == sorted(speeds) and any(0 < v < 1800 for v in speeds), f"{speeds}")
    ok(f"21 61 00 08 07: FA06 = C400, FA07 = 1770h, output ramps ({len(ramp)} samples) to 60 Hz; 71 F4 04 08 07")

    stream_2ms = measure_stream(ep, t_o_id, 2000, "RPI 2 ms")

    # The drive objects while the drive runs under the connection (check 8, running part).
    ask(c, get(0x2A, 1, 7), "8E 00 00 00 08 07", "0x2A SpeedActual at 60 Hz (deferred: FD00)")
    ask(c, get(0x2A, 1, 3), "8E 00 00 00 01", "0x2A AtReference (deferred: FD00, FE02)")
    ask(c, get(0x2A, 1, 29), "8E 00 00 00 01", "0x2A RefFromNet")
    ask(c, get(0x29, 1, 6), "8E 00 00 00 04", "0x29 State Enabled")
    ask(c, get(0x29, 1, 7), "8E 00 00 00 01", "0x29 Running1")
    ask(c, get(0x29, 1, 15), "8E 00 00 00 01", "0x29 CtrlFromNet")
    ask(c, set_(0x29, 1, 3, b"\x00"), "90 00 10 00", "0x29 Set Run1 while an exclusive owner consumes 21: 0x10")
    ask(c, set_(0x2A, 1, 8, b"\x00\x00"), "90 00 10 00", "0x2A Set SpeedRef while 21 is owned: 0x10")
    ask(c, set_(0x04, 21, 3, b"\x00\x00\x00\x00"), "90 00 10 00", "Set of the owned output assembly 21: 0x10")
    ask(c, get(0x04, 71, 3), "8E 00 00 00 F4 04 08 07", "explicit Get of input assembly 71")
    ok("0x29/0x2A while running: SpeedActual 1800 rpm, AtReference, State 4, ownership refusals 0x10")

    ep.set(conn, H("60 00 00 00"))
    wait_drive("21 60 00 00 00 stops the drive", 2.0, state="stopped", fa06="0xC000", output_hz=0.0)
    wait_t_o(ep, t_o_id, "70 03 00 00", "71 stopped")
    ok("21 60 00 00 00: the drive decelerates to a stop, 71 70 03 00 00")

    same("trip command", sim.command("trip 1"), [])
    wait_t_o(ep, t_o_id, "61 07 00 00", "71 Faulted: Faulted bit, state 7 Faulted, Ctrl/Ref From Net")
    ask(c, get(0x29, 1, 10), "8E 00 00 00 01", "0x29 Faulted")
    ep.set(conn, H("64 00 00 00"))  # fault reset: bit 2, 0 -> 1
    wait_drive("fault reset through 21 bit 2 clears the trip", 4.0, trip=0, state="stopped")
    wait_t_o(ep, t_o_id, "70 03 00 00", "71 after the fault reset: Ready, state 3")
    ep.set(conn, H("60 00 00 00"))
    ok("trip 1 -> 71 61 07 00 00; 21 bit 2 edge: the trip is reset, 71 70 03 00 00 again")

    finish(c, ep, conn, triad, path, "21/71")

    triad = Triad(0x0102)
    t_o_id = 0x71000002
    o_t_id, _, _ = open_ok(c, triad, path, 1000, 10, 6, t_o_id, "21/71 RPI 1 ms", multiplier=6)
    conn = ep.add(IoConnection(o_t_id, t_o_id, 1000, H("60 00 00 00"), name="21/71 1 ms"))
    wait_t_o(ep, t_o_id, "70 03 00 00", "71 at RPI 1 ms")
    stream_1ms = measure_stream(ep, t_o_id, 1000, "RPI 1 ms")
    finish(c, ep, conn, triad, path, "21/71 1 ms")
    ok("21/71 at RPI 1 ms: API 1000 us, every datagram in sequence, median interval within 5 % of the RPI")
    return stream_2ms, stream_1ms


def native_assemblies(c, ep):
    # 100/150, 4 bytes.
    path = io_path(100, 150)
    triad = Triad(0x0201)
    t_o_id = 0x15000001
    o_t_id, _, _ = open_ok(c, triad, path, 10000, 2 + 4 + 4, 2 + 4, t_o_id, "100/150 4 bytes")
    conn = ep.add(IoConnection(o_t_id, t_o_id, 10000, H("00 00 00 00"), name="100/150"))
    wait_t_o(ep, t_o_id, "00 48 00 00", "150 stopped (FD01 4800h)")
    ep.set(conn, H("00 C4 70 17"))
    wait_drive("100 00 C4 70 17", 2.0, fa06="0xC400", fa07=6000)
    wait_t_o(ep, t_o_id, "00 64 70 17", "150 at 60 Hz (FD01 6400h, FD00 1770h)")
    ep.set(conn, H("00 00 00 00"))
    wait_drive("100 00 00 00 00 stops", 2.0, state="stopped", output_hz=0.0, fa06="0x0000")
    wait_t_o(ep, t_o_id, "00 48 00 00", "150 stopped again")
    finish(c, ep, conn, triad, path, "100/150")
    ok("100/150 of 4 bytes: 00 C4 70 17 -> FA06 C400h, FA07 1770h; 150 00 64 70 17 at 60 Hz, 00 48 00 00 stopped")

    # 100/150, 16 bytes: words 3-8 are c001-c006 / c021-c026 (factory: FA06, FA07 / FD01, FD00, then 0).
    triad = Triad(0x0202)
    t_o_id = 0x15000002
    o_t_id, _, _ = open_ok(c, triad, path, 10000, 2 + 4 + 16, 2 + 16, t_o_id, "100/150 16 bytes", large=True)
    conn = ep.add(IoConnection(o_t_id, t_o_id, 10000, H("00 C4 70 17 | 11 11 22 22 33 33 44 44 55 55 66 66"),
                               name="100/150 16"))
    wait_drive("100 (16 bytes) 00 C4 70 17: words 3-4 (c001 on FA06, c002 on FA07) are not written", 2.0,
               fa06="0xC400", fa07=6000)
    wait_t_o(ep, t_o_id, "00 64 70 17 | 00 64 70 17 00 00 00 00 00 00 00 00", "150 (16 bytes) at 60 Hz: c021 FD01, c022 FD00")
    ep.set(conn, H("00 00 00 00 | 00 00 00 00 00 00 00 00 00 00 00 00"))
    wait_drive("100 (16 bytes) stop", 2.0, state="stopped", output_hz=0.0)
    wait_t_o(ep, t_o_id, "00 48 00 00 | 00 48 00 00 00 00 00 00 00 00 00 00", "150 (16 bytes) stopped")
    finish(c, ep, conn, triad, path, "100/150 16 bytes")
    ok("100/150 of 16 bytes (Large_Forward_Open): FA06/FA07 from words 1-2 only; 150 words 3-8 = c021-c026")

    # 102/152: scanner words with the factory menus c001 = 1 (FA06), c002 = 3 (FA07), c021 = 1 (FD01),
    # c022 = 2 (FD00), c003-c006 = c023-c026 = 0.
    path = io_path(102, 152)
    triad = Triad(0x0203)
    t_o_id = 0x15200001
    o_t_id, _, _ = open_ok(c, triad, path, 10000, 2 + 4 + 12, 2 + 12, t_o_id, "102/152")
    conn = ep.add(IoConnection(o_t_id, t_o_id, 10000, H("00 C4 70 17 00 00 00 00 00 00 00 00"), name="102/152"))
    wait_drive("102 word 1 -> FA06 (c001 = 1), word 2 -> FA07 (c002 = 3)", 2.0, fa06="0xC400", fa07=6000)
    wait_t_o(ep, t_o_id, "00 64 70 17 00 00 00 00 00 00 00 00", "152 at 60 Hz: FD01 (c021 = 1), FD00 (c022 = 2)")
    ep.set(conn, H("00 00 00 00 00 00 00 00 00 00 00 00"))
    wait_drive("102 stop", 2.0, state="stopped", output_hz=0.0, fa06="0x0000")
    wait_t_o(ep, t_o_id, "00 48 00 00 00 00 00 00 00 00 00 00", "152 stopped")
    finish(c, ep, conn, triad, path, "102/152")
    ok("102/152 with the factory menus: scanner words 1-2 on FA06/FA07, 152 = FD01, FD00, 0 x 4")


def multicast(c, ep):
    path = io_path(21, 71)
    triad = Triad(0x0301)
    o_t_id, t_o_id, extra = open_ok(c, triad, path, 5000, 10, 6, 0x77000001, "21/71 multicast", t_o_kind=TYPE_MULTICAST)
    sockaddr = struct.pack(">HH", 2, IO_PORT) + socket.inet_aton(GROUP) + bytes(8)
    same("multicast T->O socket address item (0x8001: AF_INET, 2222, the group)", extra, [(ITEM_SOCKADDR_T_O, sockaddr)])
    same("socket address decoded", decode_sockaddr(extra[0][1]), (2, 2222, GROUP))
    ep.join(GROUP, HOST)
    owner = ep.add(IoConnection(o_t_id, t_o_id, 5000, H("60 00 00 00"), name="multicast owner"))
    wait_t_o(ep, t_o_id, "70 03 00 00", "multicast productions of 71 received from the group")
    newest = ep.latest(t_o_id)
    same("T->O datagrams go to the group from the card", (newest.destination, newest.source), (GROUP, (CARD, IO_PORT)))
    ok(f"multicast T->O: group {GROUP} (239.192.1.0 + (host ID - 1) x 32), card-chosen T->O ID 0x{t_o_id:08X}")

    # A second connection to the same point (input only, multicast) shares group, ID and production.
    triad2 = Triad(0x0302)
    path2 = io_path(199, 71)
    o_t_id2, t_o_id2, extra2 = open_ok(c, triad2, path2, 5000, 2, 6, 0x77000002, "input only 199/71 multicast",
                                       t_o_kind=TYPE_MULTICAST)
    same("second multicast connection: same T->O connection ID and group", (t_o_id2, extra2),
         (t_o_id, [(ITEM_SOCKADDR_T_O, sockaddr)]))
    heartbeat = ep.add(IoConnection(o_t_id2, t_o_id2, 5000, b"", header=False, name="multicast input only"))
    # The joining one must ask for the production's RPI: 0x0112 with the RPI it must use.
    triad3 = Triad(0x0303)
    request = forward_open(triad3, path2, 5000, net_params(2), 10000, net_params(6, kind=TYPE_MULTICAST),
                           t_o_id=0x77000003, multiplier=2)
    refused(c, request, triad3, rpi_refusal_words(0x0112, 0, 4, 5000, 5000),
            "multicast join with another T->O RPI: 0x0112, T->O type 4 with the production's RPI")
    time.sleep(0.2)
    start = ep.count(t_o_id)
    time.sleep(1.0)
    shared = ep.since(t_o_id, start)
    check("one production for both: about 200 datagrams per second at 5 ms, not 400", 180 <= len(shared) <= 220,
          f"({len(shared)})")
    check_stream(shared, 5000, "multicast RPI 5 ms, two connections")
    finish(c, ep, heartbeat, triad2, path2, "multicast input only", check_stop=False)
    time.sleep(0.2)
    before = ep.count(t_o_id)
    time.sleep(0.3)
    check("the production goes on for the remaining connection", ep.count(t_o_id) - before >= 40)
    finish(c, ep, owner, triad, path, "multicast owner")
    ep.leave(GROUP, HOST)
    ok("a second multicast connection (input only 199) shares the group, T->O ID and the one production; RPI mismatch 0x0112")


def input_and_listen_only(c, ep):
    listen_path = io_path(198, 71)
    input_path = io_path(199, 71)
    lonely = Triad(0x0401)
    request = forward_open(lonely, listen_path, 10000, net_params(2), 10000, net_params(6), t_o_id=0x19800001,
                           multiplier=2)
    refused(c, request, lonely, [0x0119], "listen only 198/71 without a connection producing 71: 0x0119")

    triad_in = Triad(0x0402)
    o_t_in, t_o_in, _ = open_ok(c, triad_in, input_path, 10000, 2, 6, 0x19900001, "input only 199/71")
    feeder = ep.add(IoConnection(o_t_in, t_o_in, 10000, b"", header=False, name="input only"))
    wait_t_o(ep, t_o_in, "10 03 00 00", "71 to an input-only connection: Ready, state 3 (no NetCtrl/NetRef held)")
    triad_listen = Triad(0x0403)
    o_t_l, t_o_l, _ = open_ok(c, triad_listen, listen_path, 10000, 2, 6, 0x19800002, "listen only 198/71")
    listener = ep.add(IoConnection(o_t_l, t_o_l, 10000, b"", header=False, name="listen only"))
    wait_t_o(ep, t_o_l, "10 03 00 00", "71 to the listen-only connection")
    same("Identity status: class 1 connections open, none in run mode (0111)",
         c.get_attribute_single(0x01, 1, 5).data[0] & 0xF0, 0x70)
    # A heartbeat with a run/idle header (O->T size 6) is accepted too.
    triad_hdr = Triad(0x0404)
    o_t_h, t_o_h, _ = open_ok(c, triad_hdr, input_path, 10000, 6, 6, 0x19900002, "input only with a header")
    with_header = ep.add(IoConnection(o_t_h, t_o_h, 10000, b"", header=True, name="input only header"))
    wait_t_o(ep, t_o_h, "10 03 00 00", "71 to the input-only connection with a header")
    time.sleep(0.3)
    same("no O->T datagram dropped by the card", stat("cip.dropped_datagrams"), DROPPED_BEFORE[0])
    finish(c, ep, with_header, triad_hdr, input_path, "input only with a header")

    finish(c, ep, feeder, triad_in, input_path, "input only (the listener's producer)")
    stopped_sending(ep, t_o_l, "the listen-only connection closes with its producer", settle=0.0)
    ep.stop_sending(listener)
    refused(c, forward_close(triad_listen, listen_path), triad_listen, [0x0107],
            "Forward_Close of the listen-only connection closed with its owner: 0x0107", service=FORWARD_CLOSE)
    ep.remove(listener)
    ok("input only 199/71 and listen only 198/71 (heartbeats of 2 bytes, 6 with a header); 0x0119; the listener closes with its owner")


def class3(c):
    triad = Triad(0x0501)
    t_o_id = 0x33000001
    o_t_id, _, _ = open_ok(c, triad, ROUTER_PATH, 1000000, 500, 500, t_o_id, "class 3 to the Message Router",
                           multiplier=1, transport=CLASS3_SERVER_APPLICATION, o_t_variable=True, t_o_variable=True)
    x = ExplicitConnection(c, o_t_id, t_o_id)
    vendor = mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1, 1))
    name = mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1, 7))
    same("class 3 seq 1: Identity attribute 1", x.request(1, vendor), (t_o_id, 1, H("8E 00 00 00 79 01")))
    same("class 3 seq 1 repeated: the same reply", x.request(1, vendor), (t_o_id, 1, H("8E 00 00 00 79 01")))
    same("class 3 seq 2: Identity attribute 7", x.request(2, name), (t_o_id, 2, H("8E 00 00 00 06") + b"VF-MB1"))
    # A repeated count is answered from the store, not executed again: the Ethernet Link counters (in
    # octets grow with every frame) come back identical under the same count, and larger under a new one.
    counters = mr_request(GET_ATTRIBUTE_SINGLE, epath(0xF6, 1, 4))
    first = x.request(3, counters)
    check("class 3 seq 3: Ethernet Link counters", first[:2] == (t_o_id, 3) and first[2][:4] == H("8E 00 00 00")
          and len(first[2]) == 4 + 44, f"{first}")
    same("class 3 seq 3 repeated: the stored reply, byte for byte", x.request(3, counters), first)
    newer = x.request(4, counters)
    check("class 3 seq 4: executed again, in octets grew", struct.unpack_from("<I", newer[2], 4)[0] >
          struct.unpack_from("<I", first[2], 4)[0], f"{newer}")
    acc = sim.get("acc")
    same("class 3 seq 5: a deferred Parameter Get over the connection",
         x.request(5, mr_request(GET_ATTRIBUTE_SINGLE, epath(0x65, 0x0009, 3))), (t_o_id, 5, H("8E 00 00 00") + u16(acc)))
    same("class 3 seq 5 repeated after the deferral: the stored reply",
         x.request(5, mr_request(GET_ATTRIBUTE_SINGLE, epath(0x65, 0x0009, 3))), (t_o_id, 5, H("8E 00 00 00") + u16(acc)))
    close_ok(c, triad, ROUTER_PATH, "class 3")
    same("SendUnitData after the Forward_Close: no reply", x.request(6, vendor, wait=0.5), None)
    ok("class 3: Forward_Open to 20 02 24 01, SendUnitData Get_Attribute_Single, repeated sequence count answered from the store, Forward_Close")


def negative_matrix(c, ep):
    """Every refusal from NEG_IP (requests that are wrong on purpose), exact reply bytes."""
    path = io_path(21, 71)
    healthy = Triad(0x0601)
    t_o_id = 0x66000001
    o_t_id, _, _ = open_ok(c, healthy, path, 10000, 10, 6, t_o_id, "healthy 21/71 before the refusals")
    conn = ep.add(IoConnection(o_t_id, t_o_id, 10000, H("60 00 00 00"), name="healthy"))
    wait_t_o(ep, t_o_id, "70 03 00 00", "healthy 71")
    counters = {k: stat(k) for k in ("cip.open_requests", "cip.open_format_rejects", "cip.open_other_rejects",
                                     "cip.open_resource_rejects", "cip.connections")}

    def fo(triad, path=path, o_t_rpi=10000, o_t_size=10, t_o_rpi=10000, t_o_size=6, **kw):
        return forward_open(triad, path, o_t_rpi, net_params(o_t_size), t_o_rpi, net_params(t_o_size),
                            t_o_id=0x6600FFFF, multiplier=kw.pop("multiplier", 2), **kw)

    n = 0
    with Client(CARD, source=NEG_IP) as neg:
        neg.register_session()
        cases = [
            (fo(healthy), healthy, [0x0100], 0, "duplicate triad: 0x0100"),
            (fo(Triad(0x0602)), Triad(0x0602), [0x0106], 0, "second exclusive owner of 21: 0x0106"),
            (fo(Triad(0x0603), transport=0x11), Triad(0x0603), [0x0103], 0, "class 1 change of state: 0x0103"),
            (fo(Triad(0x0604), path=ROUTER_PATH), Triad(0x0604), [0x0103], 0, "class 1 to the Message Router: 0x0103"),
            (fo(Triad(0x0605), o_t_rpi=500), Triad(0x0605), rpi_refusal_words(0x0111, 2, 0, 1000, 10000), 0,
             "O->T RPI 500 us: 0x0111 with the 1 ms floor"),
            (fo(Triad(0x0606), t_o_rpi=999), Triad(0x0606), rpi_refusal_words(0x0111, 0, 2, 10000, 1000), 0,
             "T->O RPI 999 us: 0x0111 with the 1 ms floor"),
            (fo(Triad(0x0607), path=io_path(102, 152), o_t_size=16, t_o_size=14), Triad(0x0607), [0x0127, 18], 0,
             "102 with O->T size 16: 0x0127 naming 18"),
            (fo(Triad(0x0608), path=io_path(102, 152), o_t_size=18, t_o_size=10), Triad(0x0608), [0x0128, 14], 0,
             "152 with T->O size 10: 0x0128 naming 14"),
            (fo(Triad(0x0609), path=io_path(100, 150), o_t_size=11, t_o_size=6), Triad(0x0609), [0x0127, 22], 0,
             "100 with an odd O->T size: 0x0127 naming the largest (16 bytes: 22)"),
            (fo(Triad(0x060A), path=io_path(100, 150), o_t_size=10, t_o_size=20), Triad(0x060A), [0x0128, 18], 0,
             "150 of 18 bytes: 0x0128 naming the largest (16 bytes: 18)"),
            (fo(Triad(0x060B), path=io_path(22, 71)), Triad(0x060B), [0x012A], 0, "consumed point 22: 0x012A"),
            (fo(Triad(0x060C), path=io_path(70, 71)), Triad(0x060C), [0x012F], 0,
             "input 70 as consumed point (a point of the card in the wrong role): 0x012F"),
            (fo(Triad(0x060D), path=io_path(20, 72)), Triad(0x060D), [0x012B], 0, "produced point 72: 0x012B"),
            (fo(Triad(0x060E), path=io_path(20, 70, configuration=5)), Triad(0x060E), [0x0129], 0,
             "configuration instance 5: 0x0129"),
            (fo(Triad(0x060F), path=io_path(20, 70, data=b"\x01\x02")), Triad(0x060F), [0x0126, 0], 0,
             "configuration data for instance 1 (size 0): 0x0126 naming 0"),
            (fo(Triad(0x0610), path=io_path(20, 70, key=electronic_key(vendor=378))), Triad(0x0610), [0x0114], 0,
             "electronic key vendor 378: 0x0114"),
            (fo(Triad(0x0611), path=io_path(20, 70, key=electronic_key(product=32001))), Triad(0x0611), [0x0114], 0,
             "electronic key product code 32001 (a VF-S15) on a VF-MB1: 0x0114"),
            (fo(Triad(0x0612), path=io_path(20, 70, key=electronic_key(device_type=12))), Triad(0x0612), [0x0115], 0,
             "electronic key device type 12: 0x0115"),
            (fo(Triad(0x0613), path=io_path(20, 70, key=electronic_key(minor=9))), Triad(0x0613), [0x0116], 0,
             "electronic key revision 1.9: 0x0116"),
            (fo(Triad(0x0614), multiplier=8), Triad(0x0614), [0x0133], 0, "timeout multiplier 8: 0x0133"),
            (fo(Triad(0x0615), path=H("20 04 24 01 2C 14 91 02 41 42")), Triad(0x0615), [0x0315], 5,
             "a symbolic segment in the path: 0x0315, remaining path size 5"),
            (fo(Triad(0x0616), path=H("20 01 24 01")), Triad(0x0616), [0x0315], 2, "Identity as target: 0x0315"),
            (fo(Triad(0x0617), path=H("05 00") + io_path(20, 70)), Triad(0x0617), [0x0311], 5, "port 5: 0x0311"),
            (forward_open(Triad(0x0618), io_path(20, 70), 10000, net_params(10, kind=TYPE_MULTICAST), 10000,
                          net_params(6), t_o_id=1, multiplier=2), Triad(0x0618), [0x0123], 0, "multicast O->T: 0x0123"),
        ]
        for request, triad, words, remaining, what in cases:
            refused(neg, request, triad, words, what, remaining)
            n += 1
        refused(neg, forward_close(Triad(0x06FF), path), Triad(0x06FF), [0x0107],
                "Forward_Close of a connection that does not exist: 0x0107", service=FORWARD_CLOSE)
        refused(neg, forward_close(healthy, path), healthy, [0x0107],
                "Forward_Close from another IP address than the opener's: 0x0107", service=FORWARD_CLOSE)
        n += 2
        # A request too short to hold the fixed part: 0x13 without data.
        same("Forward_Open of 20 bytes: 0x13", open_connection(neg, fo(Triad(0x0619))[:6 + 20])[1], H("D4 00 13 00"))
        n += 1
    same("counters after the refusals (requests, format, other, resource, connections)",
         {k: stat(k) for k in counters},
         {"cip.open_requests": counters["cip.open_requests"] + 25, "cip.open_format_rejects": counters["cip.open_format_rejects"] + 4,
          "cip.open_other_rejects": counters["cip.open_other_rejects"] + 21,
          "cip.open_resource_rejects": counters["cip.open_resource_rejects"], "cip.connections": counters["cip.connections"]})
    # The healthy connection went on all along; then it closes, and a new one opens and works.
    start = ep.count(t_o_id)
    time.sleep(0.5)
    check_stream(ep.since(t_o_id, start), 10000, "healthy 21/71 after the refusals")
    finish(c, ep, conn, healthy, path, "healthy 21/71")
    again = Triad(0x0620)
    o_t_id, _, _ = open_ok(c, again, path, 10000, 10, 6, 0x66000002, "new 21/71 after the refusals")
    conn = ep.add(IoConnection(o_t_id, 0x66000002, 10000, H("60 00 00 00"), name="after"))
    wait_t_o(ep, 0x66000002, "70 03 00 00", "a new connection after the refusals")
    finish(c, ep, conn, again, path, "new 21/71")
    ok(f"Forward_Open/Forward_Close refusal matrix: {n} requests from {NEG_IP}, exact replies; the healthy connection kept producing")


def deferred_objects(c):
    deferred = stat("eip.deferred_replies")
    values = {name: sim.get(name) for name in ("acc", "dec", "fh", "ul", "cmod", "f417")}
    ask(c, get(0x64, 0x4009, 3), H("8E 00 00 00") + u16(values["acc"]), "0x64 instance 4009h (acc)")
    ask(c, get(0x64, 0x4003, 3), H("8E 00 00 00") + u16(values["cmod"]), "0x64 instance 4003h (cmod)")
    ask(c, get(0x65, 0x0011, 3), H("8E 00 00 00") + u16(values["fh"]), "0x65 instance 0011h (fh)")
    ask(c, get(0x64, 0x7D01, 3), H("8E 00 00 00") + u16(int(sim.status()["fd01"], 16)), "0x64 instance 7D01h (FD01)")
    ask(c, set_(0x65, 0x0010, 3, u16(7)), "90 00 00 00", "0x65 Set dec = 0.7 s")
    ask(c, get(0x65, 0x0010, 3), "8E 00 00 00 07 00", "0x65 Get dec back")
    same("dec in the inverter", sim.get("dec"), 7)
    ask(c, set_(0x65, 0x0010, 3, u16(values["dec"])), "90 00 00 00", "0x65 Set dec back")
    same("dec in the inverter again", sim.get("dec"), values["dec"])
    reply, members = c.multiple_service_packet([get(0x65, 0x0009, 3), get(0x65, 0x0011, 3), get(0x65, 0x0012, 3),
                                                get(0x64, 0x4003, 3), get(0x65, 0x0999, 3)])
    same("MSP of five Parameter Gets (one missing): 0x1E with every member",
         (reply.general, [m.raw() for m in members]),
         (0x1E, [H("8E 00 00 00") + u16(values["acc"]), H("8E 00 00 00") + u16(values["fh"]),
                 H("8E 00 00 00") + u16(values["ul"]), H("8E 00 00 00") + u16(values["cmod"]), H("8E 00 16 00")]))
    reply, members = c.multiple_service_packet([get(0x65, 0x0009, 3), get(0x65, 0x0010, 3)])
    same("MSP of two Parameter Gets", (reply.raw()[:4], [m.raw() for m in members]),
         (H("8A 00 00 00"), [H("8E 00 00 00") + u16(values["acc"]), H("8E 00 00 00") + u16(values["dec"])]))
    accesses = stat("cip.journal_accesses")
    ask(c, get(0x65, 0x000A, 3), "8E 00 16 00", "0x65 instance 000Ah (A-F ending): 0x16")
    ask(c, get(0x64, 0x5000, 3), "8E 00 16 00", "0x64 instance 5000h (outside the windows): 0x16")
    same("no drive access for instances that cannot exist", stat("cip.journal_accesses"), accesses)
    ask(c, get(0x65, 0x0999, 3), "8E 00 16 00", "0x65 instance 0999h (the inverter: no such register): 0x16")
    same("one drive access for 0999h", stat("cip.journal_accesses"), accesses + 1)
    ask(c, set_(0x65, 0xFD00, 3, u16(1)), "90 00 0E 00", "0x65 Set of a monitor (FD00): 0x0E")
    ask(c, set_(0x65, 0x0011, 3, u16(100)), "90 00 09 00", "0x65 Set fh = 1 Hz (out of range): 0x09")
    ask(c, get(0x29, 1, 1), "8E 00 00 00 0D 00", "0x29 NumAttr")
    ask(c, get(0x29, 1, 6), "8E 00 00 00 03", "0x29 State Ready")
    ask(c, get(0x29, 1, 9), "8E 00 00 00 01", "0x29 Ready")
    ask(c, get(0x2A, 1, 6), "8E 00 00 00 01", "0x2A DriveMode")
    ask(c, get(0x2A, 1, 7), "8E 00 00 00 00 00", "0x2A SpeedActual stopped")
    ask(c, get(0x2A, 1, 18), H("8E 00 00 00") + u16(values["acc"] * 100), "0x2A AccelTime (acc x 100 ms)")
    ask(c, get(0x2A, 1, 19), H("8E 00 00 00") + u16(values["dec"] * 100), "0x2A DecelTime")
    ask(c, get(0x2A, 1, 21), H("8E 00 00 00") + u16(values["ul"] * 3 // 10), "0x2A HighSpdLimit (ul in rpm)")
    ask(c, get(0x28, 1, 15), H("8E 00 00 00") + u16(values["f417"]), "0x28 BaseSpeed (f417)")
    check("the deferred replies went through the encapsulation server's deferral",
          stat("eip.deferred_replies") - deferred >= 15, f"({stat('eip.deferred_replies') - deferred})")
    ok("deferred replies: 0x64/0x65 Gets (values from the inverter), Set and Get back, MSP, missing instances 0x16, 0x0E, 0x09; 0x28/0x29/0x2A")


DROPPED_BEFORE = [0]  # cip.dropped_datagrams before input_and_listen_only


def io_phase():
    with Client(CARD) as c, IoEndpoint(CARD) as ep:
        same("RegisterSession", c.register_session().status, 0)
        deferred_objects(c)
        exclusive_owner_21_71(c, ep)
        native_assemblies(c, ep)
        multicast(c, ep)
        DROPPED_BEFORE[0] = stat("cip.dropped_datagrams")
        input_and_listen_only(c, ep)
        class3(c)
        negative_matrix(c, ep)
        same("undecodable datagrams on UDP 2222", ep.errors, [])
        same("connections left", stat("cip.connections"), 0)
        same("send failures of the card", stat("io.send_failed"), 0)
    print(f"   missed productions (card): {stat('cip.missed_productions')}")
    ok(f"io phase: {checks} checks")


# ---- loss: c100/c101 after an O->T timeout, idle, restore ---------------------------------------------------

LOSS_RPI = 10000     # µs, multiplier 0: timeout 40 ms
LOSS_TIMEOUT = 4 * LOSS_RPI / 1e6


def reload_config(c, c101, c100=0, c102=0):
    """Sets c100-c102 in the inverter and resets it with f899 = 1 written through the card (Parameter
    object 0x65 instance 0899h): the card reads its configuration again (docs/drive-link.md)."""
    for name, value in (("c100", c100), ("c101", c101), ("c102", c102)):
        sim.set(name, value)
    loads = stat("proxy.config_loads")
    ask(c, set_(0x65, 0x0899, 3, u16(1)), "90 00 00 00", "f899 = 1 through 0x65")
    wait_until("configuration reloaded", lambda: stat("proxy.config_loads") > loads, 5.0, 0.05)
    config = sim.config()
    same("configuration in force", (config["c100"], config["c101"], config["c102"]), (str(c100), str(c101), str(c102)))
    wait_drive("inverter after f899", 3.0, trip=0, state="stopped")


def link_snapshot():
    return time.monotonic(), stat("drive.frames_sent")


def exchange_seconds(since):
    """One drive-link exchange (request and reply on the serial line), measured: the link is never idle
    (the cycles run back to back), so it is the time between two snapshots over the frames sent."""
    t0, frames0 = since
    t1, frames1 = link_snapshot()
    return (t1 - t0) / max(1, frames1 - frames0)


def run_owner(c, ep, serial, multiplier=0, data="61 00 08 07"):
    triad = Triad(serial)
    t_o_id = 0x7A000000 + serial
    o_t_id, _, _ = open_ok(c, triad, io_path(21, 71), LOSS_RPI, 10, 6, t_o_id, f"loss case 21/71 #{serial:04X}",
                           multiplier=multiplier)
    conn = ep.add(IoConnection(o_t_id, t_o_id, LOSS_RPI, H(data), name=f"loss {serial:04X}"))
    return triad, conn


def command_latency(ep, conn, what):
    """Time from the first O->T datagram with the run command to FA06 = C400h seen in the inverter."""
    t0 = wait_until(f"{what}: first run datagram sent", lambda: conn.changed_sent, 1.0, 0.0005)
    seen, _, _ = watch(lambda s: s["fa06"] == "0xC400", 2.0)
    return seen - t0


def watch(predicate, limit):
    """Polls the inverter every ~1 ms until predicate(status) holds: (monotonic time, status, largest gap
    between two polls)."""
    deadline = time.monotonic() + limit
    previous, gap = time.monotonic(), 0.0
    while True:
        status = sim.status()
        now = time.monotonic()
        gap = max(gap, now - previous)
        previous = now
        if predicate(status):
            return now, status, gap
        if now > deadline:
            card = {k: v for k, v in sim.stats().items() if k.startswith(("proxy.", "cip.", "drive."))}
            fail(f"no reaction within {limit} s: {status}; card: {card}")
        time.sleep(0.0008)


REACTIONS = {
    0: ("stop: FA06 = 0000h", lambda s: s["fa06"] == "0x0000"),
    # docs/drive-link.md: held FA06 without run and jog, with command priority: C400h -> C000h. After a
    # timeout the drive profile has given the command back (ReleaseDriveCommand on the close) before c100
    # runs out; the proxy keeps the released FA06 for the action (docs/eip-tests.md "Findings" 1, fixed).
    2: ("deceleration stop: FA06 = C000h (the released C400h without run)", lambda s: s["fa06"] == "0xC000"),
    "2 idle": ("deceleration stop: FA06 = C000h (the held C400h without run)", lambda s: s["fa06"] == "0xC000"),
    3: ("coast stop: FA06 = 8800h", lambda s: s["fa06"] == "0x8800"),
    4: ("err8 trip (FA30 = 27)", lambda s: s["trip"] == 27),
    5: ("preset speed c102 = 3: FA06 = 8403h", lambda s: s["fa06"] == "0x8403"),
}
FIGURES = []


def loss_case(c, ep, serial, c101, c100=0, idle=False):
    reload_config(c, c101, c100, 3 if c101 == 5 else 0)
    link = link_snapshot()
    triad, conn = run_owner(c, ep, serial)
    latency = command_latency(ep, conn, f"c101={c101}")
    wait_drive(f"c101={c101}: running", 2.0, state="running", fa06="0xC400")
    wait_until("output above 20 Hz", lambda: sim.status()["output_hz"] >= 20.0, 2.0)
    # (The recovery connection of the previous case was closed: a loss, restored by this one's run mode.)
    same(f"c101={c101}: in run mode, nothing lost", stat("cip.lost"), 0)
    counters = {k: stat(k) for k in ("cip.losses", "cip.restores", "cip.connection_timeouts", "cip.loss_idle",
                                     "cip.loss_timeouts", "proxy.loss_actions")}
    exchange = exchange_seconds(link)
    if idle:
        ep.set(conn, run=False)
        t_last = wait_until("first idle datagram sent", lambda: conn.changed_sent if not conn.changed else None, 1.0, 0.0005)
        timeout = 0.0
        cause = "idle"
    else:
        t_last = ep.stop_sending(conn)
        timeout = LOSS_TIMEOUT
        cause = "O->T stopped"
    delay = c100 / 10.0
    if c101 == 1:
        what = "continue: the card's loss only (cip.lost = 1), the drive runs on"
        t_react, gap = None, 0.0
        deadline = time.monotonic() + timeout + delay + 1.0
        previous = time.monotonic()
        while stat("cip.lost") != 1:
            now = time.monotonic()
            gap = max(gap, now - previous)
            previous = now
            if now > deadline:
                fail("c101=1: the card did not report the loss")
            time.sleep(0.0008)
        t_react = time.monotonic()
        status = sim.status()
    else:
        what, predicate = REACTIONS["2 idle" if idle and c101 == 2 else c101]
        t_react, status, gap = watch(predicate, timeout + delay + 1.0)
    elapsed = t_react - t_last
    low = timeout + delay
    # Allowance above timeout + c100: one RPI (the watchdog is checked at the card's next deadline), two
    # drive-link exchanges (the transaction on the wire ends, then the action's own write: the action is
    # "the next own transaction", docs/drive-link.md "Loss actions"), and the resolution of our polling
    # (the largest gap between two status polls) plus 2 ms for the kernel and event loop.
    high = low + LOSS_RPI / 1e6 + 2 * exchange + gap + 0.002
    FIGURES.append((f"c101={c101} c100={c100 / 10:.1f} s {cause}", elapsed, low, high, exchange, latency))
    print(f"   c101={c101} c100={delay:.1f} s ({cause}): {what} after {elapsed * 1000:.1f} ms; window "
          f"[{low * 1000:.1f}, {high * 1000:.1f}] ms (exchange {exchange * 1000:.2f} ms, poll gap {gap * 1000:.2f} ms); "
          f"command latency run -> FA06 {latency * 1000:.1f} ms", flush=True)
    check(f"c101={c101} c100={c100} ({cause}): reaction within [timeout + c100, + RPI + 2 exchanges + polling]",
          low <= elapsed <= high, f"({elapsed * 1000:.1f} ms, window [{low * 1000:.1f}, {high * 1000:.1f}] ms)")
    if c101 == 0:
        wait_drive("c101=0: the drive stops under cmod/fmod (panel)", 2.0, state="stopped", command_source="panel")
    elif c101 == 1:
        time.sleep(0.5)
        status = sim.status()
        same("c101=1: the drive runs on at 60 Hz with FA06 C400h",
             (status["state"], status["output_hz"], status["fa06"]), ("running", 60.0, "0xC400"))
    elif c101 == 2:
        first = status["output_hz"]
        check("c101=2: still turning when the action arrives", first > 0)
        time.sleep(0.05)
        check("c101=2: decelerating", 0 < sim.status()["output_hz"] < first, f"{sim.status()}")
        wait_drive("c101=2: the deceleration ends in a stop", 2.0, state="stopped", output_hz=0.0)
    elif c101 == 3:
        same("c101=3: output cut at once (coast)", sim.status()["output_hz"], 0.0)
    elif c101 == 4:
        same("c101=4: trip code 27 (err8)", (status["trip"], status["state"]), (27, "tripped"))
    elif c101 == 5:
        wait_drive("c101=5: runs at sr3 = 25 Hz", 2.0, state="running", output_hz=25.0, target_hz=25.0)
    stats = {k: stat(k) for k in counters}
    expected = dict(counters)
    expected["cip.losses"] += 1
    if idle:
        expected["cip.loss_idle"] += 1
    else:
        expected["cip.loss_timeouts"] += 1
        expected["cip.connection_timeouts"] += 1
    expected["proxy.loss_actions"] += 1
    same(f"c101={c101}: counters", stats, expected)
    if c101 != 1:
        same("the loss action in force", (stat("proxy.loss_action_active"), stat("proxy.c536")), (1, 0))
    if not idle:
        # NS: "connection timed out" (red flashing) until re-established (docs/network.md "LED model").
        check("LED inputs: the owner timed out", "connections=timed-out" in sim.command("led-inputs")[0],
              sim.command("led-inputs")[0])

    # Restore: a connection in run mode again (a new one after a timeout, the same one after idle).
    if idle:
        ep.set(conn, H("60 00 00 00"), run=True)
        recovery = (triad, conn)
    else:
        ep.remove(conn)
        stopped_sending(ep, conn.t_o_id, f"c101={c101}: the timed-out connection", settle=0.0, window=0.1)
        recovery = run_owner(c, ep, serial + 0x80, multiplier=2, data="60 00 00 00")
    wait_until("NetworkRestored", lambda: stat("cip.restores") == counters["cip.restores"] + 1, 2.0)
    check("LED inputs: a connection established again",
          "connections=established" in sim.command("led-inputs")[0], sim.command("led-inputs")[0])
    same(f"c101={c101}: restored (cip.lost, loss action, c536)",
         (stat("cip.lost"), stat("proxy.loss_action_active"), stat("proxy.c536")), (0, 0, 0))
    if c101 == 4:
        wait_drive("err8 stays after the restore", 1.0, trip=27)
    else:
        wait_drive(f"c101={c101}: the new connection commands the drive again (stop)", 3.0, fa06="0xC000",
                   state="stopped", output_hz=0.0)
    return recovery


def close_recovery(c, ep, recovery):
    triad, conn = recovery
    finish(c, ep, conn, triad, io_path(21, 71), "recovery connection")


def loss_phase():
    with Client(CARD) as c, IoEndpoint(CARD) as ep:
        same("RegisterSession", c.register_session().status, 0)
        # Order: the recovery connection's own close is a loss too (Forward_Close of an exclusive owner),
        # harmless on a stopped drive for c101 = 0-4; c101 = 5 comes last and is closed under c101 = 1.
        for serial, c101, c100, idle in ((0x701, 1, 0, False), (0x702, 0, 0, False), (0x703, 2, 0, False),
                                         (0x704, 3, 0, False), (0x705, 4, 0, False), (0x706, 2, 0, True),
                                         (0x707, 0, 10, False), (0x708, 5, 0, False)):
            recovery = loss_case(c, ep, serial, c101, c100, idle)
            if c101 == 5:
                reload_config(c, 1)  # the drive is stopped; the recovery connection stays open across f899
            close_recovery(c, ep, recovery)
            ok(f"c101 = {c101}, c100 = {c100 / 10:.1f} s ({'idle' if idle else 'timeout'}): reaction in its window, restored")
        wait_drive("final: stopped, no trip", 2.0, state="stopped", trip=0)
        same("connections left", stat("cip.connections"), 0)
    print("   loss reaction times (ms): " + "; ".join(f"{name}: {e * 1000:.1f} in [{lo * 1000:.1f}, {hi * 1000:.1f}]"
                                                      for name, e, lo, hi, _, _ in FIGURES))
    ok(f"loss phase: {checks} checks")


{"io": io_phase, "loss": loss_phase}[sys.argv[1]]()
PY

[ "$("$CTL" "$CARD_CONTROL" "get c500" | sed -n 's/^c500 = \([0-9]*\).*/\1/p')" = 1 ] || fail "this test needs c500 = 1"
ip addr add "$NEG_IP/24" dev "$TAP_L"
wait_for 10 "$PY" -c "import socket; socket.create_connection(('$CARD_IP', 44818), 1).close()" \
  || fail "EtherNet/IP port 44818 not open"

# Real-time scheduling (SCHED_FIFO) for the card and, one step below, for our scanner: the host is shared
# (builds, fuzzers, other tests on 2 CPUs), and an MCU has its CPU to itself. What is left of the T->O
# jitter and of the loss reaction times is then the firmware's own scheduling, not another process's.
rt=()
if chrt -a -f -p 30 "$CARD_PID" 2>/dev/null; then
  rt=(chrt -f 20)
else
  echo "   (SCHED_FIFO not available: timing runs at normal priority)"
fi

for phase in io loss; do
  started=$SECONDS
  "${rt[@]}" "$PY" -c "$CHECKS" "$phase" || fail "phase $phase"
  echo "   ($phase: $((SECONDS - started)) s)"
done

# The capture: every frame of ours and every frame the card sends must dissect cleanly; the requests sent
# from NEG_IP are wrong on purpose and only counted. Class 1 frames decode as CIP I/O because the capture
# holds their Forward_Open.
sleep 0.3
pcap="$CARD_STATE_DIR/../eip_io.pcap"
cp "$CARD_PCAP" "$pcap"
[ -n "${EIP_IO_KEEP_PCAP:-}" ] && cp "$pcap" "$EIP_IO_KEEP_PCAP"  # for a look afterwards
bad="_ws.malformed || _ws.expert.severity >= warning"
count() { tshark -r "$pcap" -Y "$1" 2>/dev/null | wc -l; }
ours="(ip.addr == $HOST_IP || ip.src == $CARD_IP) && !tcp.connection.rst && ($bad)"
n=$(count "$ours")
if [ "$n" -ne 0 ]; then
  tshark -r "$pcap" -Y "$ours" 2>/dev/null | head -20
  tshark -r "$pcap" -Y "$ours" -V 2>/dev/null | grep -E "^Frame |Expert Info|Malformed" | head -40
  fail "$n frames of the card's traffic malformed or with expert warnings"
fi
io_frames=$(count "cipio")
udp_frames=$(count "udp.port == 2222")
cm_frames=$(count "cipcm")
[ "$io_frames" -ge 5000 ] && [ "$io_frames" -eq "$udp_frames" ] \
  || fail "$io_frames of $udp_frames frames on UDP 2222 decoded as CIP I/O (expected all, at least 5000)"
flagged=$(count "ip.src == $NEG_IP && ($bad)")
pass "capture: $io_frames CIP I/O frames and every other frame of the card's traffic clean ($cm_frames Connection Manager frames; $flagged of the deliberately wrong requests from $NEG_IP flagged)"
pass "EtherNet/IP connections over TAP: class 1, class 3, drive assemblies, refusals, loss actions, deferred replies"
