"""The Modbus card's part of the command/effect matrix of issue 21 (docs/drive-control.md): Modbus unit 0
writes of FA06/FA07 (FC 06, FC 16) and IO scanning on unit 255 (FC 23) in every state of IO scanning's loss
(none, c523 expired and c100 running, c101 = 0-5 in force, another client while the scanner runs the drive),
each row's exact answer PDU and its effect in the simulated inverter (FA06/FA07, output frequency, trip),
c536 and the loss action. A success row must show its effect, an error row none. The markdown of
docs/drive-control-matrix-modbus.md is printed from the same data and compared with the committed file.

Two scanner configurations (c604 = 1, c523 = 0.5 s, c600-c603 = 0.0.0.0):
- "scanner owns FA06/FA07" (the factory c001 = 1, c002 = 3): the scanner's words are FA06/FA07, so unit 0
  writes of them are 02 (seed 000 §9.1, "even if the IO Scanner is not sending") and FC 23 is the command
  path (its words restore the loss: counted communication).
- "no scanner command words" (c001 = c002 = 0): the scanner only supervises; unit 0 writes FA06/FA07 and
  meet the loss rule: a run or speed write during a loss that holds the drive is 04, a stop is taken.

Run by drive_control_matrix_modbus_tap.sh (card c500 = 0, acc = dec = 0.5 s, sr3 = 25 Hz)."""
import os
import socket
import struct
import sys
import threading
import time

from drive_matrix import RUN, SPEED_30HZ, effect, fail, inverter, settle, sim, stat, wait_until

CARD = os.environ["CARD_IP"]
RUN_WORD = 0xC400    # priorities (command, frequency) + run
STOP_WORD = 0x8000   # command priority, no run: distinct from every c101 action's FA06
FA06, FA07, F899 = 0xFA06, 0xFA07, 0x0899
LOSS_LOST = 3        # modbus.loss_state: lost (docs/modbus.md, unit 251 register 49)


# ---- Modbus on a plain socket: exact PDUs ----------------------------------------------------------------

class Link:
    def __init__(self):
        self.sock = socket.create_connection((CARD, 502), timeout=5)
        self.transaction = 0

    def request(self, unit, pdu):
        self.transaction = (self.transaction + 1) & 0xFFFF
        self.sock.sendall(struct.pack(">HHHB", self.transaction, 0, len(pdu) + 1, unit) + pdu)
        header = self._read(7)
        tid, proto, length, answer_unit = struct.unpack(">HHHB", header)
        if (tid, proto, answer_unit) != (self.transaction, 0, unit):
            fail(f"MBAP echo: {header.hex()}")
        return self._read(length - 1)

    def _read(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            if not chunk:
                fail("Modbus connection closed")
            data += chunk
        return data

    def close(self):
        self.sock.close()


def fc06(number, value):
    return struct.pack(">BHH", 0x06, number, value)


def fc16(number, values):
    return struct.pack(">BHHB", 0x10, number, len(values), 2 * len(values)) + b"".join(
        struct.pack(">H", v) for v in values)


def fc23(words):
    """Reads input word 0 (reserved: reads 0, so the answer is exact) and writes output words 0..n-1."""
    return struct.pack(">BHHHHB", 0x17, 0, 1, 0, len(words), 2 * len(words)) + b"".join(
        struct.pack(">H", w) for w in words)


def hexs(data):
    return " ".join(f"{b:02X}" for b in data)


class Scanner(threading.Thread):
    """The IO scanner of a PLC: FC 23 on unit 255 every 100 ms while `active` (c523 = 0.5 s)."""

    def __init__(self):
        super().__init__(daemon=True)
        self.link = Link()
        self.lock = threading.Lock()
        self.words = [0, 0, 0]
        self.active = False
        self.halt = False

    def exchange(self, words):
        """New words, sent at once; the answer of this first request is returned, the cycle goes on."""
        with self.lock:
            self.words = words
            self.active = True
            return self.link.request(255, fc23(words))

    def silence(self):
        with self.lock:
            self.active = False

    def run(self):
        deadline = time.monotonic() + 900  # bounded whatever happens
        while not self.halt and time.monotonic() < deadline:
            with self.lock:
                if self.active:
                    answer = self.link.request(255, fc23(self.words))
                    if answer != bytes.fromhex("17 02 00 00"):
                        print(f"FAIL: scanner answer {hexs(answer)}", file=sys.stderr)
                        os._exit(1)
            time.sleep(0.1)
        self.link.close()


# ---- paths, configurations, states -----------------------------------------------------------------------

OWNS = "scanner owns FA06/FA07"
NO_WORDS = "no scanner command words"
CONFIGS = {OWNS: (1, 3), NO_WORDS: (0, 0)}  # c001, c002

PATHS = {
    "unit 0 FC06 run": ("FC06 FA07=0BB8h, FC06 FA06=C400h",
                        lambda c: [c.client.request(0, fc06(FA07, SPEED_30HZ)), c.client.request(0, fc06(FA06, RUN_WORD))]),
    "unit 0 FC16 run": ("FC16 FA06..FA07 = C400h, 0BB8h",
                        lambda c: [c.client.request(0, fc16(FA06, [RUN_WORD, SPEED_30HZ]))]),
    "unit 0 FC06 stop": ("FC06 FA06=8000h", lambda c: [c.client.request(0, fc06(FA06, STOP_WORD))]),
    "unit 255 FC23 run": ("FC23 words 1-2 = C400h, 0BB8h", lambda c: [c.scanner.exchange([0, RUN_WORD, SPEED_30HZ])]),
    "unit 255 FC23 stop": ("FC23 words 1-2 = 8000h, 0BB8h", lambda c: [c.scanner.exchange([0, STOP_WORD, SPEED_30HZ])]),
}

# In the order that needs the fewest f899 reloads (the first three share c100 = 0, c101 = 2).
STATES = ["no loss", "scanner runs, another client writes", "c101=2 in force", "c100 delay running",
          "c101=0 in force", "c101=1 (continue)", "c101=3 in force", "c101=4 in force (err8)", "c101=5 in force"]
HELD = {"c100 delay running", "c101=0 in force", "c101=2 in force", "c101=3 in force", "c101=4 in force (err8)",
        "c101=5 in force"}
LOSS = HELD | {"c101=1 (continue)"}


def expect(config, path, state):
    """(answer PDUs, effect, c536 after) by the rule of docs/drive-control.md."""
    run = path.endswith(" run")
    c536 = 1 if state in LOSS else 0
    if path.startswith("unit 255"):
        # Counted communication: restores the loss first (c536 back to 0), then the words reach FA06/FA07.
        if state == "c101=4 in force (err8)" and run:
            return "17 02 00 00", "set, no run", 0  # err8 stays until f899 or a power cycle
        return "17 02 00 00", "runs" if run else "stops", 0
    if config == OWNS:  # seed 000 §9.1: the scanner's targets refuse other writers, sending or not
        return ("86 02, 86 02" if "FC06 run" in path else "90 02" if "FC16" in path else "86 02"), "none", c536
    if run and state in HELD:
        return ("86 04, 86 04" if "FC06" in path else "90 04"), "none", c536
    if "FC06 run" in path:
        return "06 FA 07 0B B8, 06 FA 06 C4 00", "runs", c536
    if "FC16" in path:
        return "10 FA 06 00 02", "runs", c536
    return "06 FA 06 80 00", "stops", c536


ROWS = []
for _config in CONFIGS:
    for _state in STATES:
        if _config == NO_WORDS and _state.startswith("scanner runs"):
            continue  # without command words the scanner does not run the drive
        # Refused rows first: they leave the state as it was, so the next row needs no new entry.
        paths = ["unit 0 FC06 run", "unit 0 FC16 run", "unit 0 FC06 stop"]
        if _config == OWNS:
            paths += ["unit 255 FC23 stop", "unit 255 FC23 run"] if _state == "no loss" else ["unit 255 FC23 run"]
        ROWS += [(_config, p, _state) for p in paths]


class Context:
    def __init__(self):
        self.client = Link()     # an engineering tool or second PLC: its own TCP connection
        self.scanner = Scanner()
        self.loaded = None       # (c001, c002, c100, c101) in force
        self.reloads = 0


def stop_drive(ctx):
    """Restores any loss (the scanner's counted communication) and stops the drive, by the scanner's words
    or by unit 0, as the configuration in force allows."""
    config = NO_WORDS if ctx.loaded is not None and ctx.loaded[:2] == CONFIGS[NO_WORDS] else OWNS
    if config == OWNS:
        ctx.scanner.exchange([0, STOP_WORD, SPEED_30HZ])
    else:
        ctx.scanner.exchange([0, 0, 0])
        wait_until("loss restored", lambda: stat("modbus.loss_state") != LOSS_LOST, 2.0)
        if inverter()["fa06"] & RUN or inverter()["hz"] != 0.0:
            answer = ctx.client.request(0, fc06(FA06, STOP_WORD))
            if answer != fc06(FA06, STOP_WORD):
                fail(f"stop before the next state: {hexs(answer)}")
    wait_until("drive stopped", lambda: inverter()["hz"] == 0.0 and not inverter()["fa06"] & RUN, 5.0)
    if config == OWNS:
        wait_until("the scanner's stop words in the inverter",
                   lambda: (inverter()["fa06"], inverter()["fa07"]) == (STOP_WORD, SPEED_30HZ), 2.0)


def reload_config(ctx, wanted):
    c001, c002, c100, c101 = wanted
    for name, value in (("c001", c001), ("c002", c002), ("c100", c100), ("c101", c101),
                        ("c102", 3 if c101 == 5 else 0)):
        sim.set(name, value)
    loads = stat("proxy.config_loads")
    answer = ctx.client.request(0, fc06(F899, 1))
    if answer != fc06(F899, 1):
        fail(f"f899 = 1: {hexs(answer)}")
    wait_until("configuration reloaded", lambda: stat("proxy.config_loads") > loads, 5.0, 0.05)
    wait_until("inverter reset", lambda: sim.status()["trip"] == 0 and sim.status()["state"] == "stopped", 3.0)
    ctx.loaded = wanted
    ctx.reloads += 1


def enter(ctx, config, state):
    """Puts the card and the inverter into `state`; a reload (f899) only when c001/c002/c100/c101 change
    or the drive tripped (err8 stays until f899)."""
    stop_drive(ctx)
    c101 = {"c101=0 in force": 0, "c101=1 (continue)": 1, "c101=3 in force": 3, "c101=4 in force (err8)": 4,
            "c101=5 in force": 5}.get(state, 2)
    wanted = CONFIGS[config] + (50 if state == "c100 delay running" else 0, c101)
    if wanted != ctx.loaded or inverter()["trip"] != 0:
        reload_config(ctx, wanted)
        if config == OWNS:
            # The reset cleared FA06/FA07 in the inverter; the scanner's words come back with its next
            # exchange after the load. Before that, a row's "before" would see them arrive as its effect.
            wait_until("the scanner's stop words in the inverter after the reload",
                       lambda: (inverter()["fa06"], inverter()["fa07"]) == (STOP_WORD, SPEED_30HZ), 2.0)
    if state == "no loss":
        return
    # The drive runs at 60 Hz: by the scanner's words, or by unit 0 when the scanner has none.
    if config == OWNS:
        ctx.scanner.exchange([0, RUN_WORD, 6000])
    else:
        answer = ctx.client.request(0, fc16(FA06, [RUN_WORD, 6000]))
        if answer != bytes.fromhex("10 FA 06 00 02"):
            fail(f"unit 0 run before the loss: {hexs(answer)}")
    wait_until("drive at 60 Hz", lambda: inverter()["hz"] == 60.0, 3.0)
    if state.startswith("scanner runs"):
        return
    actions = stat("proxy.loss_actions")
    ctx.scanner.silence()
    wait_until("loss reported (c523)", lambda: stat("modbus.loss_state") == LOSS_LOST, 2.0)
    if state == "c100 delay running":
        return  # c100 = 5 s: the refused rows and the first success fit into it
    if state == "c101=1 (continue)":
        wait_until("loss action decided", lambda: stat("proxy.loss_actions") > actions, 2.0)
        return
    wait_until("loss action in force", lambda: stat("proxy.loss_action_active") == 1, 2.0)
    settle()


def main():
    results = []
    started = time.monotonic()
    ctx = Context()
    ctx.scanner.start()
    sim.command("terminal ST on")
    fresh = False
    current = None
    for config, path, state in ROWS:
        if (config, state) != current:
            fresh = False
            current = (config, state)
        want_answer, want_effect, want_c536 = expect(config, path, state)
        if not fresh:
            enter(ctx, config, state)
        before = inverter()
        answer = ", ".join(hexs(a) for a in PATHS[path][1](ctx))
        got_effect = effect(before, want_effect, RUN_WORD)
        c536, loss = stat("proxy.c536"), stat("proxy.loss_action_active")
        results.append((config, path, state, answer, got_effect, c536, loss))
        print(f"   {config:25} {state:34} {path:19} answer {answer:30} effect {got_effect:11} c536={c536} "
              f"loss_action={loss}", flush=True)
        if (answer, got_effect, c536) != (want_answer, want_effect, want_c536):
            fail(f"{config} / {state} / {path}: answer {answer!r} effect {got_effect!r} c536 {c536}, "
                 f"expected {want_answer!r} {want_effect!r} {want_c536}")
        fresh = want_effect == "none"
    stop_drive(ctx)
    ctx.scanner.halt = True
    ctx.scanner.join(5)
    ctx.client.close()
    print(f"ok: drive control matrix (Modbus): {len(results)} rows, {ctx.reloads} f899 reloads, in "
          f"{time.monotonic() - started:.0f} s; every "
          f"success row showed its effect, every error row none")
    write_markdown(results)


def write_markdown(results):
    lines = ["# Drive control matrix: the Modbus card (generated)", "",
             "Generated by `integration.drive_control_matrix_modbus` (tests/integration/drive_control_matrix_modbus.py)",
             "from the rows it ran against the host card (c500 = 0, c604 = 1, c523 = 0.5 s, c600-c603 = 0.0.0.0) and",
             "the simulated inverter; the test fails when this file differs from its run (`DRIVE_MATRIX_UPDATE=1`",
             "rewrites it). The rule: docs/drive-control.md; the EtherNet/IP card: docs/drive-control-matrix.md.", "",
             "Configurations: \"scanner owns FA06/FA07\" = c001 = 1, c002 = 3 (factory: IO scanning's output words",
             "1-2 are FA06/FA07); \"no scanner command words\" = c001 = c002 = 0 (the scanner only supervises).",
             "Loss states: the scanner ran the drive (or unit 0 did) at 60 Hz and went silent for c523; c100 = 5 s",
             "in the c100 row, 0 otherwise. Unit 0 writes come from a second TCP connection.", "",
             "Answer: each answer PDU (hex; 86/90 xx = FC06/FC16 exception xx, FC23 reads input word 0).",
             "Effect in the inverter: runs = FA06 run bit, FA07 = 0BB8h, 30 Hz; stops = run bit clear and 0 Hz, still",
             "after two refreshes of the loss action; none = FA06, FA07 and the trip code unchanged; set, no run =",
             "FA06 C400h, FA07 0BB8h, 0 Hz, err8 (27) stays. c536: read after the row (1 = IO scanning timeout).", "",
             "| Configuration | State | Path | Request | Answer | Effect | c536 | Loss action after |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for config, path, state, answer, got_effect, c536, loss in results:
        lines.append(f"| {config} | {state} | {path} | {PATHS[path][0]} | {answer} | {got_effect} | {c536} | "
                     f"{'in force' if loss else '-'} |")
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.environ["MATRIX_OUT"], "w") as f:
        f.write(text)


main()
