"""The command/effect matrix of issue 21 (docs/drive-control.md): every control path of the EtherNet/IP card
in every loss state, each row's answer (exact CIP general status per request, HTTP status) and its effect in
the simulated inverter (FA06/FA07, output frequency, trip) and c536/the loss action. A success row must show
its effect, an error row none. The rows are one table (ROWS x STATES, expected values from EXPECT); the
markdown of docs/drive-control-matrix.md is printed from the same data and compared with the committed file.

Run by drive_control_matrix_tap.sh (card c500 = 1, acc = dec = 0.5 s, sr3 = 25 Hz)."""
import http.cookiejar
import json
import os
import time
import urllib.request

from eip_originator import *
from eip_io import *
from drive_matrix import RUN, SPEED_30HZ, effect, fail, inverter, settle, sim, stat, wait_until

CARD = os.environ["CARD_IP"]
RPI = 20000  # µs, multiplier 2: timeout 320 ms
RUN_WORD = 0xC400    # priority (command, frequency) + run
STOP_WORD = 0x8000   # command priority, no run: a deceleration stop, distinct from every c101 action's FA06


def u16(value):
    return struct.pack("<H", value & 0xFFFF)


def set_request(class_id, instance, attribute, value):
    return mr_request(SET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute), value)


# ---- the paths ---------------------------------------------------------------------------------------------

# The sequence: NetCtrl, NetRef, SpeedRef 900 rpm (30 Hz with 2 pole pairs), Run1.
CIP_RUN = [(0x29, 1, 5, b"\x01"), (0x2A, 1, 4, b"\x01"), (0x2A, 1, 8, u16(900)), (0x29, 1, 3, b"\x01")]
CIP_STOP = [(0x29, 1, 3, b"\x00")]
PARAM_RUN = [(0x65, 0xFA07, 3, u16(SPEED_30HZ)), (0x65, 0xFA06, 3, u16(RUN_WORD))]
PARAM_STOP = [(0x65, 0xFA06, 3, u16(STOP_WORD))]
# 0x64: F-numbers at number - 0x8000 (FA06 -> 7A06h, FA07 -> 7A07h, docs/drive-objects.md).
PARAM64_RUN = [(0x64, 0x7A07, 3, u16(SPEED_30HZ)), (0x64, 0x7A06, 3, u16(RUN_WORD))]
PARAM64_STOP = [(0x64, 0x7A06, 3, u16(STOP_WORD))]


def answer_codes(replies):
    return " ".join(f"{r.general:02X}" for r in replies)


def unconnected(ctx, sets):
    return answer_codes([ctx.client.cip(set_request(*s)) for s in sets])


def open_class3(ctx):
    """A class 3 connection to the Message Router (its open restores a loss with no exclusive owner open;
    its Forward_Close is no loss): its triad and its ExplicitConnection."""
    triad = Triad(0x0C00 + ctx.serial())
    t_o_id = 0x3C000000 + triad.serial
    request = forward_open(triad, ROUTER_PATH, 1000000, net_params(500, variable=True), 1000000,
                           net_params(500, variable=True), transport=CLASS3_SERVER_APPLICATION, t_o_id=t_o_id,
                           multiplier=1)
    mr, raw, _ = open_connection(ctx.client, request)
    if mr.general != 0:
        fail(f"class 3 Forward_Open refused: {hexs(raw)}")
    return triad, ExplicitConnection(ctx.client, decode_open_success(mr.data)["o_t_id"], t_o_id)


def class3(ctx, sets):
    """The Sets over a class 3 connection opened for them, then its Forward_Close."""
    triad, x = open_class3(ctx)
    codes = []
    for n, s in enumerate(sets, 1):
        reply = x.request(n, set_request(*s))
        codes.append(f"{reply[2][2]:02X}")
    open_connection(ctx.client, forward_close(triad, ROUTER_PATH))
    return " ".join(codes)


class Web:
    def __init__(self):
        self.jar = http.cookiejar.CookieJar()
        self.opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor(self.jar))
        self.csrf = None

    def post(self, path, body):
        headers = {"Content-Type": "application/json"}
        if self.csrf:
            headers["X-CSRF-Token"] = self.csrf
        request = urllib.request.Request(f"http://{CARD}{path}", json.dumps(body).encode(), headers, method="POST")
        try:
            with self.opener.open(request, timeout=10) as reply:
                return reply.status, json.loads(reply.read() or b"{}")
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read() or b"{}")

    def login(self):
        status, body = self.post("/api/login", {"password": "USER"})
        if status != 200:
            fail(f"web login: {status}")
        self.csrf = body["csrf"]
        if self.post("/api/elevate", {"password": "USER"})[0] != 200:
            fail("web elevate")

    def write(self, words):
        out = []
        for number, value in words:
            status, body = self.post("/api/registers", {"number": number, "value": value})
            out.append(f"{status}" + (f" {body['error']}" if "error" in body else ""))
        return ", ".join(out)


WEB_RUN = [("FA07", SPEED_30HZ), ("FA06", RUN_WORD)]
WEB_STOP = [("FA06", STOP_WORD)]


def class1(ctx, consumed, produced, produced_size, data):
    """An exclusive owner of `consumed` (-> `produced`, `produced_size` bytes) in run mode: the answer is the
    Forward_Open's status."""
    ep = ctx.endpoint
    triad = Triad(0x0D00 + ctx.serial())
    t_o_id = 0x1D000000 + triad.serial
    path = io_path(consumed, produced)
    request = forward_open(triad, path, RPI, net_params(len(H(data)) + 6), RPI, net_params(produced_size + 2),
                           t_o_id=t_o_id, multiplier=2)
    mr, raw, _ = open_connection(ctx.client, request)
    if mr.general != 0:
        return f"{mr.general:02X} ext " + " ".join(f"{w:04X}" for w in mr.extended)
    ctx.extra.append((triad, path, ep.add(IoConnection(decode_open_success(mr.data)["o_t_id"], t_o_id, RPI,
                                                         H(data), name=f"row {consumed}"))))
    return "00"


def basic_speed(ctx):
    """20 carries no NetCtrl/NetRef: FA06's priority bits come from 0x29 attribute 5 and 0x2A attribute 4,
    which every state leaves at 1 (the owner 21's `60`/`61` and the Sets before; with the factory cmod = 1
    the drive would ignore 20's run bit otherwise). Checked, so that the row's effect does not depend on
    history nobody sees."""
    for class_id, attribute in ((0x29, 5), (0x2A, 4)):
        reply = ctx.client.cip(mr_request(GET_ATTRIBUTE_SINGLE, epath(class_id, 1, attribute)))
        if reply.general != 0 or reply.data != b"\x01":
            fail(f"20 row: {class_id:#x} attribute {attribute} is {reply}, not 1")
    return class1(ctx, 20, 70, 4, "01 00 84 03")
def H(text):
    return bytes.fromhex(text)


# path name -> (what is sent, function)
PATHS = {
    "unconnected 0x29/0x2A run": ("Set NetCtrl=1, NetRef=1, SpeedRef=900 rpm, Run1=1", lambda c: unconnected(c, CIP_RUN)),
    "unconnected 0x29 stop": ("Set Run1=0", lambda c: unconnected(c, CIP_STOP)),
    "unconnected 0x65 run": ("Set FA07=0BB8h, FA06=C400h", lambda c: unconnected(c, PARAM_RUN)),
    "unconnected 0x65 stop": ("Set FA06=8000h", lambda c: unconnected(c, PARAM_STOP)),
    "unconnected 0x64 run": ("Set 7A07h (FA07)=0BB8h, 7A06h (FA06)=C400h", lambda c: unconnected(c, PARAM64_RUN)),
    "unconnected 0x64 stop": ("Set 7A06h (FA06)=8000h", lambda c: unconnected(c, PARAM64_STOP)),
    "class 3 0x29/0x2A run": ("Forward_Open, the 4 Sets, Forward_Close", lambda c: class3(c, CIP_RUN)),
    "web API run": ("POST FA07=0BB8h, FA06=C400h", lambda c: c.web.write(WEB_RUN)),
    "web API stop": ("POST FA06=8000h", lambda c: c.web.write(WEB_STOP)),
    "class 1 21/71 run": ("Forward_Open, O->T 61 00 84 03 run mode", lambda c: class1(c, 21, 71, 4, "61 00 84 03")),
    "class 1 20/70 run": ("Forward_Open, O->T 01 00 84 03 run mode (NetCtrl = NetRef = 1)", basic_speed),
    "class 1 100/150 run": ("Forward_Open, O->T 00 C4 B8 0B run mode",
                            lambda c: class1(c, 100, 150, 4, "00 C4 B8 0B")),
    # c001 = 1 (FA06), c002 = 3 (FA07), c003-c006 = 0: the factory menus, so 102/105 command the drive.
    "class 1 102/152 run": ("Forward_Open, O->T 00 C4 B8 0B + 8 x 00 run mode (c001 = FA06, c002 = FA07)",
                            lambda c: class1(c, 102, 152, 12, "00 C4 B8 0B" + " 00" * 8)),
    "class 1 105/155 run": ("Forward_Open, O->T 00 00 03 00 00 00 (read cmod) 00 C4 B8 0B + 8 x 00 run mode",
                            lambda c: class1(c, 105, 155, 18, "00 00 03 00 00 00 00 C4 B8 0B" + " 00" * 8)),
}

# ---- the states ---------------------------------------------------------------------------------------------

STATES = ["no loss", "c100 delay running", "c101=0 in force", "c101=0 in force (timeout)", "c101=1 (continue)",
          "c101=2 in force", "c101=2 in force (timeout)", "c101=3 in force", "c101=4 in force (err8)",
          "c101=5 in force", "owner idle", "another owner runs"]
# The loss cause is the owner's Forward_Close, or its timeout (it stops sending O->T: RPI x 4 x 2^2 = 320 ms)
# in the states marked so; the proxy acts the same for both (docs/drive-control.md). "c101=2 in force
# (timeout)" follows its twin with no f899 between: its explicit FA06 writes come after the twin's 102/105
# connections closed (their scanner words must no longer reserve FA06/FA07).
TIMEOUT_STATES = {"c101=0 in force (timeout)", "c101=2 in force (timeout)"}

# The rule (docs/drive-control.md): what each path answers in each state, and what the drive shows after.
# Effects: "runs" (FA06 run bit, FA07 0BB8h, 30 Hz reached), "stops" (FA06 = 8000h or the run bits cleared,
# 0 Hz, held past two refreshes of the action), "none" (FA06, FA07, trip unchanged).
HELD = {"c100 delay running", "c101=0 in force", "c101=2 in force", "c101=3 in force", "c101=4 in force (err8)",
        "c101=5 in force"} | TIMEOUT_STATES
OWNED = {"owner idle", "another owner runs"}


def expect(path, state):
    run = path.endswith(" run")
    if path.startswith("class 1"):
        if state in OWNED:
            return "01 ext 0106", "none"  # Forward_Open refused: ownership conflict 0106h
        if state == "c101=4 in force (err8)":
            # The owner restores the network; its priorities and speed reach FA06/FA07, the run is dropped
            # while err8 stays (f899 or a power cycle); 71 shows Faulted. I/O data has no per-packet answer.
            return "00", "set, no run"
        return "00", "runs"
    if path.startswith("class 3"):
        if state in OWNED:
            return "10 10 10 10", "none"
        if state == "c101=4 in force (err8)":
            # Restored by the open; NetCtrl, NetRef, SpeedRef take effect (FA06 C000h, FA07 0BB8h), Run1 into
            # the tripped drive (err8 stays until f899 or a power cycle): 0x10.
            return "00 00 00 10", "set, no run"
        return "00 00 00 00", "runs"
    if state in OWNED:  # the owner's connection holds FA06/FA07: stops included (seed §9.1, exclusive owner)
        if path.startswith("web"):
            return ", ".join(["409 reserved-for-scanner"] * (2 if run else 1)), "none"
        return ("10 10 10 10" if "0x29" in path and run else "10 10" if run else "10"), "none"
    if run and state in HELD:
        if path.startswith("web"):
            return "409 network-lost, 409 network-lost", "none"
        return ("10 10 10 10" if "0x29" in path else "10 10"), "none"
    if path.startswith("web"):
        return ", ".join(["200"] * (2 if run else 1)), "runs" if run else "stops"
    if run:
        return ("00 00 00 00" if "0x29" in path else "00 00"), "runs"
    return "00", "stops"


# The other class 1 command outputs only where their answer can differ from 21's: no loss (taken), one loss
# state (the open restores the network), and while the owner 21 is open, idle or running (from our own
# address: one owner of the drive command, 0x0106).
CLASS1_OTHERS = ("class 1 20", "class 1 100", "class 1 102", "class 1 105")
# 0x64 reaches FA06/FA07 by the same register write as 0x65 (only the instance numbering differs): no loss,
# the c101=2 loss by both causes, and another owner running.
PARAM64_STATES = {"no loss", "c101=2 in force", "c101=2 in force (timeout)", "another owner runs"}
ROWS = [(path, state) for state in STATES for path in PATHS
        if not (path.startswith(CLASS1_OTHERS) and state not in {"no loss", "c101=2 in force"} | OWNED)
        and not ("0x64" in path and state not in PARAM64_STATES)]


# ---- running a row ------------------------------------------------------------------------------------------

class Context:
    def __init__(self, client, endpoint, web):
        self.client, self.endpoint, self.web = client, endpoint, web
        self.owner = None
        self.extra = []
        self.count = 0
        self.loaded = None  # (c100, c101, c102) of the last f899
        self.reloads = 0

    def serial(self):
        self.count += 1
        return self.count


def reload_config(ctx, c100, c101, c102):
    ctx.loaded = (c100, c101, c102)
    ctx.reloads += 1
    for name, value in (("c100", c100), ("c101", c101), ("c102", c102)):
        sim.set(name, value)
    # f899 is refused while the drive runs: stopped first through the explicit Run1 = 0 (a stop is taken in
    # every state once no owner is open).
    if inverter()["hz"] != 0.0 or inverter()["fa06"] & RUN:
        ctx.client.cip(set_request(0x29, 1, 3, b"\x00"))
        wait_until("drive stopped before f899", lambda: inverter()["hz"] == 0.0, 5.0)
    # f899 is a card reset: it ends an explicit command's hold of FA06/FA07 (docs/drive-control.md), so
    # every state starts with nobody holding them.
    loads = stat("proxy.config_loads")
    reply = ctx.client.cip(set_request(0x65, 0x0899, 3, u16(1)))
    if reply.general != 0:
        fail(f"f899 = 1: {reply}")
    wait_until("configuration reloaded", lambda: stat("proxy.config_loads") > loads, 5.0, 0.05)
    wait_until("inverter reset", lambda: sim.status()["trip"] == 0 and sim.status()["state"] == "stopped", 3.0)


def start_afresh(ctx):
    """What f899 gives a state (the drive stopped, no loss, nobody holding FA06/FA07) without its reset
    silence and configuration read: a class 3 connection is opened first (its open restores a loss, and
    while it is open an owner's Forward_Close is a loss restored at once, before c100 can run out); an
    explicit Run1 = 0 stops the drive; an exclusive owner with a stop command takes FA06/FA07 over from any
    explicit hold and gives them back at its close; then the class 3 connection is closed (no loss)."""
    triad, _ = open_class3(ctx)
    wait_until("network restored by the class 3 open", lambda: stat("cip.lost") == 0, 2.0)
    if inverter()["hz"] != 0.0 or inverter()["fa06"] & RUN:
        reply = ctx.client.cip(set_request(0x29, 1, 3, b"\x00"))
        if reply.general != 0:
            fail(f"Run1 = 0 before the next state: {reply}")
        wait_until("drive stopped", lambda: inverter()["hz"] == 0.0 and not inverter()["fa06"] & RUN, 5.0)
    open_owner(ctx, "60 00 00 00")
    close_all(ctx)
    open_connection(ctx.client, forward_close(triad, ROUTER_PATH))
    wait_until("no loss after the owner's close", lambda: stat("cip.lost") == 0, 2.0)
    if stat("proxy.loss_action_active") != 0 or inverter()["trip"] != 0:
        fail("start afresh: a loss action or a trip left")


def close_all(ctx):
    for triad, path, conn in ctx.extra + ([ctx.owner] if ctx.owner else []):
        ctx.endpoint.stop_sending(conn)
        open_connection(ctx.client, forward_close(triad, path))
        ctx.endpoint.remove(conn)
    ctx.extra, ctx.owner = [], None


def open_owner(ctx, data="61 00 08 07"):
    """Exclusive owner 21/71 in run mode: run forward at 60 Hz (1800 rpm) unless `data` says otherwise."""
    triad = Triad(0x0E00 + ctx.serial())
    t_o_id = 0x1E000000 + triad.serial
    mr, raw, _ = open_connection(ctx.client, forward_open(triad, io_path(21, 71), RPI, net_params(10), RPI,
                                                          net_params(6), t_o_id=t_o_id, multiplier=2))
    if mr.general != 0:
        fail(f"owner Forward_Open refused: {hexs(raw)}")
    conn = ctx.endpoint.add(IoConnection(decode_open_success(mr.data)["o_t_id"], t_o_id, RPI, H(data), name="owner"))
    ctx.owner = (triad, io_path(21, 71), conn)
    if data == "61 00 08 07":
        wait_until("owner runs the drive at 60 Hz", lambda: inverter()["hz"] == 60.0, 3.0)
    else:
        wait_until("owner's command in the inverter", lambda: not inverter()["fa06"] & RUN, 3.0)
        time.sleep(0.3)  # 15 RPIs: its data consumed, so the connection (not an explicit hold) owns FA06


def enter(ctx, state):
    """Puts the card and the inverter into `state` from anything: f899 = 1 when c100-c102 change or the
    drive tripped (err8 stays until f899), else start_afresh."""
    close_all(ctx)
    c101 = {"c101=0 in force": 0, "c101=0 in force (timeout)": 0, "c101=1 (continue)": 1, "c101=3 in force": 3, "c101=4 in force (err8)": 4,
            "c101=5 in force": 5}.get(state, 2)
    wanted = (50 if state == "c100 delay running" else 0, c101, 3 if c101 == 5 else 0)
    if wanted != ctx.loaded or inverter()["trip"] != 0:
        reload_config(ctx, *wanted)
    else:
        start_afresh(ctx)
    actions = stat("proxy.loss_actions")
    if state == "no loss":
        return
    open_owner(ctx)
    if state == "another owner runs":
        return
    if state == "owner idle":
        ctx.endpoint.set(ctx.owner[2], run=False)
    elif state in TIMEOUT_STATES:
        triad, path, conn = ctx.owner
        timeouts = stat("cip.loss_timeouts")
        ctx.endpoint.stop_sending(conn)
        wait_until("owner timed out", lambda: stat("cip.loss_timeouts") > timeouts and stat("cip.lost") == 1, 2.0)
        ctx.endpoint.remove(conn)
        ctx.owner = None
    else:
        triad, path, conn = ctx.owner
        ctx.endpoint.stop_sending(conn)
        open_connection(ctx.client, forward_close(triad, path))
        ctx.endpoint.remove(conn)
        ctx.owner = None
    if state == "c100 delay running":
        wait_until("loss reported", lambda: stat("cip.lost") == 1, 2.0)
        return
    if state == "c101=1 (continue)":
        wait_until("loss reported", lambda: stat("cip.lost") == 1 and stat("proxy.loss_actions") > actions, 2.0)
        return
    wait_until("loss action in force", lambda: stat("proxy.loss_action_active") == 1, 3.0)
    # The action's FA06 (or err8) has reached the inverter and its ramp is over (dec 0.5 s): the "none"
    # check compares a settled drive.
    wait_until("loss action in the inverter", lambda: inverter()["fa06"] != 0xC400 or inverter()["trip"] != 0, 2.0)
    settle()


def main():
    results = []
    started = time.monotonic()
    with Client(CARD) as client, IoEndpoint(CARD) as ep:
        if client.register_session().status != 0:
            fail("RegisterSession")
        web = Web()
        web.login()
        ctx = Context(client, ep, web)
        for state in STATES:
            fresh = False
            for path, row_state in ROWS:
                if row_state != state:
                    continue
                want_answer, want_effect = expect(path, state)
                if not fresh:
                    enter(ctx, state)
                before = inverter()
                answer = PATHS[path][1](ctx)
                got_effect = effect(before, want_effect, 0xC000)
                c536, loss = stat("proxy.c536"), stat("proxy.loss_action_active")
                results.append((path, state, answer, got_effect, c536, loss))
                print(f"   {state:24} {path:28} answer {answer:38} effect {got_effect:6} c536={c536} "
                      f"loss_action={loss}", flush=True)
                if (answer, got_effect) != (want_answer, want_effect):
                    fail(f"{state} / {path}: answer {answer!r} effect {got_effect!r}, "
                         f"expected {want_answer!r} {want_effect!r}")
                if c536 != 0:
                    fail(f"{state} / {path}: c536 = {c536} (a CIP loss has no c536 code)")
                # A refused row left the state as it was; a success changed it (a run restores or takes over).
                fresh = want_effect == "none"
        close_all(ctx)
    print(f"ok: drive control matrix: {len(results)} rows, {ctx.reloads} f899 reloads, in "
          f"{time.monotonic() - started:.0f} s; every success "
          f"row showed its effect, every error row none")
    write_markdown(results)


def write_markdown(results):
    lines = ["# Drive control matrix (generated)", "",
             "Generated by `integration.drive_control_matrix` (tests/integration/drive_control_matrix.py) from the rows",
             "it ran against the host card (c500 = 1) and the simulated inverter; the test fails when this file",
             "differs from its run (`DRIVE_MATRIX_UPDATE=1` rewrites it). The rule: docs/drive-control.md.", "",
             "Answer: the CIP general status of each request in order (hex), the HTTP status of each write, or",
             "the class 1 Forward_Open's status. Effect in the inverter: runs = FA06 run bit, FA07 = 0BB8h, 30 Hz;",
             "stops = run bit clear and 0 Hz, still after two refreshes of the loss action; none = FA06, FA07 and",
             "the trip code unchanged; set, no run = FA06 C000h, FA07 0BB8h, 0 Hz, err8 (27) stays. c536 stays 0 in every row (a CIP loss has no c536 code).",
             "The loss is the owner 21's Forward_Close, or its timeout (it stops sending O->T) where the state says",
             "\"(timeout)\"; 0x64 instances 7A06h/7A07h are FA06/FA07.", "",
             "| State | Path | Request | Answer | Effect | Loss action after |",
             "| --- | --- | --- | --- | --- | --- |"]
    for path, state, answer, got_effect, c536, loss in results:
        lines.append(f"| {state} | {path} | {PATHS[path][0]} | {answer} | {got_effect} | {'in force' if loss else '-'} |")
    text = "\n".join(lines) + "\n"
    print(text)
    out = os.environ["MATRIX_OUT"]
    with open(out, "w") as f:
        f.write(text)


main()
