#!/usr/bin/python3
"""The card killed (SIGKILL) in the middle of writes, then started again on its state dir
(docs/robustness.md "Power loss"). Run by tools/netns with c500 = 1 (CARD_IP, CARD_PID, CARD_STATE_DIR,
CARD_READY).

Each round, three writers run at once until the kill, at a random moment 50-1600 ms after they start:
  - the TCP/IP object's TTL (attribute 8) over EtherNet/IP: the card's NV record kNvTcpIpExtras;
  - the web write password (POST /api/passwords): the card's NV record kNvWebPasswords;
  - acc (register 0009) through the web API, RAM and EEPROM: the simulated inverter's EEPROM file.
Each remembers the last value the card acknowledged and the one on its way when the card died. After
the restart (same command line, same state dir):
  - the card comes up with the same MAC (kNvFactoryMac) and no warning; no temp file and no `.bad` file
    is left in the state dir (the inverter's image passed its check);
  - the TTL read back and the write password that elevates are the acknowledged value or the one on its
    way, nothing else;
  - acc is one of the values written (the inverter stores its image within a second of a change, so a
    recent acknowledged write may be lost with the drive's power, as on a drive whose EEPROM write was
    cut; a value never written or a damaged image never appears).
Bounded: ROUNDS rounds and TIME_LIMIT seconds.
"""
import http.client
import json
import os
import random
import signal
import socket
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from eip_originator import Client  # noqa: E402

CARD_IP = os.environ["CARD_IP"]
STATE = os.environ["CARD_STATE_DIR"]

ROUNDS = 12
TIME_LIMIT = 75.0
READY_LIMIT = 15.0
TTL = (0xF5, 1, 8)
ACC = "0009"


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def ok(message):
    print(f"ok: {message}")


def mac_of(ready):
    for field in ready.split():
        if field.startswith("mac="):
            return field[4:]
    fail(f"no mac in the ready line: {ready}")


class Card:
    """The firmware process: the one tools/netns started, then the ones this test starts again."""

    def __init__(self):
        self.pid = int(os.environ["CARD_PID"])
        with open(f"/proc/{self.pid}/cmdline", "rb") as f:
            self.argv = [a.decode() for a in f.read().split(b"\0") if a]
        self.process = None
        self.log_path = os.path.join(os.path.dirname(STATE), "restarted-card.log")
        self.ready = os.environ["CARD_READY"]

    def kill(self):
        os.kill(self.pid, signal.SIGKILL)
        if self.process is not None:
            self.process.wait(5)
        else:
            deadline = time.monotonic() + 5
            while time.monotonic() < deadline:
                try:
                    with open(f"/proc/{self.pid}/stat") as f:
                        if f.read().split(") ")[1].startswith("Z"):
                            break  # a zombie of tools/netns: dead, not reaped yet
                except FileNotFoundError:
                    break  # reaped by tools/netns (between any check and the open: seen in a full run)
                time.sleep(0.01)

    def start(self):
        log = open(self.log_path, "w")
        self.process = subprocess.Popen(self.argv, stdout=log, stderr=subprocess.STDOUT)
        self.pid = self.process.pid
        deadline = time.monotonic() + READY_LIMIT
        while time.monotonic() < deadline:
            with open(self.log_path) as f:
                text = f.read()
            ready = [line for line in text.splitlines() if line.startswith("ready ")]
            if ready:
                self.ready = ready[0]
                return text
            if self.process.poll() is not None:
                fail(f"the card exited with {self.process.returncode} on restart:\n{text}")
            time.sleep(0.05)
        fail(f"the card was not ready {READY_LIMIT:.0f} s after the restart")

    def stop(self):
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(5)
            except subprocess.TimeoutExpired:
                self.process.kill()


class Web:
    def __init__(self):
        self.conn = http.client.HTTPConnection(CARD_IP, 80, timeout=3)
        self.cookie = ""
        self.csrf = ""

    def call(self, method, path, body=None):
        headers = {"Content-Type": "application/json"}
        if self.cookie:
            headers["Cookie"] = self.cookie
        if self.csrf:
            headers["X-CSRF-Token"] = self.csrf
        self.conn.request(method, path, None if body is None else json.dumps(body), headers)
        response = self.conn.getresponse()
        data = response.read()
        cookie = response.getheader("Set-Cookie")
        if cookie:
            self.cookie = cookie.split(";")[0]
        return response.status, (json.loads(data) if data else None)

    def login(self):
        status, body = self.call("POST", "/api/login", {"password": "USER"})
        if status != 200:
            fail(f"login with the read password: {status} {body}")
        self.csrf = body["csrf"]

    def elevate(self, password):
        return self.call("POST", "/api/elevate", {"password": password})[0] == 200

    def close(self):
        self.conn.close()

    def socket(self):
        return self.conn.sock


def cut_off(sock):
    """A dead card answers nothing, not even RST: wake a writer blocked on its socket."""
    if sock is not None:
        try:
            sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass


class Writer(threading.Thread):
    """Writes distinct values until the connection breaks; `acked` and `on_its_way` say what the card
    confirmed last and what it was asked last without answering."""

    def __init__(self, name, acked, values, write):
        super().__init__(name=name, daemon=True)
        self.acked, self.on_its_way, self.values, self.write = acked, None, values, write
        self.written = []  # every value asked for
        self.count = 0

    def run(self):
        try:
            for value in self.values:
                self.on_its_way = value
                self.written.append(value)
                if not self.write(value):
                    return
                self.acked, self.on_its_way = value, None
                self.count += 1
        except Exception:  # noqa: BLE001 - whatever the dead card's socket raises ends the writer
            return


def ttl_values(start):
    value = start
    while True:
        value = value % 254 + 2  # 2..255, never the default 1
        yield value


def wait_http():
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        try:
            socket.create_connection((CARD_IP, 80), 1).close()
            return
        except OSError:
            time.sleep(0.05)
    fail("port 80 not open after the restart")


def leftovers():
    found = []
    for directory, _, files in os.walk(STATE):
        found += [os.path.join(directory, f) for f in files if f.endswith(".tmp") or f.endswith(".bad")]
    return found


def main():
    card = Card()
    mac = mac_of(card.ready)
    started = time.monotonic()
    ttl_acked, password_acked, acc_written = 1, "USER", {None}
    acc_initial = None
    rng = random.Random(8)
    kills_during = {"ttl": 0, "password": 0, "acc": 0}
    try:
        for round_number in range(ROUNDS):
            if time.monotonic() - started > TIME_LIMIT:
                fail(f"only {round_number} rounds in {TIME_LIMIT:.0f} s")
            wait_http()
            eip = Client(CARD_IP, timeout=3.0)
            if eip.register_session().status != 0:
                fail("RegisterSession")
            web_password, web_acc = Web(), Web()
            for web in (web_password, web_acc):
                web.login()
                if not web.elevate(password_acked):
                    fail(f"round {round_number}: the write password {password_acked!r} does not elevate")
            if acc_initial is None:
                status, body = web_acc.call("GET", f"/api/registers?numbers={ACC}")
                acc_initial = body["values"][0]["value"]
                acc_written = {acc_initial}

            def write_ttl(value):
                return eip.set_attribute_single(*TTL, bytes([value])).general == 0

            def write_password(value):
                return web_password.call("POST", "/api/passwords", {"which": "write", "password": value})[0] == 204

            def write_acc(value):
                return web_acc.call("POST", "/api/registers", {"number": ACC, "value": value})[0] == 200

            passwords = (f"r{round_number}w{n}" for n in range(1_000_000))
            accs = (10 + (round_number * 997 + n) % 5000 for n in range(1_000_000))
            writers = [Writer("ttl", ttl_acked, ttl_values(ttl_acked), write_ttl),
                       Writer("password", password_acked, passwords, write_password),
                       Writer("acc", None, accs, write_acc)]
            for writer in writers:
                writer.start()
            # Up to 1.6 s: the inverter stores its image once a second, so some kills come after a store.
            time.sleep(rng.uniform(0.05, 1.6))
            card.kill()
            for sock in (eip.sock, web_password.socket(), web_acc.socket()):
                cut_off(sock)
            for writer in writers:
                writer.join(5)
                if writer.is_alive():
                    fail(f"the {writer.name} writer did not notice the card's death")
                if writer.on_its_way is not None:
                    kills_during[writer.name] += 1
            eip.close()
            web_password.close()
            web_acc.close()
            ttl, password, acc = writers
            acc_written.update(acc.written)

            log = card.start()
            if mac_of(card.ready) != mac:
                fail(f"round {round_number}: the MAC changed from {mac} to {mac_of(card.ready)}")
            if "warning" in log:
                fail(f"round {round_number}: the restarted card warns:\n{log}")
            if leftovers():
                fail(f"round {round_number}: left in the state dir: {leftovers()}")

            wait_http()
            eip = Client(CARD_IP, timeout=3.0)
            eip.register_session()
            got_ttl = eip.get_attribute_single(*TTL[:2], TTL[2]).data[0]
            eip.close()
            if got_ttl not in (ttl.acked, ttl.on_its_way):
                fail(f"round {round_number}: TTL {got_ttl} after the restart; acknowledged {ttl.acked}, "
                     f"on its way {ttl.on_its_way}")
            ttl_acked = got_ttl

            web = Web()
            web.login()
            candidates = [p for p in (password.on_its_way, password.acked) if p is not None]
            for candidate in candidates:
                if web.elevate(candidate):
                    password_acked = candidate
                    break
            else:
                fail(f"round {round_number}: neither {candidates} is the write password after the restart")
            status, body = web.call("GET", f"/api/registers?numbers={ACC}")
            web.close()
            got_acc = body["values"][0]["value"] if status == 200 else None
            if got_acc not in acc_written:
                fail(f"round {round_number}: acc {got_acc} after the restart was never written")
            print(f"round {round_number}: killed after {ttl.count} TTL, {password.count} password and "
                  f"{acc.count} acc writes; TTL {got_ttl}, acc {got_acc}")
        ok(f"{ROUNDS} kills in the middle of writes (a write on its way at the kill: {kills_during}); after "
           f"each restart the same MAC, no warning, no temp or .bad file, TTL and write password old or new, "
           f"acc a written value")
    finally:
        card.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
