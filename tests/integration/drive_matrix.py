"""What the two drive control matrices share (drive_control_matrix.py: the EtherNet/IP card,
drive_control_matrix_modbus.py: the Modbus card; docs/drive-control.md): the simulated inverter and the
card's stats through the control socket, bounded waits, and the effect check of a row."""
import os
import sys
import time

from eip_io import SimControl

sim = SimControl(os.environ["CARD_CONTROL"])
RUN = 0x0400         # FA06 run bit
SPEED_30HZ = 0x0BB8  # FA07, 0.01 Hz


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    card = {k: v for k, v in sim.stats().items()
            if k.startswith(("proxy.loss", "proxy.c536", "cip.lost", "modbus.loss", "modbus.lost"))}
    print(f"      inverter {sim.status()}; card {card}", file=sys.stderr)
    sys.exit(1)


def stat(name):
    return int(sim.stats()[name])


def inverter():
    s = sim.status()
    word = lambda v: int(v, 16) if isinstance(v, str) else int(v)  # "0xC400" (FA06), a number (FA07)
    return {"fa06": word(s["fa06"]), "fa07": word(s["fa07"]), "hz": s["output_hz"], "trip": s["trip"]}


def wait_until(what, predicate, limit, step=0.02):
    deadline = time.monotonic() + limit
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            fail(f"{what}: not within {limit} s")
        time.sleep(step)


def settle():
    """A loss action's ramp is over: the "none" check compares a drive that no longer moves."""
    last = None
    deadline = time.monotonic() + 3.0
    while time.monotonic() < deadline:
        s = inverter()
        now = (s["fa06"], s["fa07"], s["hz"], s["trip"])
        if now == last:
            return
        last = now
        time.sleep(0.15)
    fail(f"drive does not settle: {inverter()}")


def effect(before, want, set_fa06):
    """Checks the effect `want` in the inverter and returns what was seen: "runs" (FA06 run bit, FA07 0BB8h,
    30 Hz within 3 s), "stops" (run bit clear and 0 Hz within 3 s, still after 1.2 s: two refreshes of a
    loss action), "none" (FA06, FA07 and the trip code unchanged for 0.6 s), "set, no run" (FA06 `set_fa06`,
    FA07 0BB8h, 0 Hz, err8 (27) stays); anything else is described."""
    def runs(s):
        return s["fa06"] & RUN and s["fa07"] == SPEED_30HZ and s["hz"] == 30.0 and s["trip"] == 0

    def stopped(s):
        return not s["fa06"] & RUN and s["hz"] == 0.0

    if want == "set, no run":
        time.sleep(0.6)
        s = inverter()
        ok = s["fa06"] == set_fa06 and s["fa07"] == SPEED_30HZ and s["hz"] == 0.0 and s["trip"] == 27
        return want if ok else f"not reached: {s}"
    if want == "none":
        end = time.monotonic() + 0.6
        while time.monotonic() < end:
            s = inverter()
            if (s["fa06"], s["fa07"], s["trip"]) != (before["fa06"], before["fa07"], before["trip"]):
                return f"changed to {s}"
            time.sleep(0.02)
        return "none"
    end = time.monotonic() + 3.0
    while time.monotonic() < end:
        s = inverter()
        if want == "runs" and runs(s):
            return "runs"
        if want == "stops" and stopped(s):
            time.sleep(1.2)
            s = inverter()
            return "stops" if stopped(s) else f"restarted: {s}"
        time.sleep(0.02)
    return f"not reached: {inverter()}"
