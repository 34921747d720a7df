#!/usr/bin/env bash
# EtherNet/IP over TAP in a namespace (tools/netns), against our originator (eip_originator.py) and an
# independent one (st-ethernet-ip, eip_browse.js). Expected bytes and codes are docs/ethernetip.md's and
# the unit tests' (cip/test/cip_*_test.cc). docs/eip-tests.md describes every check.
#
# Card started with c500=1 (integration.eip_tap, --pcap):
#   walk      every object of §4 the core implements, exact bytes; settable attributes and their effect
#             (the stored value read back, the inverter's c-parameters); MSP; Unconnected_Send;
#             ListIdentity over TCP, unicast UDP, broadcast UDP with its delay bound; Modbus 502 refused
#   browse    st-ethernet-ip: Browser discovery (255.255.255.255), explicit messages through its ENIP class
#   negative  encapsulation and CIP errors, sent from a second host address (NEG_IP) so that the capture
#             check can tell them apart; then a healthy client is still served
#   tshark    no malformed frame and no expert warning on the walk's and browse's traffic; on the
#             negative traffic, nothing malformed from the card
#   reset     Identity Reset type 0 restarts the card: the stored settings survive (c081-c096 in the
#             inverter, TTL in the card's store); type 1 restores the card's own settings to defaults
# Card started with c500=0 (integration.eip_closed): TCP 44818 refused, UDP 44818 unanswered, Modbus 502
# serves.
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CTL CARD_IP CARD_MAC CARD_CONTROL CARD_LOG
export NEG_IP="${HOST_IP%.*}.3"
PY=/usr/bin/python3
c500=$("$CTL" "$CARD_CONTROL" "get c500" | sed -n 's/^c500 = \([0-9]*\).*/\1/p')
[ -n "$c500" ] || fail "cannot read c500 from the simulated inverter"

# The indicators after start (docs/network.md "LED model"): the power-up test, then MS steady green and,
# under EtherNet/IP with no connection yet, NS flashing green (1 Hz); under Modbus TCP NS steady green.
"$IT/led_log.py" "$CARD_LOG" MS power-up || fail "power-up LED test"
sleep 3.6
"$IT/led_log.py" "$CARD_LOG" MS steady-green || fail "MS not steady green: $("$CTL" "$CARD_CONTROL" leds)"
if [ "$c500" = 1 ]; then
  "$IT/led_log.py" "$CARD_LOG" NS flash-green || fail "EtherNet/IP NS not flashing green without connections"
else
  "$IT/led_log.py" "$CARD_LOG" NS steady-green || fail "Modbus TCP NS not steady green"
fi
pass "LEDs: power-up test, MS green, NS $([ "$c500" = 1 ] && echo 'flashing green (no connection)' || echo green)"

# The checks, one program; the first argument picks the phase.
read -r -d '' CHECKS <<'PY' || true
import os, re, socket, struct, subprocess, sys, time
from eip_originator import *

CARD = os.environ["CARD_IP"]
MAC = bytes.fromhex(os.environ["CARD_MAC"].replace(":", ""))
NEG_IP = os.environ["NEG_IP"]
IP_LE = socket.inet_aton(CARD)[::-1]           # an address as the TCP/IP object sends it (UDINT)
GW_LE = socket.inet_aton(CARD.rsplit(".", 1)[0] + ".1")[::-1]
SERIAL = int.from_bytes(MAC[2:], "big")         # §4.1 "4 last bytes of MAC", docs: one big-endian number
SERIAL_LE = struct.pack("<I", SERIAL)
checks = 0


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def ok(message):
    print(f"ok: {message}")


def H(text):
    return unhex(text) if isinstance(text, str) else bytes(text)


def same(what, got, want):
    global checks
    checks += 1
    if got != want:
        fail(f"{what}: got {got!r}, expected {want!r}")


def ask(c, request, want, what):
    """One message router request; the whole reply must be `want` (hex or bytes)."""
    global checks
    checks += 1
    got = c.cip(H(request)).raw()
    if got != H(want):
        fail(f"{what}: request {hexs(H(request))}\n  got      {hexs(got)}\n  expected {hexs(H(want))}")
    return got


def get(class_id, instance, attribute):
    return mr_request(GET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute))


def get_all(class_id, instance):
    return mr_request(GET_ATTRIBUTES_ALL, epath(class_id, instance))


def set_(class_id, instance, attribute, value):
    return mr_request(SET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute), H(value))


def short_string(text):
    return bytes([len(text)]) + text.encode()


def cip_string(text):
    data = struct.pack("<H", len(text)) + text.encode()
    return data + (b"\x00" if len(text) % 2 else b"")


def cparam(name):
    out = subprocess.run([os.environ["CTL"], os.environ["CARD_CONTROL"], f"get {name}"], capture_output=True,
                         text=True, timeout=10).stdout
    m = re.match(rf"{name} = (-?\d+) ", out)
    if not m:
        fail(f"card-ctl get {name}: {out!r}")
    return int(m.group(1))


def wait_cparams(values, what, limit=5.0):
    """The inverter's parameters reach `values` (written through the card's queue) within `limit` s."""
    global checks
    checks += 1
    deadline = time.monotonic() + limit
    while True:
        got = {name: cparam(name) for name in values}
        if got == values:
            return
        if time.monotonic() > deadline:
            fail(f"{what}: inverter parameters {got}, expected {values}")
        time.sleep(0.1)


def stat(name):
    out = subprocess.run([os.environ["CTL"], os.environ["CARD_CONTROL"], "stats"], capture_output=True, text=True,
                         timeout=10).stdout
    m = re.search(rf"^{re.escape(name)}=(\S+)$", out, re.M)
    if not m:
        fail(f"card-ctl stats has no {name}")
    return m.group(1)


def wait_stat(name, value, what, limit=5.0):
    deadline = time.monotonic() + limit
    while stat(name) != value:
        if time.monotonic() > deadline:
            fail(f"{what}: {name}={stat(name)}, expected {value} within {limit} s")
        time.sleep(0.1)


def host_name_params(name):
    return {f"c{81 + i:03d}": (ord(name[i]) if i < len(name) else 0) for i in range(16)}


def counters(data):
    same("counter attribute size", len(data), 44)
    return dict(zip(("in_octets", "in_ucast", "in_nucast", "in_discards", "in_errors", "in_unknown",
                     "out_octets", "out_ucast", "out_nucast", "out_discards", "out_errors"),
                    struct.unpack("<11I", data)))


def identity_all(product=32000, name="VF-MB1"):
    return (b"\x79\x01\x02\x00" + struct.pack("<H", product) + b"\x01\x08\x30\x00" + SERIAL_LE + short_string(name))


def list_identity_data():
    """ListIdentity's command data for the card (docs: version 1, socket address, Identity 1-7, state FF)."""
    item = (b"\x01\x00" + b"\x00\x02\xaf\x12" + socket.inet_aton(CARD) + bytes(8) + identity_all() + b"\xff")
    return b"\x01\x00\x0c\x00" + struct.pack("<H", len(item)) + item


LIST_SERVICES_DATA = H("01 00 00 01 14 00 01 00 20 01") + b"Communications\x00\x00"


# ---- walk: every object, settings and their effect, MSP, Unconnected_Send, discovery --------------

def walk():
    # Discovery over TCP, before and inside a session; UDP unicast; UDP broadcast with its delay bound.
    with Client(CARD) as c:
        r = c.list_identity()
        same("TCP ListIdentity", (r.command, r.status, r.session, r.context, r.data),
             (LIST_IDENTITY, 0, 0, c.context, list_identity_data()))
        item = parse_list_identity(r.data)[0][0]
        same("ListIdentity decoded", (item["vendor_id"], item["device_type"], item["product_code"],
                                      item["revision"], item["product_name"], item["sin_addr"], item["serial_number"]),
             (377, 2, 32000, (1, 8), "VF-MB1", CARD, SERIAL))
        r = c.list_services()
        same("TCP ListServices", (r.status, r.data), (0, LIST_SERVICES_DATA))
        same("ListServices decoded", parse_list_services(r.data),
             [{"type": 0x100, "version": 1, "flags": 0x120, "name": "Communications"}])
        r = c.list_interfaces()
        same("TCP ListInterfaces", (r.status, r.data), (0, b"\x00\x00"))
        r = c.register_session()
        same("RegisterSession", (r.command, r.length, r.status, r.context, r.data),
             (REGISTER_SESSION, 4, 0, c.context, b"\x01\x00\x00\x00"))
        if r.session == 0:
            fail("RegisterSession gave handle 0")
        r = c.list_identity()
        same("ListIdentity in a session echoes the handle", (r.session, r.data), (c.session, list_identity_data()))
        same("UnRegisterSession closes the connection without a reply", c.unregister_session(), True)
    ok("ListIdentity, ListServices, ListInterfaces over TCP (exact bytes); RegisterSession/UnRegisterSession")

    replies = list_identity_udp(CARD)
    same("unicast UDP ListIdentity replies", len(replies), 1)
    delay, peer, r = replies[0]
    same("unicast UDP ListIdentity", (peer, r.command, r.status, r.data), ((CARD, 44818), LIST_IDENTITY, 0,
                                                                            list_identity_data()))
    for command, data in ((LIST_SERVICES, LIST_SERVICES_DATA), (LIST_INTERFACES, b"\x00\x00")):
        replies = udp_exchange(CARD, encode(command, context=b"udp-test"), wait=1.0)
        same(f"unicast UDP command 0x{command:04X}", [(p, x.status, x.context, x.data) for _, p, x in replies],
             [((CARD, 44818), 0, b"udp-test", data)])
    ok("ListIdentity, ListServices, ListInterfaces over unicast UDP")

    broadcast = CARD.rsplit(".", 1)[0] + ".255"
    for max_delay, bound in ((500, 1.0), (500, 1.0), (500, 1.0), (0, 2.5)):
        replies = list_identity_udp(broadcast, broadcast=True, max_delay_ms=max_delay, wait=bound + 0.5)
        same(f"broadcast ListIdentity (max delay {max_delay} ms) replies", len(replies), 1)
        delay, peer, r = replies[0]
        same("broadcast ListIdentity reply", (peer, r.status, r.context[:2], r.data),
             ((CARD, 44818), 0, struct.pack("<H", max_delay), list_identity_data()))
        if delay > bound:
            fail(f"broadcast ListIdentity with max delay {max_delay or 2000} ms answered after {delay:.3f} s")
        print(f"   broadcast ListIdentity, max delay {max_delay or 2000} ms: answered after {delay * 1000:.0f} ms")
    ok("broadcast ListIdentity answered once, within its max delay (500 ms x3, default 2000 ms)")

    c = Client(CARD)
    if c.register_session().status != 0:
        fail("RegisterSession")

    # Identity 0x01 (§4.1).
    for attribute, value in ((1, "01 00"), (2, "01 00"), (3, "01 00"), (4, "00 00"), (6, "07 00"), (7, "07 00")):
        ask(c, get(0x01, 0, attribute), "8E 00 00 00" + value, f"Identity class attribute {attribute}")
    ask(c, get_all(0x01, 0), "81 00 00 00 01 00 01 00 01 00 00 00 07 00 07 00", "Identity class Get_Attributes_All")
    expected = {1: "79 01", 2: "02 00", 3: "00 7D", 4: "01 08", 5: "30 00", 6: SERIAL_LE,
                7: short_string("VF-MB1")}
    for attribute, value in expected.items():
        ask(c, get(0x01, 1, attribute), H("8E 00 00 00") + H(value), f"Identity attribute {attribute}")
    ask(c, get_all(0x01, 1), H("81 00 00 00") + identity_all(), "Identity Get_Attributes_All")
    ok(f"Identity: vendor 377, type 2, product 32000 VF-MB1, revision 1.8, status 0x0030, serial 0x{SERIAL:08X}")

    # Message Router 0x02 (§4.2).
    for attribute, value in ((1, "01 00"), (2, "01 00"), (3, "01 00"), (4, "02 00 02 00 03 00"), (6, "07 00"),
                             (7, "03 00")):
        ask(c, get(0x02, 0, attribute), "8E 00 00 00" + value, f"Message Router class attribute {attribute}")
    ask(c, get(0x02, 1, 2), "8E 00 00 00 10 00", "Message Router attribute 2")
    ask(c, get(0x02, 1, 3), "8E 00 00 00 00 00", "Message Router attribute 3")
    ok("Message Router: class attributes, 16 connections available, 0 active")

    # Assembly 0x04 (§4.3): 13 instances, the highest 199 (the §5 assemblies and the heartbeat 199).
    for attribute, value in ((1, "02 00"), (6, "07 00"), (7, "04 00")):
        ask(c, get(0x04, 0, attribute), "8E 00 00 00" + value, f"Assembly class attribute {attribute}")
    sizes = {20: 4, 21: 4, 70: 4, 71: 4, 100: 16, 101: 8, 102: 12, 105: 18, 150: 16, 151: 8, 152: 12, 155: 18, 199: 0}
    for instance, size in sizes.items():
        ask(c, get(0x04, instance, 4), H("8E 00 00 00") + struct.pack("<H", size), f"Assembly {instance} size")
        data = c.get_attribute_single(0x04, instance, 3)
        same(f"Assembly {instance} data size", (data.general, len(data.data)), (0, size))
    ask(c, get(0x04, 0, 2), "8E 00 00 00 C7 00", "Assembly max instance")
    ask(c, get(0x04, 0, 3), "8E 00 00 00 0D 00", "Assembly instance count")
    ask(c, get(0x04, 198, 3), "8E 00 16 00", "Assembly 198 is a connection point only")
    ok("Assembly: revision 2, the 13 instances of §4.3/§5 with their sizes, max instance 199")

    # Port 0xF4 (§4.10).
    for attribute, value in ((1, "01 00"), (2, "01 00"), (3, "01 00"), (6, "09 00"), (7, "07 00"), (8, "01 00"),
                             (9, "00 00 00 00 00 00 02 00")):
        ask(c, get(0xF4, 0, attribute), "8E 00 00 00" + value, f"Port class attribute {attribute}")
    ask(c, get_all(0xF4, 0), "81 00 00 00 01 00 01 00 01 00 09 00 07 00 01 00 00 00 00 00 00 00 02 00",
        "Port class Get_Attributes_All")
    node = b"\x12" + short_string(CARD) + (b"\x00" if len(CARD) % 2 else b"")
    port = {1: H("00 00"), 2: H("02 00"), 3: H("02 00 20 F5 24 01"), 4: short_string("EtherNet/IP"), 7: node}
    for attribute, value in port.items():
        ask(c, get(0xF4, 1, attribute), H("8E 00 00 00") + value, f"Port attribute {attribute}")
    ask(c, get_all(0xF4, 1), H("81 00 00 00") + b"".join(port.values()), "Port Get_Attributes_All")
    ok(f"Port: type 0, number 2, link path to TCP/IP 1, \"EtherNet/IP\", node address \"{CARD}\"")

    # TCP/IP Interface 0xF5 (§4.11), factory state.
    for attribute, value in ((1, "01 00"), (2, "01 00"), (3, "01 00"), (4, "04 00 08 00 09 00 0A 00 0B 00"),
                             (5, "00 00"), (6, "07 00"), (7, "0B 00")):
        ask(c, get(0xF5, 0, attribute), "8E 00 00 00" + value, f"TCP/IP class attribute {attribute}")
    config = IP_LE + H("00 FF FF FF") + GW_LE + bytes(8) + H("00 00")
    tcpip = {1: H("01 00 00 00"), 2: H("9D 00 00 00"), 3: H("00 00 00 00"), 4: H("02 00 20 F6 24 01"),
             5: config, 6: H("00 00"), 8: H("01"), 9: bytes(8), 10: H("01"), 11: bytes(35)}
    for attribute, value in tcpip.items():
        ask(c, get(0xF5, 1, attribute), H("8E 00 00 00") + value, f"TCP/IP attribute {attribute}")
    ask(c, get_all(0xF5, 1), H("81 00 00 00") + b"".join(tcpip[a] for a in (1, 2, 3, 4, 5, 6)) + bytes(6) +
        b"".join(tcpip[a] for a in (8, 9, 10, 11)), "TCP/IP Get_Attributes_All (6 bytes for attribute 7)")
    ok("TCP/IP: status 1, capability 0x9D, control 0, link path, configuration in use, host name, TTL 1, "
       "multicast, SelectAcd 1, last conflict; class attributes")

    # Ethernet Link 0xF6 (§4.12): port 1 is the TAP (up, shown as 100 Mbit/s full duplex); port 2 absent.
    for attribute, value in ((1, "03 00"), (2, "02 00"), (3, "02 00"), (6, "07 00"), (7, "0A 00")):
        ask(c, get(0xF6, 0, attribute), "8E 00 00 00" + value, f"Ethernet Link class attribute {attribute}")
    ask(c, get_all(0xF6, 0), "81 00 00 00 03 00 02 00 02 00 00 00 00 00 07 00 0A 00", "Ethernet Link class Get_Attributes_All")
    links = {1: (H("64 00 00 00"), H("2F 00 00 00"), short_string("Left")),
             2: (H("00 00 00 00"), H("20 00 00 00"), short_string("Right"))}
    for instance, (speed, flags, label) in links.items():
        for attribute, value in ((1, speed), (2, flags), (3, MAC), (5, bytes(48)), (6, H("01 00 00 00")), (7, H("02")),
                                 (10, label)):
            ask(c, get(0xF6, instance, attribute), H("8E 00 00 00") + value, f"Ethernet Link {instance} attribute {attribute}")
    ask(c, get(0xF6, 2, 4), H("8E 00 00 00") + bytes(44), "Ethernet Link 2 counters (no second port)")
    first = counters(c.get_attribute_single(0xF6, 1, 4).data)
    for key in ("in_octets", "in_ucast", "out_octets", "out_ucast"):
        if first[key] == 0:
            fail(f"Ethernet Link 1 counter {key} is 0 after this much traffic: {first}")
    for key in ("in_errors", "out_errors", "in_unknown"):
        same(f"Ethernet Link 1 {key}", first[key], 0)
    second = counters(c.get_attribute_single(0xF6, 1, 4).data)
    for key in ("in_octets", "in_ucast", "out_octets", "out_ucast"):
        if not second[key] > first[key]:
            fail(f"Ethernet Link 1 counter {key} did not grow: {first[key]} -> {second[key]}")
    everything = c.get_attributes_all(0xF6, 1)
    same("Ethernet Link 1 Get_Attributes_All size", (everything.general, len(everything.data)), (0, 4 + 4 + 6 + 44 + 48 + 4 + 1 + 1 + 1 + 5))
    d = everything.data
    same("Ethernet Link 1 Get_Attributes_All fixed parts", (d[:14], d[58:]),
         (H("64 00 00 00 2F 00 00 00") + MAC, bytes(48) + H("01 00 00 00 02 01 01") + short_string("Left")))
    cleared = c.get_and_clear(0xF6, 1, 4)
    same("Get_and_Clear reply", (cleared.service, cleared.general, len(cleared.data)), (0xCC, 0, 44))
    before = counters(cleared.data)
    after = counters(c.get_attribute_single(0xF6, 1, 4).data)
    if not (before["in_octets"] >= second["in_octets"] and after["in_octets"] < before["in_octets"]
            and after["in_ucast"] < before["in_ucast"] and after["out_octets"] < before["out_octets"]):
        fail(f"Get_and_Clear: before {before}, after {after}")
    ask(c, mr_request(GET_AND_CLEAR, epath(0xF6, 2, 5)), H("CC 00 00 00") + bytes(48), "Get_and_Clear media counters")
    ok(f"Ethernet Link: speed, flags 0x2F/0x20, MAC, counters growing ({second['in_octets']} octets in), "
       f"Get_and_Clear restarted them ({after['in_octets']} octets since), media counters, control, type, labels")

    # Settable attributes: the stored value reads back and reaches the inverter's c-parameters.
    long_name = "ABCDEFGHIJ-12345"
    ask(c, set_(0xF5, 1, 6, cip_string(long_name)), "90 00 00 00", "Set host name (16 characters)")
    ask(c, get(0xF5, 1, 6), H("8E 00 00 00") + cip_string(long_name), "Get host name")
    wait_cparams(host_name_params(long_name), "host name -> c081-c096")
    ask(c, set_(0xF5, 1, 6, cip_string("EIP-TEST1")), "90 00 00 00", "Set host name EIP-TEST1")
    ask(c, get(0xF5, 1, 6), H("8E 00 00 00") + cip_string("EIP-TEST1"), "Get host name (odd length: pad byte)")
    wait_cparams(host_name_params("EIP-TEST1"), "host name -> c081-c096, the rest cleared")
    ok("TCP/IP attribute 6 (host name): stored, read back, c081-c096 hold it (16 characters, then 9 + zeros)")

    ask(c, set_(0xF5, 1, 3, "02 00 00 00"), "90 00 00 00", "Set configuration control DHCP")
    ask(c, get(0xF5, 1, 3), "8E 00 00 00 02 00 00 00", "Get configuration control")
    wait_cparams({"c504": 2}, "configuration control -> c504")
    static = IP_LE + H("00 FF FF FF") + GW_LE + socket.inet_aton(CARD.rsplit(".", 1)[0] + ".53")[::-1] + bytes(4)
    ask(c, set_(0xF5, 1, 5, static + cip_string("abc")), "90 00 0C 00",
        "Set interface configuration while DHCP is to be used: object state conflict")
    ask(c, set_(0xF5, 1, 3, "00 00 00 00"), "90 00 00 00", "Set configuration control stored")
    wait_cparams({"c504": 0}, "configuration control -> c504")
    ok("TCP/IP attribute 3: DHCP/stored read back, c504 = 2 then 0; attribute 5 refused 0x0C while DHCP")

    ask(c, set_(0xF5, 1, 5, static + cip_string("abc")), "90 00 00 00", "Set interface configuration")
    octets = [int(x) for x in CARD.split(".")] + [255, 255, 255, 0] + [int(x) for x in CARD.split(".")[:3]] + [1]
    wait_cparams({f"c{505 + i}": v for i, v in enumerate(octets)}, "interface configuration -> c505-c516")
    # The address in use is reported (the stored one takes effect after a reset); the card keeps the
    # name servers and domain itself and reports them.
    ask(c, get(0xF5, 1, 5), H("8E 00 00 00") + static + cip_string("abc"), "Get interface configuration")
    ok("TCP/IP attribute 5: stored into c505-c516; Get shows the configuration in use with the stored DNS fields")

    for attribute, value in ((8, "05"), (9, "01 00 20 00 00 01 C0 EF"), (10, "00")):
        ask(c, set_(0xF5, 1, attribute, value), "90 00 00 00", f"Set TCP/IP attribute {attribute}")
        ask(c, get(0xF5, 1, attribute), "8E 00 00 00" + value, f"Get TCP/IP attribute {attribute}")
    ask(c, set_(0xF5, 1, 11, bytes(35)), "90 00 00 00", "Clear the last conflict")
    ask(c, get_all(0xF5, 1), H("81 00 00 00 01 00 00 00 9D 00 00 00 00 00 00 00 02 00 20 F6 24 01") + static +
        cip_string("abc") + cip_string("EIP-TEST1") + bytes(6) + H("05 01 00 20 00 00 01 C0 EF 00") + bytes(35),
        "TCP/IP Get_Attributes_All after the settings")
    ok("TCP/IP attributes 8 (TTL 5), 9 (32 from 239.192.1.0), 10 (SelectAcd 0), 11 (cleared): stored and read back")

    for value, c501 in (("02 00 64 00", 3), ("00 00 0A 00", 2), ("01 00 00 00", 0)):
        ask(c, set_(0xF6, 1, 6, value), "90 00 00 00", f"Set interface control {value}")
        ask(c, get(0xF6, 1, 6), "8E 00 00 00" + value, "Get interface control (instance 1)")
        ask(c, get(0xF6, 2, 6), "8E 00 00 00" + value, "Get interface control (instance 2: the same c501)")
        wait_cparams({"c501": c501}, f"interface control {value} -> c501")
    ok("Ethernet Link attribute 6: 100 full -> c501 = 3, 10 half -> 2, auto -> 0; one setting for both ports")

    # Multiple Service Packet and Unconnected_Send.
    members = [get(0x01, 1, 1), get(0x01, 1, 7), get(0xF5, 1, 6), get(0xF6, 2, 10), set_(0xF5, 1, 8, "05")]
    reply, replies = c.multiple_service_packet(members)
    same("MSP", (reply.service, reply.general, [r.raw() for r in replies]),
         (0x8A, 0, [H("8E 00 00 00 79 01"), H("8E 00 00 00") + short_string("VF-MB1"),
                    H("8E 00 00 00") + cip_string("EIP-TEST1"), H("8E 00 00 00") + short_string("Right"),
                    H("90 00 00 00")]))
    ask(c, msp_request([]), "8A 00 00 00 00 00", "MSP with count 0")
    ok("Multiple Service Packet: 5 members (4 Gets, 1 Set) answered in order; count 0")
    ask(c, unconnected_send(get(0x01, 1, 1)), "8E 00 00 00 79 01", "Unconnected_Send, empty route")
    ask(c, unconnected_send(get(0x01, 1, 1), port_segment(1, 0)), "8E 00 00 00 79 01",
        "Unconnected_Send, route port 1 slot 0")
    ask(c, unconnected_send(get(0xF4, 1, 4), port_segment(1, 0) + port_segment(1, 0)),
        H("8E 00 00 00") + short_string("EtherNet/IP"), "Unconnected_Send, route port 1 slot 0 twice")
    ask(c, unconnected_send(msp_request([get(0x01, 1, 1), get(0x01, 1, 9)]), port_segment(1, 0)),
        "8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 79 01 8E 00 14 00", "Unconnected_Send carrying an MSP")
    ask(c, unconnected_send(get_all(0x01, 1)), H("81 00 00 00") + identity_all(),
        "Unconnected_Send carrying Get_Attributes_All (odd size: pad byte)")
    ok("Unconnected_Send: empty route, port 1 slot 0 (once, twice), carrying an MSP and an odd-sized request")
    c.close()

    # With c500 = 1 the Modbus TCP port is closed.
    try:
        socket.create_connection((CARD, 502), 2).close()
        fail("Modbus TCP port 502 accepted a connection with c500 = 1")
    except ConnectionRefusedError:
        pass
    ok("Modbus TCP 502 refused (RST) while the card speaks EtherNet/IP")
    print(f"walk: {checks} checks passed")


# ---- negative cases, from NEG_IP ------------------------------------------------------------------

def header_bytes(command, length, session, status=ENCAP_SUCCESS, context=b"neg-test", options=0):
    return HEADER.pack(command, length, session, status, context, options)


def neg_client():
    c = Client(CARD, source=NEG_IP)
    c.context = b"neg-test"
    return c


def exchange(c, raw, want, what):
    """Sends raw bytes; the next reply must be exactly `want` (None: no reply within 0.3 s)."""
    global checks
    checks += 1
    c.send(raw)
    if want is None:
        if not c.expect_nothing(0.3):
            fail(f"{what}: expected no reply, got {hexs(c.receive_raw(0.1) or b'')}")
        return
    got = c.receive_raw()
    if got != want:
        fail(f"{what}:\n  got      {hexs(got or b'')}\n  expected {hexs(want)}")


def still_in_sync(c, what):
    r = c.list_services()
    same(f"{what}: the stream is still in step (ListServices)", (r.command, r.status, r.data),
         (LIST_SERVICES, 0, LIST_SERVICES_DATA))


def negative():
    # Encapsulation level.
    with neg_client() as c:
        exchange(c, encode(0x0001, H("AA BB"), 0x42, c.context),
                 header_bytes(0x0001, 0, 0x42, ENCAP_INVALID_COMMAND), "unknown command 0x0001")
        exchange(c, encode(0x00C8, b"", 0, c.context), header_bytes(0x00C8, 0, 0, ENCAP_INVALID_COMMAND),
                 "unknown command 0x00C8")
        still_in_sync(c, "after unknown commands")
        exchange(c, encode(REGISTER_SESSION, H("01 00"), 0, c.context),
                 header_bytes(REGISTER_SESSION, 0, 0, ENCAP_INVALID_LENGTH), "RegisterSession with 2 bytes: 0x0065")
        exchange(c, encode(LIST_IDENTITY, H("00"), 0, c.context),
                 header_bytes(LIST_IDENTITY, 0, 0, ENCAP_INVALID_LENGTH), "ListIdentity with data: 0x0065")
        exchange(c, encode(REGISTER_SESSION, H("02 00 00 00"), 0, c.context),
                 header_bytes(REGISTER_SESSION, 4, 0, ENCAP_UNSUPPORTED_PROTOCOL) + H("01 00 00 00"),
                 "RegisterSession version 2: 0x0069 naming version 1")
        exchange(c, encode(REGISTER_SESSION, H("01 00 01 00"), 0, c.context),
                 header_bytes(REGISTER_SESSION, 4, 0, ENCAP_UNSUPPORTED_PROTOCOL) + H("01 00 01 00"),
                 "RegisterSession options 1: 0x0069")
        exchange(c, encode(SEND_RR_DATA, send_rr_data_body(get(0x01, 1, 1)), 0, c.context),
                 header_bytes(SEND_RR_DATA, 0, 0, ENCAP_INVALID_SESSION), "SendRRData without a session: 0x0064")
        exchange(c, encode(NOP, H("01 02 03"), 0, c.context), None, "NOP with data: no reply")
        exchange(c, encode(REGISTER_SESSION, H("01 00 00 00"), 0, c.context, options=1), None,
                 "header options 1: dropped")
        still_in_sync(c, "after NOP and a message with options")
        # A message longer than the card's buffer: answered 0x0002, its body skipped, the stream goes on.
        exchange(c, header_bytes(SEND_RR_DATA, 1000, 0) + bytes(1000),
                 header_bytes(SEND_RR_DATA, 0, 0, ENCAP_INSUFFICIENT_MEMORY), "1000-byte message: 0x0002")
        still_in_sync(c, "after the oversized message")
    ok("encapsulation: 0x0001 unknown command, 0x0065 bad length, 0x0069 version/options, 0x0064 no session, "
       "0x0002 oversized (stream kept), NOP and options silent")

    # Sessions belong to their connection (BEY-3).
    a, b = neg_client(), neg_client()
    handle = a.register_session().session
    exchange(b, encode(SEND_RR_DATA, send_rr_data_body(get(0x01, 1, 1)), handle, b.context),
             header_bytes(SEND_RR_DATA, 0, handle, ENCAP_INVALID_SESSION), "another connection's handle: 0x0064")
    own = b.register_session().session
    if own in (0, handle):
        fail(f"second connection's handle 0x{own:08X}")
    exchange(b, encode(SEND_RR_DATA, send_rr_data_body(get(0x01, 1, 1)), handle, b.context),
             header_bytes(SEND_RR_DATA, 0, handle, ENCAP_INVALID_SESSION),
             "another connection's handle on a registered connection: 0x0064")
    exchange(a, encode(REGISTER_SESSION, H("01 00 00 00"), 0, a.context),
             header_bytes(REGISTER_SESSION, 4, handle, ENCAP_INVALID_COMMAND) + H("01 00 00 00"),
             "second RegisterSession on a connection: 0x0001 with the existing handle")
    exchange(a, encode(UNREGISTER_SESSION, b"", handle ^ 1, a.context),
             header_bytes(UNREGISTER_SESSION, 0, handle ^ 1, ENCAP_INVALID_SESSION), "UnRegisterSession, wrong handle")
    exchange(a, encode(SEND_RR_DATA, H("00 00 00 00 00 00"), handle, a.context),
             header_bytes(SEND_RR_DATA, 0, handle, ENCAP_INVALID_LENGTH), "SendRRData of 6 bytes: 0x0065")
    exchange(a, encode(SEND_RR_DATA, H("00 00 00 00 00 00 03 00 00 00 00 00 B2 00 00 00"), handle, a.context),
             header_bytes(SEND_RR_DATA, 0, handle, ENCAP_INCORRECT_DATA), "CPF count 3 with 2 items: 0x0003")
    exchange(a, encode(SEND_RR_DATA, H("00 00 00 00 00 00 02 00 A1 00 04 00 01 00 00 00 B2 00 00 00"), handle,
                       a.context),
             header_bytes(SEND_RR_DATA, 0, handle, ENCAP_INCORRECT_DATA), "SendRRData with a connected address: 0x0003")
    exchange(a, encode(SEND_UNIT_DATA, H("00 00 00 00 00 00 02 00 A1 00 04 00 78 56 34 12 B1 00 02 00 07 00"), handle,
                       a.context), None, "SendUnitData without a connection: no reply")
    same("the first connection's session still works", a.get_attribute_single(0x01, 1, 1).raw(),
         H("8E 00 00 00 79 01"))
    same("the second connection's own session works", b.get_attribute_single(0x01, 1, 1).raw(), H("8E 00 00 00 79 01"))
    same("UnRegisterSession closes", a.unregister_session(), True)
    a.close()
    b.close()
    ok("sessions bound to their TCP connection: 0x0064 for a foreign handle, 0x0001 for a second RegisterSession, "
       "0x0065/0x0003 for bad SendRRData, SendUnitData unanswered")

    # Session table (8) and connection table (9 = sessions + 1), starting from none (the card has seen the
    # FINs).
    wait_stat("eip.sessions", "0", "sessions before the session-table test")
    wait_stat("eip.connections", "0", "connections before the session-table test")
    clients = [neg_client() for _ in range(8)]
    for i, x in enumerate(clients):
        if x.register_session().status != 0:
            fail(f"session {i + 1} of 8 refused")
    ninth = neg_client()
    exchange(ninth, encode(REGISTER_SESSION, H("01 00 00 00"), 0, ninth.context),
             header_bytes(REGISTER_SESSION, 4, 0, ENCAP_INSUFFICIENT_MEMORY) + H("01 00 00 00"),
             "9th RegisterSession: 0x0002")
    r = ninth.list_identity()
    same("a client beyond the session limit still gets ListIdentity", (r.status, r.data), (0, list_identity_data()))
    tenth = None
    try:
        tenth = neg_client()
        tenth.send(encode(LIST_INTERFACES, context=b"neg-test"))
        if tenth.receive(2.0) is not None:
            fail("a 10th TCP connection was served")
        fail("a 10th TCP connection was neither served nor reset")
    except (ConnectionClosed, ConnectionResetError, BrokenPipeError):
        pass
    if tenth is not None:
        tenth.close()
    clients[3].close()
    time.sleep(0.3)
    deadline = time.monotonic() + 3
    while ninth.register_session().status != 0:
        if time.monotonic() > deadline:
            fail("a freed session was not given to the 9th connection")
        time.sleep(0.2)
    for x in clients + [ninth]:
        x.close()
    ok("8 sessions; the 9th RegisterSession 0x0002 (ListIdentity still served); 9 connections, the 10th reset; "
       "a closed connection frees its session")

    # CIP level: the router's error order (docs/ethernetip.md "Error order").
    with neg_client() as c:
        c.register_session()
        cases = [
            # unsupported service before path errors: 0x08
            (mr_request(0x18, epath(0x01, 1, 9) + H("28 01"), H("FF")), "98 00 08 00", "service 0x18, member, data"),
            (mr_request(GET_ATTRIBUTE_LIST, epath(0x01, 1), H("01 00 01 00")), "83 00 08 00",
             "Get_Attribute_List (no object of §4 offers it)"),
            (set_(0x01, 1, 1, "79 01"), "90 00 08 00", "Set on Identity (no Set service)"),
            (set_(0x01, 1, 99, "79 01"), "90 00 08 00", "Set on Identity, unknown attribute: 0x08 first"),
            (mr_request(RESET, epath(0x01, 0)), "85 00 08 00", "class-level Reset"),
            (mr_request(GET_AND_CLEAR, epath(0xF6, 0, 4)), "CC 00 08 00", "class-level Get_and_Clear"),
            (get_all(0x02, 1), "81 00 08 00", "Get_Attributes_All on the Message Router"),
            (set_(0xF5, 0, 1, "01 00"), "90 00 08 00", "class-level Set on TCP/IP"),
            (mr_request(0x8E, epath(0x01, 1, 1)), "8E 00 08 00", "a reply service code as request"),
            # path: 0x04
            (H("0E 03 20 01 24"), "8E 00 04 00", "path longer than the request"),
            (H("0E 01 20 01"), "8E 00 04 00", "no instance"),
            (H("0E 03 43 01 20 01 24 01"), "8E 00 04 00", "unknown segment type"),
            # unknown class 0x05 / instance 0x16 / attribute 0x14, member 0x05
            (get(0x70, 1, 1), "8E 00 05 00", "class 0x70"),
            (get(0x06, 2, 1), "8E 00 16 00", "Connection Manager instance 2"),
            (get(0x01, 2, 1), "8E 00 16 00", "Identity instance 2"),
            (get(0xF6, 3, 1), "8E 00 16 00", "Ethernet Link instance 3"),
            (get(0x04, 103, 3), "8E 00 16 00", "Assembly instance 103 (no such assembly)"),
            (get(0x01, 1, 8), "8E 00 14 00", "Identity attribute 8"),
            (get(0xF5, 1, 7), "8E 00 14 00", "TCP/IP attribute 7 (placeholder only in Get_Attributes_All)"),
            (get(0x01, 0, 5), "8E 00 14 00", "Identity class attribute 5"),
            (mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1)), "8E 00 14 00", "Get_Attribute_Single without attribute"),
            (mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1, 1, member=1)), "8E 00 05 00", "member segment"),
            (mr_request(GET_AND_CLEAR, epath(0xF6, 1, 1)), "CC 00 14 00", "Get_and_Clear of attribute 1"),
            # not settable 0x0E
            (set_(0xF5, 1, 1, "00 00 00 00"), "90 00 0E 00", "TCP/IP status"),
            (set_(0xF5, 1, 2, "00 00 00 00"), "90 00 0E 00", "TCP/IP capability"),
            (set_(0xF6, 1, 1, "64 00 00 00"), "90 00 0E 00", "Ethernet Link speed"),
            # too much / not enough data 0x15 / 0x13
            (mr_request(GET_ATTRIBUTE_SINGLE, epath(0x01, 1, 1), H("00")), "8E 00 15 00", "data with a Get"),
            (mr_request(GET_ATTRIBUTES_ALL, epath(0x01, 1), H("00")), "81 00 15 00", "data with Get_Attributes_All"),
            (set_(0xF5, 1, 3, "00 00 00 00 00"), "90 00 15 00", "configuration control, 5 bytes"),
            (set_(0xF5, 1, 3, "00 00 00"), "90 00 13 00", "configuration control, 3 bytes"),
            (set_(0xF5, 1, 6, "03 00 61 62 63"), "90 00 13 00", "host name without its pad byte"),
            (set_(0xF6, 1, 6, "00 00 0A 00 00"), "90 00 15 00", "interface control, 5 bytes"),
            (set_(0xF5, 1, 11, bytes(34)), "90 00 13 00", "last conflict, 34 bytes"),
            (mr_request(RESET, epath(0x01, 1), H("00 00")), "85 00 15 00", "Reset with 2 bytes"),
            # invalid value 0x09, invalid parameter 0x20
            (set_(0xF5, 1, 3, "03 00 00 00"), "90 00 09 00", "configuration control 3"),
            (set_(0xF5, 1, 3, "12 00 00 00"), "90 00 09 00", "configuration control with DNS"),
            (set_(0xF5, 1, 6, cip_string("a b")), "90 00 09 00", "host name with a space"),
            (set_(0xF5, 1, 6, cip_string("A" * 17)), "90 00 09 00", "host name of 17 characters"),
            (set_(0xF5, 1, 8, "00"), "90 00 09 00", "TTL 0"),
            (set_(0xF5, 1, 9, "01 00 01 00 05 00 00 E0"), "90 00 09 00", "multicast start 224.0.0.5"),
            (set_(0xF5, 1, 10, "02"), "90 00 09 00", "SelectAcd 2"),
            (set_(0xF5, 1, 11, H("00 00 00 01") + bytes(31)), "90 00 09 00", "last conflict not all zero"),
            (set_(0xF5, 1, 5, H("0A 00 A8 C0 00 FF 00 FF 01 00 A8 C0") + bytes(8) + H("00 00")), "90 00 09 00",
             "mask with a hole"),
            (set_(0xF6, 2, 6, "01 00 64 00"), "90 00 09 00", "auto-negotiate with a forced speed"),
            (mr_request(RESET, epath(0x01, 1), H("02")), "85 00 20 00", "Reset type 2"),
            # Multiple Service Packet
            (msp_request([get(0x01, 1, 1), get(0x01, 1, 9)]),
             "8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 79 01 8E 00 14 00", "MSP with a failing member"),
            (mr_request(MULTIPLE_SERVICE_PACKET, epath(0x02, 1)), "8A 00 13 00", "MSP without a count"),
            (mr_request(MULTIPLE_SERVICE_PACKET, epath(0x02, 1), H("01 00 0C 00") + get(0x01, 1, 1)), "8A 00 13 00",
             "MSP offset past the end"),
            (mr_request(MULTIPLE_SERVICE_PACKET, epath(0x02, 1), H("02 00 0E 00 06 00") + get(0x01, 1, 1) * 2),
             "8A 00 20 00", "MSP offsets going down"),
            (mr_request(MULTIPLE_SERVICE_PACKET, epath(0x01, 1), H("01 00 04 00") + get(0x01, 1, 1)), "8A 00 08 00",
             "MSP to the Identity object"),
            # Unconnected_Send routes and nesting
            (unconnected_send(get(0x01, 1, 1), port_segment(1, 3)), "D2 00 01 01 12 03 01 00", "route to slot 3"),
            (unconnected_send(get(0x01, 1, 1), port_segment(2, 5)), "D2 00 01 01 12 03 01 00", "route out on Ethernet"),
            (unconnected_send(get(0x01, 1, 1), port_segment(1, 0) + port_segment(3, 1)), "D2 00 01 01 11 03 02 00",
             "route via port 3"),
            (unconnected_send(get(0x01, 1, 1), H("20 01")), "D2 00 01 01 15 03 01 00", "route that is no port segment"),
            (H("52 02 20 06 24 01 0A F0 08"), "D2 00 13 00", "Unconnected_Send cut short"),
            (unconnected_send(get(0x01, 1, 1), port_segment(1, 0)) + H("00"), "D2 00 15 00",
             "bytes after the route"),
            (unconnected_send(unconnected_send(msp_request([get(0x01, 1, 1)]))), "8A 00 02 00", "nesting depth 3"),
        ]
        for request, want, what in cases:
            ask(c, request, want, what)
        # The stored settings are what the walk left: nothing above changed them.
        ask(c, get(0xF5, 1, 6), H("8E 00 00 00") + cip_string("EIP-TEST1"), "host name unchanged")
        ask(c, get(0xF5, 1, 8), "8E 00 00 00 05", "TTL unchanged")
        ok(f"CIP: {len(cases)} error cases (0x08 before path checks, 0x04, 0x05, 0x16, 0x14, 0x0E, 0x15, 0x13, "
           "0x09, 0x20, MSP 0x1E/0x13/0x20, Unconnected_Send 0x01 + 0x0311/0x0312/0x0315, 0x13/0x15, nesting 0x02); "
           "no setting changed")

    # UDP: TCP-only commands, bad lengths, malformed datagrams, broadcasts never answered with errors.
    def udp(raw, host=CARD, broadcast=False, wait=0.5):
        return [(p, x.encode()) for _, p, x in udp_exchange(host, raw, broadcast=broadcast, wait=wait, source=NEG_IP)]
    same("RegisterSession over unicast UDP",
         udp(encode(REGISTER_SESSION, H("01 00 00 00"), 0, b"neg-test")),
         [((CARD, 44818), header_bytes(REGISTER_SESSION, 0, 0, ENCAP_INVALID_COMMAND))])
    same("SendRRData over unicast UDP", udp(encode(SEND_RR_DATA, send_rr_data_body(get(0x01, 1, 1)), 7, b"neg-test")),
         [((CARD, 44818), header_bytes(SEND_RR_DATA, 0, 7, ENCAP_INVALID_COMMAND))])
    same("unknown command over unicast UDP", udp(encode(0x0001, b"", 0, b"neg-test")),
         [((CARD, 44818), header_bytes(0x0001, 0, 0, ENCAP_INVALID_COMMAND))])
    same("ListIdentity with data over unicast UDP", udp(encode(LIST_IDENTITY, H("00"), 0, b"neg-test")),
         [((CARD, 44818), header_bytes(LIST_IDENTITY, 0, 0, ENCAP_INVALID_LENGTH))])
    same("NOP over UDP", udp(encode(NOP, b"", 0, b"neg-test")), [])
    same("datagram shorter than its header", udp(encode(LIST_IDENTITY)[:23]), [])
    same("datagram longer than its header says", udp(encode(LIST_IDENTITY) + H("00")), [])
    same("datagram with options", udp(encode(LIST_IDENTITY, options=4)), [])
    broadcast = CARD.rsplit(".", 1)[0] + ".255"
    same("RegisterSession broadcast", udp(encode(REGISTER_SESSION, H("01 00 00 00")), broadcast, True), [])
    same("ListIdentity with data broadcast", udp(encode(LIST_IDENTITY, H("00")), broadcast, True, 1.0), [])
    ok("UDP: TCP-only and unknown commands 0x0001, bad length 0x0065 (unicast); malformed datagrams, NOP and "
       "every broadcast error dropped")

    # Afterwards a healthy client (from the main host address) is still served.
    with Client(CARD) as c:
        same("healthy client: RegisterSession", c.register_session().status, 0)
        same("healthy client: vendor ID", c.get_attribute_single(0x01, 1, 1).raw(), H("8E 00 00 00 79 01"))
        same("healthy client: UnRegisterSession", c.unregister_session(), True)
    replies = list_identity_udp(CARD)
    same("healthy client: unicast ListIdentity", [x.data for _, _, x in replies], [list_identity_data()])
    ok("a healthy client is served after the negative cases")
    print(f"negative: {checks} checks passed")


# ---- reset: Identity Reset restarts the card; what was stored survives ----------------------------

def ready_lines():
    with open(os.environ["CARD_LOG"], errors="replace") as log:
        return sum(1 for line in log if line.startswith("ready "))


def reset_and_wait(reset_type):
    lines = ready_lines()
    with Client(CARD) as c:
        c.register_session()
        ask(c, mr_request(RESET, epath(0x01, 1), b"" if reset_type is None else bytes([reset_type])), "85 00 00 00",
            f"Identity Reset type {reset_type}")
    started = time.monotonic()
    while ready_lines() <= lines:
        if time.monotonic() - started > 15:
            fail(f"no new ready line within 15 s of Reset type {reset_type}")
        time.sleep(0.1)
    deadline = time.monotonic() + 10
    while True:
        try:
            replies = list_identity_udp(CARD, wait=0.5)
            if replies:
                same("ListIdentity after the restart", replies[0][2].data, list_identity_data())
                break
        except OSError:
            pass
        if time.monotonic() > deadline:
            fail("the card does not answer ListIdentity within 10 s of its restart")
    return time.monotonic() - started


def reset():
    took = reset_and_wait(None)
    with Client(CARD) as c:
        c.register_session()
        ask(c, get(0xF5, 1, 6), H("8E 00 00 00") + cip_string("EIP-TEST1"), "host name after the reset (c081-c096)")
        ask(c, get(0xF5, 1, 3), "8E 00 00 00 00 00 00 00", "configuration control after the reset (c504)")
        ask(c, get(0xF5, 1, 8), "8E 00 00 00 05", "TTL after the reset (card store)")
        ask(c, get(0xF5, 1, 9), "8E 00 00 00 01 00 20 00 00 01 C0 EF", "multicast after the reset")
        ask(c, get(0xF5, 1, 10), "8E 00 00 00 00", "SelectAcd after the reset")
        ask(c, get(0xF6, 1, 6), "8E 00 00 00 01 00 00 00", "interface control after the reset (c501)")
    ok(f"Identity Reset (no data) answered, card restarted in {took:.1f} s; stored settings survived")
    took = reset_and_wait(1)
    with Client(CARD) as c:
        c.register_session()
        ask(c, get(0xF5, 1, 8), "8E 00 00 00 01", "TTL after the factory reset")
        ask(c, get(0xF5, 1, 9), H("8E 00 00 00") + bytes(8), "multicast after the factory reset")
        ask(c, get(0xF5, 1, 10), "8E 00 00 00 01", "SelectAcd after the factory reset")
        ask(c, get(0xF5, 1, 6), H("8E 00 00 00") + cip_string("EIP-TEST1"),
            "host name after the factory reset (the drive's c081-c096 stay)")
        ask(c, get(0x01, 1, 1), "8E 00 00 00 79 01", "vendor ID after the factory reset")
    ok(f"Identity Reset type 1: restarted in {took:.1f} s; the card's own settings (TTL, multicast, SelectAcd) "
       "back to defaults, the inverter's c-parameters kept")


# ---- closed: c500 = 0 -----------------------------------------------------------------------------

def closed():
    try:
        socket.create_connection((CARD, EIP_PORT), 2).close()
        fail("TCP 44818 accepted a connection with c500 = 0")
    except ConnectionRefusedError:
        pass
    ok("TCP 44818 refused (RST) with c500 = 0")
    try:
        replies = list_identity_udp(CARD, wait=1.0)
    except ConnectionRefusedError:  # an ICMP port unreachable reached the socket: no EtherNet/IP reply either
        replies = []
    same("unicast ListIdentity with c500 = 0", replies, [])
    broadcast = CARD.rsplit(".", 1)[0] + ".255"
    same("broadcast ListIdentity with c500 = 0", list_identity_udp(broadcast, broadcast=True, max_delay_ms=500,
                                                                    wait=1.5), [])
    ok("UDP 44818: ListIdentity unanswered (unicast and broadcast)")
    # Modbus TCP serves: FC 03 of drive register 0x0009 (unit 0).
    with socket.create_connection((CARD, 502), 3) as s:
        s.settimeout(3)
        s.sendall(H("00 01 00 00 00 06 00 03 00 09 00 01"))
        reply = b""
        while len(reply) < 11:
            chunk = s.recv(64)
            if not chunk:
                break
            reply += chunk
    same("Modbus FC 03 reply header", reply[:9], H("00 01 00 00 00 05 00 03 02"))
    ok(f"Modbus TCP 502 serves (FC 03 of 0x0009 = 0x{reply[9:11].hex()})")


{"walk": walk, "negative": negative, "reset": reset, "closed": closed}[sys.argv[1]]()
PY

if [ "$c500" = 0 ]; then
  "$PY" -c "$CHECKS" closed || fail "c500=0 phase"
  pass "c500 = 0: EtherNet/IP ports closed, Modbus TCP serves"
  exit 0
fi
[ "$c500" = 1 ] || fail "this test needs c500 = 0 or 1, the card has $c500"

# A second host address on the TAP (the negative cases come from it) and a route for the limited
# broadcast st-ethernet-ip's Browser sends (the namespace has no default route).
ip addr add "$NEG_IP/24" dev "$TAP_L"
ip route add 255.255.255.255/32 dev "$TAP_L"
wait_for 10 "$PY" -c "import socket; socket.create_connection(('$CARD_IP', 44818), 1).close()" \
  || fail "EtherNet/IP port 44818 not open"

started=$SECONDS
"$PY" -c "$CHECKS" walk || fail "positive walk"
echo "   ($((SECONDS - started)) s)"

# st-ethernet-ip: discovery and explicit messages.
serial="0x$(printf '%x' "0x$(tr -d : <<<"$CARD_MAC" | cut -c5-12)")"
expected=$(printf '{"vendorID":377,"deviceType":2,"productCode":32000,"productName":"VF-MB1","serialNumber":"%s","revision":"1.8"}' "$serial")
timeout 30 node "$IT/eip_browse.js" "$CARD_IP" "$expected" || fail "st-ethernet-ip"

started=$SECONDS
"$PY" -c "$CHECKS" negative || fail "negative cases"
echo "   ($((SECONDS - started)) s)"

# The capture (before the reset: a restart begins a new capture file).
pcap="$CARD_STATE_DIR/../eip.pcap"
sleep 0.3  # the last frames reach the file
cp "$CARD_PCAP" "$pcap"
bad="_ws.malformed || _ws.expert.severity >= warning"
count() { tshark -r "$pcap" -Y "$1" 2>/dev/null | wc -l; }
# Our positive traffic (walk, st-ethernet-ip): nothing malformed, no expert warning or error, except the
# TCP reset of the refused Modbus connection (tcp.connection.rst is a warning).
ours="ip.addr == $HOST_IP && !tcp.connection.rst && ($bad)"
n=$(count "$ours")
[ "$n" -eq 0 ] || { tshark -r "$pcap" -Y "$ours" -V 2>/dev/null | grep -E "^Frame|Expert|Malformed" | head -40
                    fail "$n frames of the positive traffic malformed or with expert warnings"; }
enip=$(count "ip.addr == $HOST_IP && (enip || cip)")
[ "$enip" -ge 200 ] || fail "only $enip EtherNet/IP frames of the positive traffic in the capture"
# The negative cases (from NEG_IP): our requests are malformed on purpose and may be flagged; every
# frame the card sends back must still dissect cleanly.
replies="ip.src == $CARD_IP && ip.dst == $NEG_IP && !tcp.connection.rst && ($bad)"
n=$(count "$replies")
[ "$n" -eq 0 ] || { tshark -r "$pcap" -Y "$replies" -V 2>/dev/null | grep -E "^Frame|Expert|Malformed" | head -40
                    fail "$n replies to the negative cases malformed or with expert warnings"; }
flagged=$(count "ip.src == $NEG_IP && ($bad)")
pass "capture: $enip EtherNet/IP frames of positive traffic clean; replies to the negative cases clean ($flagged of our deliberately bad requests flagged by the dissector)"

started=$SECONDS
"$PY" -c "$CHECKS" reset || fail "Identity Reset"
echo "   ($((SECONDS - started)) s)"
pcap=$CARD_PCAP
n=$(count "($bad) && !tcp.connection.rst")
[ "$n" -eq 0 ] || { tshark -r "$pcap" -Y "($bad) && !tcp.connection.rst" 2>/dev/null | head -20
                    fail "$n malformed or flagged frames in the capture after the restart"; }
pass "EtherNet/IP over TAP: objects, settings, MSP, Unconnected_Send, discovery, st-ethernet-ip, errors, reset"
