#!/usr/bin/python3
"""board.qemu_boot: the card image boots on QEMU's mps2-an386 without a drive and without a network
peer beyond QEMU's user-mode network (no host ports are forwarded).

Checks, on the console (UART0, a UNIX socket chardev): the start lines; the drive link gives up (e-23)
and the ready line comes with drive=fault and no address; `stats` reports the painted stack
(stack.size, stack.high_water within it) and the loop; `leds` in the host's format; an unknown command
and an overlong line get their errors; `watchdog-test` stops the loop, the watchdog warns after its first timeout and resets
the card after the second, and the card starts again with the records of its first start (its MAC, the
stored random seed) read back from the flash store on the semihosting file. Every wait is bounded.

usage: qemu_boot.py QEMU IMAGE
"""
import os
import re
import socket
import subprocess
import sys
import tempfile
import time


def fail(message, log=""):
    print("FAIL: " + message)
    if log:
        print("--- console so far:\n" + log)
    sys.exit(1)


class Console:
    def __init__(self, path, deadline=20.0):
        end = time.time() + deadline
        while True:
            try:
                self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                self.sock.connect(path)
                break
            except OSError:
                self.sock.close()
                if time.time() > end:
                    fail("cannot connect to the console socket " + path)
                time.sleep(0.1)
        self.sock.settimeout(0.2)
        self.text = ""

    def wait_for(self, pattern, seconds):
        """The first match of `pattern` after what earlier waits consumed."""
        end = time.time() + seconds
        regex = re.compile(pattern, re.MULTILINE)
        while True:
            # Only whole lines: a line still arriving must not match a pattern ending in $.
            complete = self.text[:self.text.rfind("\n") + 1]
            match = regex.search(complete)
            if match:
                self.text = self.text[match.end():]
                return match
            if time.time() > end:
                fail("no line matching %r within %d s" % (pattern, seconds), self.text)
            try:
                data = self.sock.recv(4096)
                if not data:
                    fail("the console closed", self.text)
                self.text += data.decode(errors="replace").replace("\r", "")
            except socket.timeout:
                pass

    def command(self, line, seconds=5):
        self.sock.sendall(line.encode() + b"\r")
        match = self.wait_for(r"^(ok|error[^\n]*)$", seconds)
        return match


def main():
    if len(sys.argv) != 3:
        fail("usage: qemu_boot.py QEMU IMAGE")
    qemu, image = sys.argv[1], sys.argv[2]
    if not qemu or not os.access(qemu, os.X_OK):
        fail("qemu-system-arm not found (%r); install qemu-system-arm (tools/setup)" % qemu)
    if not os.path.isfile(image):
        fail("no board image at %s; build it: cmake --preset cortex-m4 && cmake --build --preset cortex-m4" % image)
    with tempfile.TemporaryDirectory() as work:
        sock = os.path.join(work, "console.sock")
        args = [qemu, "-M", "mps2-an386", "-display", "none", "-monitor", "none", "-kernel", image,
                "-semihosting-config", "enable=on,target=native,arg=ipe002z-board,arg=flash=%s/flash.bin" % work,
                "-nic", "user",
                "-chardev", "socket,id=console,path=%s,server=on,wait=on" % sock, "-serial", "chardev:console",
                "-serial", "null"]
        process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        try:
            console = Console(sock)
            console.wait_for(r"^ipe002z-board: mps2-an386 \(Cortex-M4F\), starting$", 20)
            console.wait_for(r"^flash: file=\S+/flash\.bin sectors=8x4096 unit=8$", 10)
            console.wait_for(r"^nv: flash store mounted, empty$", 10)
            console.wait_for(r"^random: chacha20 seed=new renewed=yes jitter_samples=256 ", 10)
            mac = console.wait_for(r"^ethernet: LAN9118 id_rev=0x01180001 mac=((?:[0-9a-f]{2}:){5}[0-9a-f]{2})$",
                                   10).group(1)
            console.wait_for(r"^led MS red t=\d+$", 10)
            console.wait_for(r"^ready ip=0\.0\.0\.0 mac=([0-9a-f]{2}:){5}[0-9a-f]{2} net=board "
                             r"modbus=0\.0\.0\.0:502 enip=0\.0\.0\.0:44818 enip-udp=0\.0\.0\.0:44818 "
                             r"io=0\.0\.0\.0:2222 http=0\.0\.0\.0:80 drive=fault$", 30)

            console.sock.sendall(b"stats\r")
            size = int(console.wait_for(r"^stack\.size=(\d+)$", 5).group(1))
            high = int(console.wait_for(r"^stack\.high_water=(\d+)$", 5).group(1))
            if size != 8192 or not 0 < high < size:
                fail("stack.size=%d stack.high_water=%d: expected 8192 and a high water within it" % (size, high))
            passes = int(console.wait_for(r"^loop\.passes=(\d+)$", 5).group(1))
            if passes == 0:
                fail("loop.passes=0")
            console.wait_for(r"^netif\.link=up$", 5)
            console.wait_for(r"^drive\.link=fault$", 5)
            console.wait_for(r"^ok$", 5)

            console.sock.sendall(b"leds\r")
            console.wait_for(r"^LNK-L=green LNK-R=off MS=red NS=off$", 5)
            console.wait_for(r"^ok$", 5)
            answer = console.command("no-such-command").group(1)
            if answer != "error unknown command (help lists them)":
                fail("an unknown command got %r" % answer, console.text)
            answer = console.command("stats" + " " * 100).group(1)
            if answer != "error line too long":
                fail("a line of 105 characters got %r" % answer, console.text)

            console.sock.sendall(b"watchdog-test\r")
            console.wait_for(r"^watchdog-test: the event loop stops here", 5)
            started = time.time()
            console.wait_for(r"^watchdog: the loop has not fed the watchdog for 1000 ms; reset in 1000 ms", 5)
            console.wait_for(r"^ipe002z-board: mps2-an386 \(Cortex-M4F\), starting$", 5)
            elapsed = time.time() - started
            # The records written at the first start are on the flash file: the same MAC, the stored seed.
            console.wait_for(r"^nv: flash store mounted, generation=\d+ active_sector=\d+$", 10)
            console.wait_for(r"^random: chacha20 seed=stored renewed=yes ", 10)
            console.wait_for(r"^ethernet: LAN9118 id_rev=0x01180001 mac=%s$" % re.escape(mac), 10)
            console.wait_for(r"^ready ip=0\.0\.0\.0 mac=%s " % re.escape(mac), 30)
            print("ok: booted, ready without a drive, stats (stack %d of %d bytes), leds, watchdog reset after "
                  "%.1f s, booted again with its MAC %s from the flash store" % (high, size, elapsed, mac))
        finally:
            process.kill()
            process.wait(timeout=10)


if __name__ == "__main__":
    main()
