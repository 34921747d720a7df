#!/usr/bin/env bash
# The built EDS against the running host card (docs/eds.md; CTest integration.eds_loopback): the card on
# the loopback port with EtherNet/IP on (c500=1), as any user. For the VF-MB1 EDS (the simulated inverter
# is a VF-MB1), every [Params] entry with a link path is read back from the Parameter object 0x0F over
# explicit messaging: its name (7), units (8), min (10), max (11), default (12), divisor (14), decimals (21)
# and data type (5) equal the EDS's fields, and its value (1) reads with status 0 through the drive link;
# every [Assembly] entry's size equals the card's Assembly attribute 4; class attribute 2 of 0x0F is the
# number of linked parameters.
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
PY
pass "the VF-MB1 EDS agrees with the running card"
