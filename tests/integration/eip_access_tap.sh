#!/usr/bin/env bash
# The exclusive-owner write lock with two originators over TAP in a namespace (docs/security.md
# "Exclusive-owner write lock"; CTest integration.eip_access, subnet 10.243.0). The owner is the kernel
# side of tapL (HOST_IP, 10.243.0.1); the stranger is a second address on the same TAP (10.243.0.3).
#
# Card started with c500=1 (EtherNet/IP), c101=1 (a closed owner is no trip), c001=2 c002=0 (scanner word 1
# is FA23, nothing targets FA06/FA07): the owner's exclusive owner 102/152 carries scanner words only, so
# the Control Supervisor's own ownership rule (docs/drive-objects.md) leaves explicit Run1 open and only the
# lock stands between a stranger and the motor.
#
# While the owner's 102/152 runs (RPI 10 ms), every control request of the stranger (0x29 Run1/Reset,
# 0x2A SpeedRef, assembly 20 data, 0x65 FA06/FA07/FA50, 0x64 cmod, Identity Reset), unconnected, inside a
# Multiple Service Packet and over the stranger's own class 3 connection, gets exactly 0x10 and nothing
# changes in the inverter; its Forward_Open of an exclusive owner 21/71 gets 0x01/0x0106; its Gets and a
# parameter Set (acc) are served. The owner, on a second TCP connection and session, commands the drive
# (Run1 -> FA06 0x0400, FA50 written). After the owner's Forward_Close the stranger may command.
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CARD_IP HOST_IP CARD_CONTROL
export STRANGER_IP="${HOST_IP%.*}.3"
ip addr add "$STRANGER_IP/24" dev "$TAP_L"
wait_for 10 /usr/bin/python3 -c "import socket; socket.create_connection(('$CARD_IP', 44818), 1)" \
  || fail "EtherNet/IP port not open"

/usr/bin/python3 - <<'PY' || fail "exclusive-owner write lock"
import os, struct, sys, time
from eip_originator import *
from eip_io import *

CARD, OWNER, STRANGER = os.environ["CARD_IP"], os.environ["HOST_IP"], os.environ["STRANGER_IP"]
sim = SimControl(os.environ["CARD_CONTROL"])
checks = 0


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def same(what, got, want):
    global checks
    checks += 1
    if got != want:
        fail(f"{what}:\n  got      {hexs(got) if isinstance(got, bytes) else got}\n"
             f"  expected {hexs(want) if isinstance(want, bytes) else want}")


def H(text):
    return bytes.fromhex(text.replace("|", " "))


def ask(client, request, want, what):
    same(what, client.cip(H(request)).raw(), H(want))


def session(source):
    client = Client(CARD, source=source)
    if client.register_session().status != ENCAP_SUCCESS:
        fail(f"RegisterSession from {source}")
    return client


def refusals():
    return int(sim.stats()["cip.control_lock_refusals"])


owner, stranger = session(OWNER), session(STRANGER)
sim.set("fa50", 0)
before = sim.status()

# The owner's exclusive owner 102/152 (12 bytes each way), RPI 10 ms, run.
triad, path = Triad(0x5EC1), io_path(102, 152)
mr, raw, _ = open_connection(owner, forward_open(triad, path, 10000, net_params(2 + 4 + 12), 10000,
                                                 net_params(2 + 12), t_o_id=0x5EC00001, multiplier=2))
if mr.general != 0:
    fail(f"owner's Forward_Open 102/152 refused: {hexs(raw)}")
o_t_id = decode_open_success(mr.data)["o_t_id"]
with IoEndpoint(CARD) as ep:
    io = ep.add(IoConnection(o_t_id, 0x5EC00001, 10000, bytes(12), name="102/152"))
    if not ep.wait_count(0x5EC00001, 20, 3.0):
        fail("no T->O production of 102/152")
    print("ok: the owner's exclusive owner 102/152 runs at RPI 10 ms", flush=True)

    # Every control request of the stranger: 0x10, before anything happens.
    base = refusals()
    ask(stranger, "10 03 20 29 24 01 30 03 01", "90 00 10 00", "stranger: 0x29 Run1 = 1")
    ask(stranger, "05 02 20 29 24 01", "85 00 10 00", "stranger: 0x29 Reset")
    ask(stranger, "10 03 20 2A 24 01 30 08 08 07", "90 00 10 00", "stranger: 0x2A SpeedRef = 1800 rpm")
    ask(stranger, "10 03 20 04 24 14 30 03 01 00 08 07", "90 00 10 00", "stranger: assembly 20 Run Fwd")
    ask(stranger, "10 04 20 65 25 00 06 FA 30 03 00 84", "90 00 10 00", "stranger: 0x65 FA06 = 0x8400")
    ask(stranger, "10 04 20 65 25 00 07 FA 30 03 70 17", "90 00 10 00", "stranger: 0x65 FA07 = 60 Hz")
    ask(stranger, "10 04 20 65 25 00 50 FA 30 03 01 00", "90 00 10 00", "stranger: 0x65 FA50 = 1")
    ask(stranger, "10 04 20 64 25 00 03 40 30 03 00 00", "90 00 10 00", "stranger: 0x64 cmod = 0")
    ask(stranger, "05 02 20 01 24 01", "85 00 10 00", "stranger: Identity Reset")
    ask(stranger, "0A 02 20 02 24 01 | 02 00 06 00 0E 00 | 0E 03 20 29 24 01 30 06 | 10 03 20 29 24 01 30 03 01",
        "8A 00 1E 00 | 02 00 06 00 0B 00 | 8E 00 00 00 03 | 90 00 10 00", "stranger: MSP Get State + Run1")
    # Its own class 3 connection is welcome, a command over it is not.
    c3_triad = Triad(0x5EC3)
    mr, raw, _ = open_connection(stranger, forward_open(c3_triad, ROUTER_PATH, 2000000, net_params(500, variable=True),
                                                        2000000, net_params(500, variable=True),
                                                        transport=CLASS3_SERVER_APPLICATION, t_o_id=0x5EC30001))
    if mr.general != 0:
        fail(f"stranger's class 3 Forward_Open refused: {hexs(raw)}")
    explicit = ExplicitConnection(stranger, decode_open_success(mr.data)["o_t_id"], 0x5EC30001)
    got = explicit.request(1, H("10 03 20 29 24 01 30 03 01"))
    same("stranger: Run1 over class 3", got, (0x5EC30001, 1, H("90 00 10 00")))
    same("stranger: refusals counted", refusals() - base, 11)
    # An exclusive owner of another output: the drive has one owner (0x0106).
    t2 = Triad(0x5EC2)
    mr, raw, _ = open_connection(stranger, forward_open(t2, io_path(21, 71), 10000, net_params(10), 10000,
                                                        net_params(6), t_o_id=0x5EC20001))
    same("stranger: Forward_Open exclusive owner 21/71", raw, refused_bytes(t2, [0x0106]))
    after = sim.status()
    for field in ("fa06", "fa07", "fa50"):
        same(f"inverter {field} unchanged by the stranger", after.get(field), before.get(field))
    print("ok: every control request of the stranger is refused with 0x10, nothing reached the inverter",
          flush=True)

    # Reads and parameters stay open to the stranger.
    ask(stranger, "0E 03 20 29 24 01 30 03", "8E 00 00 00 00", "stranger: Get Run1")
    ask(stranger, "0E 03 20 01 24 01 30 01", "8E 00 00 00 79 01", "stranger: Get Identity vendor")
    ask(stranger, "10 04 20 65 25 00 09 00 30 03 28 00", "90 00 00 00", "stranger: 0x65 acc = 4.0 s")
    same("acc written by the stranger", sim.get("acc"), 40)
    print("ok: the stranger's Gets and its parameter write (acc) are served", flush=True)

    # The owner's address, on another TCP connection and session than its Forward_Open's.
    owner2 = session(OWNER)
    ask(owner2, "10 04 20 65 25 00 50 FA 30 03 01 00", "90 00 00 00", "owner: 0x65 FA50 = 1")
    same("FA50 written by the owner", sim.get("fa50"), 1)
    ask(owner2, "10 03 20 29 24 01 30 03 01", "90 00 00 00", "owner: 0x29 Run1 = 1")
    deadline = time.monotonic() + 2.0
    while sim.status().get("fa06") != "0x0400":
        if time.monotonic() > deadline:
            fail(f"owner's Run1 did not reach FA06: {sim.status().get('fa06')}")
        time.sleep(0.01)
    ask(owner2, "10 03 20 29 24 01 30 03 00", "90 00 00 00", "owner: 0x29 Run1 = 0")
    print("ok: the owner's address commands the drive from another session (Run1 -> FA06 0x0400, FA50)",
          flush=True)

    ep.stop_sending(io)
    mr, raw, _ = open_connection(owner, forward_close(triad, path))
    same("owner's Forward_Close", raw, close_success_bytes(triad))

# No exclusive owner: the stranger may command.
ask(stranger, "10 04 20 65 25 00 50 FA 30 03 00 00", "90 00 00 00", "stranger without an owner: FA50 = 0")
same("FA50 written by the stranger once the owner is gone", sim.get("fa50"), 0)
print(f"ok: after the owner's Forward_Close the stranger may command ({checks} checks)", flush=True)
PY
pass "exclusive-owner write lock with two originators"
