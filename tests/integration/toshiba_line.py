#!/usr/bin/python3
"""Talk to a simulated inverter's serial line as the card would (ipe002z-inverter --serial ENDPOINT).

usage: toshiba_line.py unix:PATH|tcp:HOST:PORT FRAME [FRAME ...]
FRAME is hex bytes ("2F 52 FD 01 7F"; spaces optional) or ascii:TEXT (sent with the CR that ends an
ASCII frame). The frames go one at a time on one connection; for each, one line is printed: the reply in
hex (uppercase, bytes separated by spaces), or "-" when nothing came within 0.5 s. A reply is complete
when the line stays quiet for 0.1 s after its first byte. Exit 2 on a connection problem.
"""
import select
import socket
import sys

NOTHING_AFTER = 0.5  # s: no reply (the inverter stays silent)
QUIET_AFTER = 0.1    # s: the reply is complete


def frame_bytes(text):
    if text.startswith("ascii:"):
        return text[len("ascii:"):].encode() + b"\r"
    return bytes.fromhex(text)


def receive(sock):
    data = b""
    while True:
        ready, _, _ = select.select([sock], [], [], QUIET_AFTER if data else NOTHING_AFTER)
        if not ready:
            return data
        chunk = sock.recv(256)
        if not chunk:  # the inverter closed the line: what came is all there is
            return data
        data += chunk


def connect(endpoint):
    if endpoint.startswith("unix:"):
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        sock.connect(endpoint[len("unix:"):])
        return sock
    host, port = endpoint[len("tcp:"):].rsplit(":", 1)
    return socket.create_connection((host, int(port)), timeout=5)


def main(argv):
    if len(argv) < 3 or not argv[1].startswith(("unix:", "tcp:")):
        sys.stderr.write(__doc__)
        return 2
    try:
        sock = connect(argv[1])
    except (OSError, ValueError) as error:
        sys.stderr.write("toshiba_line: %s\n" % error)
        return 2
    for text in argv[2:]:
        sock.sendall(frame_bytes(text))
        reply = receive(sock)
        print(" ".join("%02X" % b for b in reply) if reply else "-", flush=True)
    sock.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
