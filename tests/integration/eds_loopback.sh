#!/usr/bin/env bash
# The built EDS against the running host card (docs/eds.md; CTest integration.eds_loopback): the card on
# the loopback port with EtherNet/IP on (c500=1), as any user. For the VF-MB1 EDS (the simulated inverter
# is a VF-MB1), every [Params] entry with a link path is read back from the Parameter object 0x0F over
# explicit messaging: its name (7), units (8), min (10), max (11), default (12), divisor (14), decimals (21)
# and data type (5) equal the EDS's fields, and its value (1) reads with status 0 through the drive link;
# every [Assembly] entry's size equals the card's Assembly attribute 4; class attribute 2 of 0x0F is the
# number of linked parameters; every [Connection Manager] entry opens (Forward_Open status 0) with its
# own path, sizes, transport and T->O type at its RPI parameter's default, minimum and maximum, and
# closes (a listen-only one beside a multicast input-only connection of its point).
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
EDS_DIR=${EDS_DIR:-$ROOT/build/host/eds}
[ -f "$EDS_DIR/IPE002Z_VF-MB1.eds" ] || fail "no $EDS_DIR/IPE002Z_VF-MB1.eds (build the target ipe_eds)"
host_addr=127.0.0.41
start_loopback_card "$host_addr" --param c500=1
wait_for 10 /usr/bin/python3 -c "import socket; socket.create_connection(('$host_addr', 44818), 1)" \
  || fail "EtherNet/IP port not open"

PYTHONPATH="$IT" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 - "$host_addr" "$EDS_DIR/IPE002Z_VF-MB1.eds" <<'PY' \
  || fail "EDS and card disagree"
import re, struct, sys, time
from eip_originator import Client
from eip_io import (TYPE_MULTICAST, TYPE_P2P, Triad, decode_open_success, forward_close, forward_open, net_params,
                    open_connection)

host, path = sys.argv[1], sys.argv[2]
text = open(path, encoding="ascii").read()


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def fields(entry):
    """The comma-separated fields of an EDS entry, strings unquoted (no comments in the card's EDS)."""
    out, field, quoted = [], "", False
    for ch in entry:
        if ch == '"':
            quoted = not quoted
        elif ch == "," and not quoted:
            out.append(field.strip())
            field = ""
        else:
            field += ch
    out.append(field.strip())
    return out


def section(name):
    start = text.index("\n[" + name + "]\n")
    end = text.find("\n[", start + 1)
    return text[start:end if end >= 0 else len(text)]


params = {int(n): fields(body) for n, body in re.findall(r"\n    Param(\d+) =\n(.*?);(?=\n)", section("Params"), re.S)}
assemblies = {int(n): fields(body) for n, body in re.findall(r"\n    Assem(\d+) =\n(.*?);(?=\n)", section("Assembly"), re.S)}
linked = {n: f for n, f in params.items() if f[1]}
if len(linked) < 100 or len(assemblies) != 13:
    fail(f"{len(linked)} linked parameters and {len(assemblies)} assemblies in the EDS")

with Client(host, timeout=5.0) as client:
    client.register_session()

    def get(class_id, instance, attribute):
        reply = client.get_attribute_single(class_id, instance, attribute)
        if reply.general != 0:
            fail(f"Get {class_id:#x}/{instance}/{attribute}: status {reply.general:#04x}")
        return reply.data

    def short_string(data):
        return data[1:1 + data[0]].decode("ascii")

    # The drive link comes up after the configuration load: wait for the first value (bounded).
    deadline = time.monotonic() + 20
    while client.get_attribute_single(0x0F, 6, 1).general != 0:
        if time.monotonic() > deadline:
            fail("acc never read through 0x0F")
        time.sleep(0.2)

    count = struct.unpack("<H", get(0x0F, 0, 2))[0]
    if count != len(linked):
        fail(f"0x0F has {count} instances, the EDS {len(linked)} linked parameters")
    for n, f in sorted(linked.items()):
        # reserved, path size, path, descriptor, type, size, name, units, help, min, max, default,
        # multiplier, divisor, base, offset, 4 links, decimals
        if f[2] != f"20 0F 24 {n:02X} 30 01":
            fail(f"Param{n} path {f[2]}")
        data_type = int(f[4], 16)
        signed = data_type == 0xC3
        fmt = "<h" if signed else "<H"
        checks = [
            (5, bytes([data_type])),
            (7, None, f[6]), (8, None, f[7]),
            (10, struct.pack(fmt, int(f[9]))), (11, struct.pack(fmt, int(f[10]))),
            (12, struct.pack(fmt, int(f[11]))), (14, struct.pack("<H", int(f[13]))),
            (21, bytes([int(f[20])])),
        ]
        for check in checks:
            data = get(0x0F, n, check[0])
            if len(check) == 3:
                if short_string(data) != check[2]:
                    fail(f"Param{n} attribute {check[0]}: {short_string(data)!r} != {check[2]!r}")
            elif data != check[1]:
                fail(f"Param{n} attribute {check[0]}: {data.hex()} != {check[1].hex()}")
        value = get(0x0F, n, 1)
        if len(value) != 2:
            fail(f"Param{n} value {value.hex()}")
    print(f"ok: {len(linked)} parameters agree with 0x0F (type, name, units, min, max, default, scaling, value)")

    for instance, f in sorted(assemblies.items()):
        size = struct.unpack("<H", get(0x04, instance, 4))[0]
        if size != int(f[2]):
            fail(f"Assem{instance}: EDS size {f[2]}, card {size}")
    print(f"ok: {len(assemblies)} assembly sizes agree with Assembly attribute 4")

    # [Connection Manager]: every connection opens with its own path, sizes and transport, at the RPI
    # parameter's default, minimum and maximum, and closes. A listen-only connection needs a multicast
    # producer of its input point: an input-only connection of the same point is opened first.
    connections = {int(n): fields(body) for n, body in
                   re.findall(r"\n    Connection(\d+) =\n(.*?);(?=\n)", section("Connection Manager"), re.S)}
    if len(connections) != 18:
        fail(f"{len(connections)} connections in the EDS, 18 expected (6 exclusive owner, input only, listen only)")
    serial = [0x4000]

    def point(path, index):  # "20 04 24 cc 2C o 2C t": index 0 the consumed point o, 1 the produced t
        return int(path.split()[2 * index + 5], 16)

    def rpi_limits(reference):
        p = params[int(reference[len("Param"):])]
        return int(p[9]), int(p[10]), int(p[11])

    def open_close(n, f, rpi, t_o_kind):
        trigger, parameters = int(f[0], 16), int(f[1], 16)
        o_t_size, t_o_size, path = int(f[3]), int(f[6]), f[14]
        # Trigger and transport: the lowest class bit (0-3) and trigger bit (16-18) it supports, as the
        # Forward_Open's transport byte (trigger << 4 | class).
        transport = ((((trigger >> 16) & 0x7) & -((trigger >> 16) & 0x7)).bit_length() - 1) << 4
        transport |= ((trigger & 0xF) & -(trigger & 0xF)).bit_length() - 1
        # O->T format (bits 8-11): 4 = run/idle header, 3 = heartbeat; T->O (12-15) 0 = modeless.
        o_t_format = (parameters >> 8) & 0xF
        o_t_bytes = o_t_size + (6 if o_t_format == 4 else 2)
        serial[0] += 1
        triad = Triad(serial[0])
        request = forward_open(triad, bytes.fromhex(path), rpi, net_params(o_t_bytes), rpi,
                               net_params(t_o_size + 2, kind=t_o_kind), transport=transport,
                               multiplier=7)
        mr, raw, _ = open_connection(client, request)
        if mr.general != 0:
            fail(f"Connection{n} ({f[12]}) at RPI {rpi} us: Forward_Open refused: {mr!r}")
        return triad, bytes.fromhex(path)

    def close(n, opened):
        mr, raw, _ = open_connection(client, forward_close(*opened))
        if mr.general != 0:
            fail(f"Connection{n}: Forward_Close refused: {mr!r}")

    opened_rpis = 0
    for n, f in sorted(connections.items()):
        kind = int(f[0], 16) >> 24  # 4 exclusive owner, 2 input only, 1 listen only (application type)
        low, high, default = rpi_limits(f[2])
        if rpi_limits(f[5]) != (low, high, default) or low != 1000:
            fail(f"Connection{n}: RPI limits {low}..{high} (default {default})")
        for rpi in (default, low, high):
            if kind == 1:  # listen only: beside a multicast input-only connection of the same point
                producer = next(g for g in connections.values()
                                if int(g[0], 16) >> 24 == 2 and point(g[14], 1) == point(f[14], 1))
                owner = open_close(0, producer, rpi, TYPE_MULTICAST)
                close(n, open_close(n, f, rpi, TYPE_MULTICAST))
                close(0, owner)
            else:
                close(n, open_close(n, f, rpi, TYPE_P2P))
            opened_rpis += 1
    print(f"ok: {len(connections)} connections of the EDS opened and closed with their own path and sizes "
          f"({opened_rpis} opens at the RPI default, minimum and maximum)")
PY
pass "the VF-MB1 EDS agrees with the running card"
