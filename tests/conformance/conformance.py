#!/usr/bin/python3
"""The negative conformance suite's runner (docs/conformance.md).

usage: conformance.py modbus|eip      (inside the namespace of tools/netns: CARD_IP, HOST_IP, CARD_PID,
                                       CARD_CONTROL and NEG_IP, the second host address, are set)

A case is data: what to send (bytes, or chunks with pauses between them so that they leave as separate
TCP segments) and what must come back: the exact bytes of each reply, in order, then optionally CLOSED
(the card closes the connection and sends nothing more). A case that expects no reply (a documented
drop) lists none. After the expected replies the runner sends a *probe* (a request with a known answer)
on the same connection and requires that its answer is the next thing that arrives: so "no reply" is
checked without waiting, and a stray extra reply or a stream out of step fails the case.

Each protocol module (modbus_cases, eip_*_cases) gives its case tables and a `Protocol` (how replies are
framed, how to connect, the probe). The runner prints one line per case and a summary, and exits 1 when
any case failed. Every wait is bounded.
"""
import os
import select
import socket
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "integration"))  # eip_originator, eip_io

REPLY_TIMEOUT = 2.0   # the longest a reply may take (drive reads go over the simulated serial link)
CLOSE_TIMEOUT = 2.0   # the longest the card may take to close a connection it must close


class Closed:
    """Expectation: the card closes the connection (FIN or RST) and sends nothing more."""

    def __repr__(self):
        return "CLOSED"


CLOSED = Closed()


class Chunk:
    """Bytes sent after a pause (seconds): with TCP_NODELAY each chunk leaves as its own segment."""

    def __init__(self, data, pause=0.02):
        self.data = data
        self.pause = pause


class Quiet:
    """In a send list: nothing may arrive (and the connection must stay open) for `seconds`: the card is
    waiting for the rest of a message."""

    def __init__(self, seconds=0.3):
        self.seconds = seconds


class Case:
    """One case. `send`: bytes, a callable (link -> bytes), or a list of those and Chunks. `expect`: a list
    of replies (bytes or callables link -> bytes), possibly ending in CLOSED; [] means no reply.
    `probe`: whether the connection must still be in step afterwards (False only where the card is
    waiting for more bytes of a message, which the probe would complete)."""

    def __init__(self, area, name, send, expect, probe=True, on="fresh"):
        self.area, self.name = area, name
        self.send = send if isinstance(send, list) else [send]
        self.expect = expect if isinstance(expect, list) else [expect]
        self.probe = probe and not (self.expect and self.expect[-1] is CLOSED)
        self.on = on


class Failure(Exception):
    pass


def hexs(data):
    return data.hex(" ").upper() if data is not None else "nothing"


def unhex(text):
    return bytes.fromhex(text.replace("|", " "))


def resolve(item, link):
    return item(link) if callable(item) else bytes(item)


class Link:
    """One TCP connection with a receive buffer; `framer(buffer)` tells the length of the first message
    (None until enough bytes are there)."""

    def __init__(self, host, port, framer, source=None, timeout=3.0):
        self.sock = socket.create_connection((host, port), timeout,
                                             source_address=(source, 0) if source else None)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.framer = framer
        self.buffer = b""
        self.eof = False
        self.session = 0          # EtherNet/IP: this connection's session handle
        self.other_session = 0    # EtherNet/IP: a handle registered on another connection

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass

    def send(self, data):
        self.sock.sendall(data)

    def _fill(self, deadline):
        """Reads what is there (waiting until deadline); False on timeout, sets eof on FIN or RST."""
        left = deadline - time.monotonic()
        if left <= 0 or self.eof:
            return False
        ready, _, _ = select.select([self.sock], [], [], left)
        if not ready:
            return False
        try:
            chunk = self.sock.recv(65536)
        except (ConnectionResetError, ConnectionAbortedError):
            chunk = b""
        if not chunk:
            self.eof = True
            return False
        self.buffer += chunk
        return True

    def receive(self, timeout=REPLY_TIMEOUT):
        """The next whole message, or None (timeout or the connection closed first)."""
        deadline = time.monotonic() + timeout
        while True:
            size = self.framer(self.buffer)
            if size is not None and len(self.buffer) >= size:
                message, self.buffer = self.buffer[:size], self.buffer[size:]
                return message
            if not self._fill(deadline):
                return None

    def closed_by_peer(self, timeout=CLOSE_TIMEOUT):
        """True when the card closes within `timeout` without sending another byte."""
        deadline = time.monotonic() + timeout
        while not self.eof and not self.buffer:
            if not self._fill(deadline):
                break
        return self.eof and not self.buffer


class Protocol:
    """What the runner needs from a protocol module."""

    name = "protocol"

    def connect(self, case):
        """A Link for the case (a fresh connection, or a shared one named by case.on)."""
        raise NotImplementedError

    def release(self, case, link, failed):
        """Done with the link: close a fresh one; keep a shared one unless it failed or closed."""
        raise NotImplementedError

    def probe(self, link):
        """(request bytes, the exact answer) of a request whose answer shows the stream is in step."""
        raise NotImplementedError

    def other_cases(self):
        """Cases of another kind (UDP, connection limits): [(area, name, callable raising Failure)]."""
        return []

    def health(self):
        """After every case: a healthy client is served correctly. [(name, callable raising Failure)]"""
        return []


def card_alive():
    """The card process (CARD_PID of tools/netns) still runs."""
    pid = int(os.environ["CARD_PID"])
    try:
        os.kill(pid, 0)
    except OSError as error:
        raise Failure(f"card process {pid}: {error}") from error


def run_tcp_case(protocol, case):
    link = protocol.connect(case)
    failed = True
    try:
        for item in case.send:
            if isinstance(item, Quiet):
                got = link.receive(item.seconds)
                if got is not None or link.eof:
                    raise Failure(f"expected nothing for {item.seconds} s, got {hexs(got) if got else 'a close'}")
                continue
            chunk = item if isinstance(item, Chunk) else Chunk(item, 0)
            if chunk.pause:
                time.sleep(chunk.pause)
            link.send(resolve(chunk.data, link))
        for i, want in enumerate(case.expect):
            if want is CLOSED:
                if not link.closed_by_peer():
                    raise Failure(f"expected the card to close the connection; got {hexs(link.buffer) if link.buffer else 'it stayed open'}")
                break
            want = resolve(want, link)
            got = link.receive()
            if got != want:
                what = "closed the connection" if got is None and link.eof else hexs(got)
                raise Failure(f"reply {i + 1}:\n      got      {what}\n      expected {hexs(want)}")
        if case.probe:
            request, answer = protocol.probe(link)
            link.send(request)
            got = link.receive()
            if got != answer:
                what = "the connection closed" if got is None and link.eof else hexs(got)
                raise Failure(f"probe afterwards (stream in step, no extra reply):\n      got      {what}\n"
                              f"      expected {hexs(answer)}")
        failed = False
    except OSError as error:
        raise Failure(f"socket error: {error}") from error
    finally:
        protocol.release(case, link, failed)


def main(protocol, cases):
    results = {}   # area -> [passed, failed]
    failures = []
    started = time.monotonic()

    def record(area, name, error):
        counts = results.setdefault(area, [0, 0])
        if error is None:
            counts[0] += 1
            print(f"PASS {area}: {name}", flush=True)
        else:
            counts[1] += 1
            failures.append(f"{area}: {name}")
            print(f"FAIL {area}: {name}\n    {error}", flush=True)

    def attempt(area, name, action):
        try:
            action()
            record(area, name, None)
        except Failure as error:
            record(area, name, error)
        except Exception as error:  # a broken case must not hide the others
            record(area, name, f"{type(error).__name__}: {error}")

    for case in cases:
        attempt(case.area, case.name, lambda case=case: run_tcp_case(protocol, case))
    for area, name, action in protocol.other_cases():
        attempt(area, name, action)
    for name, action in protocol.health():
        attempt("health", name, action)

    total = sum(p + f for p, f in results.values())
    print(f"\n{protocol.name}: {total} cases in {time.monotonic() - started:.1f} s")
    width = max((len(area) for area in results), default=0)
    for area, (p, f) in results.items():
        print(f"  {area:{width}s} {p:4d} passed {f:4d} failed")
    if failures:
        print(f"FAILED {len(failures)}:\n  " + "\n  ".join(failures))
        return 1
    print("all passed")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] not in ("modbus", "eip"):
        sys.exit(__doc__.split("\n\n")[1])
    # The case modules import this file as the module `conformance`: run that one, not __main__, so that
    # CLOSED, Chunk and Quiet are the same objects on both sides.
    import conformance
    if sys.argv[1] == "modbus":
        import modbus_cases as suite
    else:
        import eip_suite as suite
    sys.exit(conformance.main(suite.protocol(), suite.cases()))
