#!/usr/bin/python3
"""Modbus TCP server against python3-pymodbus (a real client), checked against the simulated inverter.

Run by modbus_loopback.sh with MODBUS_HOST, MODBUS_PORT and CARD_CONTROL set, the card started with
IO scanning on (c604 = 1), c523 = 0.5 s and c100 = 0.3 s. Covers: drive registers read and written
through unit 0-248 reach the inverter (seen with the control socket); the A-F skip of seed 000 §8.9 (5);
0x8000 for a number that does not exist; the exception matrix; unit 251; FC 43; IO scanning with FC 23;
each c101 loss action 0-5 with its reaction time inside [c523 + c100, c523 + c100 + 150 ms].
"""
import json
import os
import socket
import struct
import sys
import threading
import time

from pymodbus.client import ModbusTcpClient
from pymodbus.pdu import ExceptionResponse

# python3-pymodbus 3.0.0 (Debian 12): readwrite_registers takes unit=, the other calls slave=.

HOST = os.environ["MODBUS_HOST"]
PORT = int(os.environ["MODBUS_PORT"])
CONTROL = os.environ["CARD_CONTROL"]
LOSS_DELAY = 0.5 + 0.3          # c523 + c100
MARGIN = 0.15                   # one exchange cycle, the status poll and scheduling


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def ok(message):
    print("ok: " + message)


def control(command):
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(5)
        s.connect(CONTROL)
        s.sendall((command + "\n").encode())
        data = b""
        while not (data.endswith(b"ok\n") or b"\nerror" in data or data.startswith(b"error")):
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
    lines = data.decode().splitlines()
    if not lines or lines[-1] != "ok":
        fail(f"control '{command}': {lines}")
    return lines[:-1]


def sim_get(name):
    # "acc = 50 (0x0032)"
    return int(control("get " + name)[0].split("=")[1].split("(")[0])


def status():
    return json.loads(control("status")[0])


def expect(what, got, wanted):
    if got != wanted:
        fail(f"{what}: got {got!r}, expected {wanted!r}")


def exception_code(response):
    return response.exception_code if isinstance(response, ExceptionResponse) else None


def raw(client_socket, unit, pdu, transaction=0x1234):
    """Send one ADU on a plain socket and return the answer's PDU (exact bytes)."""
    client_socket.sendall(struct.pack(">HHHB", transaction, 0, len(pdu) + 1, unit) + pdu)
    header = b""
    while len(header) < 7:
        header += client_socket.recv(7 - len(header))
    tid, proto, length, answer_unit = struct.unpack(">HHHB", header)
    expect("echoed transaction id", tid, transaction)
    expect("echoed unit", answer_unit, unit)
    body = b""
    while len(body) < length - 1:
        body += client_socket.recv(length - 1 - len(body))
    return body


def wait_until(predicate, limit):
    start = time.monotonic()
    while time.monotonic() - start < limit:
        if predicate():
            return time.monotonic()
        time.sleep(0.01)
    return None


RUN = [0, 0xC400, 6000, 0, 0, 0, 0]    # FA06 run forward with both priorities, FA07 60.00 Hz
STOP = [0, 0xC000, 6000, 0, 0, 0, 0]


class Scanner(threading.Thread):
    """FC 23 on unit 255 every 50 ms while `active`: the IO scanner of a PLC."""

    def __init__(self):
        super().__init__(daemon=True)
        self.active = False
        self.words = RUN
        self.last_answer = 0.0
        self._halt = False

    def run(self):
        client = ModbusTcpClient(HOST, port=PORT, timeout=3)
        client.connect()
        deadline = time.monotonic() + 120            # bounded whatever happens
        while not self._halt and time.monotonic() < deadline:
            if self.active:
                client.readwrite_registers(read_address=0, read_count=7, write_address=0,
                                           write_registers=self.words, unit=255)
                self.last_answer = time.monotonic()
            time.sleep(0.05)
        client.close()

    def stop(self):
        self._halt = True
        self.join(5)


def main():
    client = ModbusTcpClient(HOST, port=PORT, timeout=3)
    if not client.connect():
        fail("connect")

    # --- Drive registers (unit = 0-248, address = communication number) ---
    r = client.read_holding_registers(0x0009, 2, slave=1)
    expect("acc, dec from 0x0009 (A-F skipped)", r.registers, [sim_get("acc"), sim_get("dec")])
    r = client.write_register(0x0009, 50, slave=0)
    expect("FC 06 acc", exception_code(r), None)
    expect("acc in the inverter", sim_get("acc"), 50)
    r = client.write_registers(0x0009, [70, 80], slave=0)
    expect("FC 16 acc, dec", exception_code(r), None)
    expect("acc, dec in the inverter", (sim_get("acc"), sim_get("dec")), (70, 80))
    r = client.read_holding_registers(0x0001, 1, slave=0)
    expect("non-existent 0001 reads 0x8000", r.registers, [0x8000])
    ok("drive registers reach the inverter; A-F skip; 0x8000")

    # --- Exceptions ---
    expect("FC 06 acc out of range -> 03", exception_code(client.write_register(0x0009, 0, slave=0)), 3)
    expect("FC 06 monitor FD00 -> 02", exception_code(client.write_register(0xFD00, 1, slave=0)), 2)
    expect("FC 03 64 registers -> 03", exception_code(client.read_holding_registers(0x0009, 64, slave=0)), 3)
    expect("FC 01 -> 01", exception_code(client.read_coils(0, 1, slave=0)), 1)
    expect("FC 04 -> 01", exception_code(client.read_input_registers(0, 1, slave=0)), 1)
    expect("FC 06 on unit 251 -> 01", exception_code(client.write_register(0, 1, slave=251)), 1)
    ok("exception matrix (01/02/03) as docs/modbus.md lists it")

    # --- Exact bytes: FC 43 of unit 251, FC 03 of unit 251 register 0 ---
    with socket.create_connection((HOST, PORT), timeout=3) as s:
        answer = raw(s, 251, bytes([0x2B, 0x0E, 0x01, 0x00]))
        expect("FC 43 unit 251 basic", answer.hex(),
               bytes([0x2B, 0x0E, 0x01, 0x02, 0x00, 0x00, 0x03, 0x00, 0x07]).hex() + b"TOSHIBA".hex() +
               "0107" + b"IPE002Z".hex() + "0204" + b"0106".hex())
        answer = raw(s, 248, bytes([0x2B, 0x0E, 0x01, 0x00]))
        expect("FC 43 unit 248 vendor", answer[7:16], bytes([0x00, 0x07]) + b"TOSHIBA")
        expect("FC 43 unit 248 product code", answer[16:31], bytes([0x01, 0x0D]) + b"VFMB1S-2007PL")
        expect("unknown function 0x41 -> 01", raw(s, 0, bytes([0x41])), bytes([0xC1, 0x01]))
    ok("FC 43 answers of §8.8 and raw exception bytes")

    # --- IO scanning (unit 255, FC 23): scanner words 1-6 per c001-c006 / c021-c026 ---
    control("terminal ST on")
    r = client.readwrite_registers(read_address=0, read_count=7, write_address=0,
                                   write_registers=[0, 0xC400, 6000, 0, 0, 0, 0], unit=255)
    expect("FC 23", exception_code(r), None)
    # Keep scanning (c523 = 0.5 s) until the drive runs at 60 Hz.
    words = None
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        r = client.readwrite_registers(read_address=0, read_count=7, write_address=0,
                                       write_registers=[0, 0xC400, 6000, 0, 0, 0, 0], unit=255)
        words = r.registers
        if words[1] == 0x6400 and words[2] == 6000:
            break
        time.sleep(0.05)
    expect("monitor words FD01, FD00 at speed", words[1:3], [0x6400, 6000])
    expect("FA06/FA07 in the inverter", (status()["fa06"], status()["fa07"]), ("0xC400", 6000))
    expect("FC 06 to the scanner's FA07 on unit 0 -> 02",
           exception_code(client.write_register(0xFA07, 100, slave=0)), 2)
    ok("IO scanning drives the inverter; its registers refuse other writers")

    # --- Loss actions: c101 0-5, reaction inside [c523 + c100, + margin] ---
    # A scanner thread keeps IO scanning alive (every 50 ms, its own connection) except while a loss
    # is measured; f899 = 1 makes the card read c101/c102 again (and clears an err8 trip).
    scanner = Scanner()
    scanner.start()
    expected_fa06 = {0: "0x0000", 2: "0xC000", 3: "0x8800", 5: "0x8403"}
    for action in (0, 1, 2, 3, 4, 5):
        scanner.words = STOP                         # f899 is refused while the drive runs
        scanner.active = True
        if wait_until(lambda: status()["state"] != "running", 10) is None:
            fail(f"c101={action}: the drive does not stop: {status()}")
        control(f"set c101 {action}")
        control("set c102 3")
        expect("f899 = 1", exception_code(client.write_register(0x0899, 1, slave=0)), None)
        time.sleep(2.5)                              # reset silence + configuration read
        expect("c101 read again", [l for l in control("config") if l.startswith("c101=")], [f"c101={action}"])
        control("terminal ST on")
        scanner.words = RUN
        if wait_until(lambda: status()["state"] == "running", 10) is None:
            fail(f"c101={action}: the drive does not run: {status()}")
        scanner.active = False
        time.sleep(0.06)                             # the scanner's last request has been answered
        last = scanner.last_answer
        if action == 1:
            time.sleep(LOSS_DELAY + 0.5)
            expect("c101=1 keeps running", (status()["state"], status()["fa06"]), ("running", "0xC400"))
            print("ok: c101=1 keeps running")
            continue
        if action == 4:
            seen = wait_until(lambda: status()["trip"] == 27, LOSS_DELAY + 2)
        else:
            seen = wait_until(lambda: status()["fa06"] == expected_fa06[action], LOSS_DELAY + 2)
        if seen is None:
            fail(f"c101={action}: no reaction: {status()}")
        reaction = seen - last
        if not (LOSS_DELAY - 0.02 <= reaction <= LOSS_DELAY + MARGIN):
            fail(f"c101={action}: reaction {reaction:.3f} s outside [{LOSS_DELAY}, {LOSS_DELAY + MARGIN}]")
        print(f"ok: c101={action} reaction {reaction * 1000:.0f} ms after the last IO scanning request")
    scanner.stop()
    ok("every c101 loss action with its reaction time")
    client.close()


if __name__ == "__main__":
    main()
