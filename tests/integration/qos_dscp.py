"""QoS object 0x48 end to end (docs/network.md "QoS (DSCP)"), run by qos_dscp.sh in a namespace with the
card's --pcap capture (host card or the board image under QEMU). tshark reads copies of the capture taken
at the end of each phase; a phase after a reset looks only at the frames after its start:

  defaults  Get of attributes 1-8 (59/47/55/47/43/31/27, tag off); a class 1 connection whose T->O
            priority is scheduled produces with DSCP 47, one with urgent with DSCP 55; the card's TCP 44818
            segments with data and its UDP 44818 replies carry DSCP 27; no frame is tagged
  bad       DSCP 64 and tag enable 2 -> 0x09, no data -> 0x13, two bytes -> 0x15, attribute 9 -> 0x14
  set       explicit 10, scheduled 20: read back at once, in force only after Identity Reset: before it
            the replies still carry 27; after it 10, and the scheduled productions 20
  tag       tag enable 1, Identity Reset: class 1 frames carry an 802.1Q tag VLAN 0 priority 5 (scheduled),
            explicit replies priority 3, ARP none
  tshark    no malformed frame in any capture
"""
import os
import shutil
import subprocess
import sys
import time

from eip_io import *
from eip_originator import *

CARD = os.environ["CARD_IP"]
PCAP = os.environ["CARD_PCAP"]
WORK = os.path.dirname(PCAP)
checks = 0


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def ok(message):
    print(f"ok: {message}", flush=True)


def same(what, got, want):
    global checks
    checks += 1
    if got != want:
        fail(f"{what}:\n  got      {got!r}\n  expected {want!r}")


def H(text):
    return bytes.fromhex(text.replace("|", " "))


def ask(c, request, want, what):
    same(f"{what} (request {hexs(request)})", c.cip(request).raw().hex(" "), H(want).hex(" "))


def get(attribute, instance=1):
    return mr_request(GET_ATTRIBUTE_SINGLE, epath(0x48, instance, attribute))


def set_(attribute, value):
    return mr_request(SET_ATTRIBUTE_SINGLE, epath(0x48, 1, attribute), value)


def snapshot(name):
    """A copy of the card's capture so far (after a pause, so that no frame is half written)."""
    time.sleep(0.3)
    path = os.path.join(WORK, f"qos_{name}.pcap")
    shutil.copyfile(PCAP, path)
    return path


def frames_so_far():
    """How many frames the capture holds now. A phase looks only at the frames after it: the host card's
    capture starts anew at a restart, QEMU's (the board image) goes on."""
    return len(fields(snapshot("mark"), "frame", "frame.number"))


def fields(pcap, display_filter, *names, after=0):
    if after:
        display_filter = f"frame.number > {after} && ({display_filter})"
    out = subprocess.run(["tshark", "-r", pcap, "-Y", display_filter, "-T", "fields", "-E", "separator=/"]
                         + [a for n in names for a in ("-e", n)], capture_output=True, text=True, timeout=60)
    return [line for line in out.stdout.splitlines() if line]


def values_of(pcap, display_filter, name, at_least=1, after=0):
    """The distinct values of one field over the frames the filter selects (at least `at_least` frames)."""
    rows = fields(pcap, display_filter, name, after=after)
    if len(rows) < at_least:
        fail(f"{pcap}: only {len(rows)} frames match '{display_filter}'")
    return sorted(set(rows))


def no_malformed(pcap):
    rows = fields(pcap, "_ws.malformed || _ws.expert.severity == error", "frame.number")
    same(f"{os.path.basename(pcap)}: malformed frames", rows, [])


def io_filter(t_o_id):
    # The sequenced address item's connection ID (little endian) starts at byte 6 of the datagram.
    le = t_o_id.to_bytes(4, "little").hex(":")
    return f"ip.src == {CARD} && udp.srcport == 2222 && udp.payload[6:4] == {le}"


def explicit_filter():
    return f"ip.src == {CARD} && ((tcp.srcport == 44818 && tcp.len > 0) || udp.srcport == 44818)"


def run_connection(c, ep, serial, priority, t_o_id, seconds=0.6):
    """A class 1 exclusive owner 21/71 at RPI 10 ms whose T->O priority is `priority`, for `seconds`."""
    triad = Triad(serial)
    path = io_path(21, 71)
    request = forward_open(triad, path, 10000, net_params(2 + 4 + 4), 10000,
                           net_params(2 + 4, priority=priority), t_o_id=t_o_id, multiplier=3)
    mr, raw, _ = open_connection(c, request)
    if mr.general != 0:
        fail(f"Forward_Open refused: {hexs(raw)}")
    reply = decode_open_success(mr.data)
    conn = ep.add(IoConnection(reply["o_t_id"], t_o_id, 10000, H("60 00 00 00"), name=f"priority {priority}"))
    time.sleep(seconds)
    ep.stop_sending(conn)
    mr, raw, _ = open_connection(c, forward_close(triad, path))
    if mr.general != 0:
        fail(f"Forward_Close refused: {hexs(raw)}")
    ep.remove(conn)
    same(f"T->O datagrams of priority {priority} received", ep.count(t_o_id) > 10, True)


def traffic(ep, first_id):
    """One scheduled and one urgent connection, some explicit requests and a ListIdentity over UDP."""
    with Client(CARD) as c:
        c.register_session()
        run_connection(c, ep, first_id & 0xFFFF, PRIORITY_SCHEDULED, first_id)
        run_connection(c, ep, (first_id + 1) & 0xFFFF, PRIORITY_URGENT, first_id + 1)
        for attribute in (1, 8):
            c.cip(get(attribute))
    same("ListIdentity over UDP answered", len(list_identity_udp(CARD, wait=0.5)) >= 1, True)


def ready_lines():
    with open(os.environ["CARD_LOG"], errors="replace") as log:
        return sum(1 for line in log if line.startswith("ready "))


def identity_reset():
    lines = ready_lines()
    with Client(CARD) as c:
        c.register_session()
        ask(c, mr_request(RESET, epath(0x01, 1)), "85 00 00 00", "Identity Reset")
    deadline = time.monotonic() + 15
    while ready_lines() <= lines:
        if time.monotonic() > deadline:
            fail("no new ready line within 15 s of the Identity Reset")
        time.sleep(0.1)
    deadline = time.monotonic() + 10
    while True:
        try:
            if list_identity_udp(CARD, wait=0.5):
                return
        except OSError:
            pass
        if time.monotonic() > deadline:
            fail("the card does not answer ListIdentity within 10 s of its restart")


def check_marks(pcap, after, scheduled_id, scheduled, urgent_id, urgent, explicit, what):
    same(f"{what}: DSCP of the scheduled connection's productions",
         values_of(pcap, io_filter(scheduled_id), "ip.dsfield.dscp", 10), [str(scheduled)])
    same(f"{what}: DSCP of the urgent connection's productions",
         values_of(pcap, io_filter(urgent_id), "ip.dsfield.dscp", 10), [str(urgent)])
    same(f"{what}: DSCP of the card's explicit messaging (TCP and UDP 44818)",
         values_of(pcap, explicit_filter(), "ip.dsfield.dscp", 5, after=after), [str(explicit)])
    no_malformed(pcap)


def main():
    with IoEndpoint(CARD) as ep:
        # ---- defaults
        with Client(CARD) as c:
            c.register_session()
            for attribute, value in enumerate([0, 59, 47, 55, 47, 43, 31, 27], start=1):
                ask(c, get(attribute), f"8E 00 00 00 {value:02X}", f"attribute {attribute} default")
            ask(c, mr_request(GET_ATTRIBUTES_ALL, epath(0x48, 1)), "81 00 00 00 00 3B 2F 37 2F 2B 1F 1B",
                "Get_Attributes_All")
            ask(c, get(1, instance=0), "8E 00 00 00 01 00", "class revision")
        traffic(ep, 0x51000001)
        pcap = snapshot("defaults")
        check_marks(pcap, 0, 0x51000001, 47, 0x51000002, 55, 27, "defaults")
        same("defaults: no tagged frame from the card", fields(pcap, "vlan", "frame.number"), [])
        ok("defaults: class 1 scheduled DSCP 47, urgent 55, explicit TCP/UDP 44818 DSCP 27, no tag")

        # ---- bad values
        with Client(CARD) as c:
            c.register_session()
            ask(c, set_(4, b"\x40"), "90 00 09 00", "DSCP Urgent 64")
            ask(c, set_(8, b"\xFF"), "90 00 09 00", "DSCP Explicit 255")
            ask(c, set_(1, b"\x02"), "90 00 09 00", "tag enable 2")
            ask(c, set_(8, b""), "90 00 13 00", "no data")
            ask(c, set_(8, b"\x0A\x00"), "90 00 15 00", "two bytes")
            ask(c, set_(9, b"\x0A"), "90 00 14 00", "attribute 9")
            ask(c, get(8), "8E 00 00 00 1B", "DSCP Explicit unchanged")
        ok("bad values: 0x09 (DSCP > 63, tag enable > 1), 0x13, 0x15, 0x14; nothing changed")

        # ---- set explicit 10, scheduled 20: read back at once, in force after the reset
        with Client(CARD) as c:
            c.register_session()
            ask(c, set_(8, b"\x0A"), "90 00 00 00", "DSCP Explicit 10")
            ask(c, set_(5, b"\x14"), "90 00 00 00", "DSCP Scheduled 20")
            ask(c, get(8), "8E 00 00 00 0A", "DSCP Explicit read back")
            ask(c, get(5), "8E 00 00 00 14", "DSCP Scheduled read back")
        pcap = snapshot("before_reset")
        same("before the reset the replies still carry DSCP 27",
             values_of(pcap, explicit_filter(), "ip.dsfield.dscp", 5), ["27"])
        identity_reset()
        with Client(CARD) as c:
            c.register_session()
            ask(c, get(8), "8E 00 00 00 0A", "DSCP Explicit after the reset")
            ask(c, get(5), "8E 00 00 00 14", "DSCP Scheduled after the reset")
        after = frames_so_far()
        traffic(ep, 0x52000001)
        check_marks(snapshot("after_reset"), after, 0x52000001, 20, 0x52000002, 55, 10, "after the reset")
        ok("set explicit 10, scheduled 20: read back at once; after Identity Reset class 1 scheduled DSCP 20, "
           "urgent 55, explicit 10")

        # ---- 802.1Q tagging
        with Client(CARD) as c:
            c.register_session()
            ask(c, set_(1, b"\x01"), "90 00 00 00", "tag enable 1")
        identity_reset()
        after = frames_so_far()
        traffic(ep, 0x53000001)
        pcap = snapshot("tagged")
        check_marks(pcap, after, 0x53000001, 20, 0x53000002, 55, 10, "tagged")
        same("tagged: scheduled productions carry VLAN 0 priority 5",
             values_of(pcap, io_filter(0x53000001), "vlan.priority", 10), ["5"])
        same("tagged: urgent productions carry VLAN 0 priority 6",
             values_of(pcap, io_filter(0x53000002), "vlan.priority", 10), ["6"])
        same("tagged: every tag has VLAN ID 0", values_of(pcap, f"eth.src == {os.environ['CARD_MAC']} && vlan",
                                                           "vlan.id", 10), ["0"])
        same("tagged: explicit replies carry priority 3",
             values_of(pcap, explicit_filter(), "vlan.priority", 5, after=after), ["3"])
        same("tagged: ARP from the card is not tagged",
             fields(pcap, f"arp && eth.src == {os.environ['CARD_MAC']} && vlan", "frame.number"), [])
        same("tagged: the card's explicit replies after the reset are all tagged",
             fields(pcap, f"{explicit_filter()} && !vlan", "frame.number", after=after), [])
        ok("tag enable 1 after Identity Reset: class 1 frames tagged VLAN 0 priority 5 (scheduled) and 6 (urgent), "
           "explicit 3, ARP untagged; the host's answers (untagged) reach the card")
    print(f"qos_dscp: {checks} checks passed")


if __name__ == "__main__":
    main()
