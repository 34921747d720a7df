#!/usr/bin/python3
"""The card's EDS from the card itself (docs/file-object.md), over TAP against the host card (c500 = 1).
Run by tools/netns with --pcap (CARD_IP, HOST_IP, CARD_PCAP); EDS_FILE names the file the card was told to
serve (--eds), or the built EDS of the card's own model (EDS_NAME: the name the card gives it): every
download must equal it byte for byte (without EDS_FILE: the HTTP body is the reference).

1. HTTP: GET /api/eds without a session is 401; after login it is 200 with application/octet-stream, an
   attachment file name and Content-Length equal to the body's size; curl downloads the same bytes.
2. CIP, File object 0x37 instance 0xC8: attribute 6 (size) and 7 (checksum) agree with the HTTP body,
   attribute 4 names the same file; the whole file uploaded with Initiate_Upload at transfer size 7
   (numbers wrapping past 255 for a file over 1792 bytes), packet types first / middle / last, the
   checksum after the last packet's data, a resend of packet 3 equal to the first sending, an
   out-of-sequence number refused 0x20/0x0006 without losing the place; a second session cannot
   initiate while the first one's upload is live (0x0C); Upload_Transfer without an upload is 0x0C.
   The uploaded bytes equal the HTTP body byte for byte; bytes + checksum = 0 modulo 2^16.
3. tshark over the capture: no malformed frame and no expert warning in the EtherNet/IP and HTTP traffic.
Every loop is bounded (the transfer count by the file size, each request by the client's timeout).
"""
import http.client
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from eip_originator import Client, epath, mr_request  # noqa: E402

CARD_IP = os.environ["CARD_IP"]
HOST_IP = os.environ["HOST_IP"]
FILE_CLASS = 0x37
EDS_INSTANCE = 0xC8
INITIATE_UPLOAD = 0x4B
UPLOAD_TRANSFER = 0x4F
TRANSFER_SIZE = 7
checks = 0


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def same(what, got, want):
    global checks
    checks += 1
    if got != want:
        fail(f"{what}: got {got!r}, expected {want!r}")


def http_get_eds():
    def get(cookie=None):
        connection = http.client.HTTPConnection(CARD_IP, 80, timeout=10)
        connection.request("GET", "/api/eds", headers={"Cookie": f"ipe_session={cookie}"} if cookie else {})
        response = connection.getresponse()
        body = response.read()
        connection.close()
        return response, body

    response, _ = get()
    same("GET /api/eds without a session", response.status, 401)
    connection = http.client.HTTPConnection(CARD_IP, 80, timeout=10)
    connection.request("POST", "/api/login", body=json.dumps({"password": "USER"}),
                       headers={"Content-Type": "application/json"})
    login = connection.getresponse()
    login.read()
    same("login", login.status, 200)
    cookie = re.search(r"ipe_session=([0-9a-f]{32})", login.getheader("Set-Cookie") or "")
    if not cookie:
        fail("login set no session cookie")
    connection.close()
    response, body = get(cookie.group(1))
    same("GET /api/eds", response.status, 200)
    same("Content-Type", response.getheader("Content-Type"), "application/octet-stream")
    same("Content-Length", response.getheader("Content-Length"), str(len(body)))
    name = re.fullmatch(r'attachment; filename="([^"]+)"', response.getheader("Content-Disposition") or "")
    if not name:
        fail(f"Content-Disposition: {response.getheader('Content-Disposition')!r}")
    if not body:
        fail("the EDS is empty")
    with_curl = subprocess.run(["curl", "-s", "--max-time", "20", "-b", f"ipe_session={cookie.group(1)}",
                                f"http://{CARD_IP}/api/eds"], capture_output=True, timeout=30).stdout
    same("curl's download against http.client's", with_curl, body)
    print(f"ok: GET /api/eds: 401 without a session, then 200, {len(body)} bytes as {name.group(1)}")
    return body, name.group(1)


def short_string_i(data):
    """The text of a STRINGI with one string (USINT 1, 'eng', 0xDA, UINT 4, SHORT_STRING)."""
    same("STRINGI head", data[:7], b"\x01eng\xda\x04\x00")
    return data[8:8 + data[7]].decode("latin-1")


def upload(client, eds):
    def ask(service, data, instance=EDS_INSTANCE):
        return client.cip(mr_request(service, epath(FILE_CLASS, instance), data))

    size = client.get_attribute_single(FILE_CLASS, EDS_INSTANCE, 6)
    same("attribute 6 status", size.general, 0)
    same("attribute 6 (file size)", struct.unpack("<I", size.data)[0], len(eds))
    checksum_reply = client.get_attribute_single(FILE_CLASS, EDS_INSTANCE, 7)
    checksum = struct.unpack("<H", checksum_reply.data)[0]
    same("attribute 7 (checksum) against the HTTP body", (sum(eds) + checksum) & 0xFFFF, 0)
    name = short_string_i(client.get_attribute_single(FILE_CLASS, EDS_INSTANCE, 4).data)

    refused = ask(UPLOAD_TRANSFER, b"\x00")
    same("Upload_Transfer without Initiate_Upload", (refused.general, refused.data), (0x0C, b""))
    initiated = ask(INITIATE_UPLOAD, bytes([TRANSFER_SIZE]))
    same("Initiate_Upload", (initiated.general, initiated.data), (0, struct.pack("<IB", len(eds), TRANSFER_SIZE)))
    same("attribute 1 after Initiate_Upload", client.get_attribute_single(FILE_CLASS, EDS_INSTANCE, 1).data, b"\x03")

    uploaded = b""
    packets = (len(eds) + TRANSFER_SIZE - 1) // TRANSFER_SIZE
    for index in range(packets):
        number = index % 256
        reply = ask(UPLOAD_TRANSFER, bytes([number]))
        same(f"transfer {index} status", (reply.general, reply.extended), (0, []))
        same(f"transfer {index} number", reply.data[0], number)
        last = index == packets - 1
        want_type = 4 if index == 0 and last else 0 if index == 0 else 2 if last else 1
        same(f"transfer {index} packet type", reply.data[1], want_type)
        data = reply.data[2:-2] if last else reply.data[2:]
        same(f"transfer {index} data size", len(data), min(TRANSFER_SIZE, len(eds) - len(uploaded)))
        if last:
            same("checksum after the last packet", struct.unpack("<H", reply.data[-2:])[0], checksum)
        uploaded += data
        if index == 3:
            again = ask(UPLOAD_TRANSFER, bytes([number]))
            same("resend of transfer 3", again.raw(), reply.raw())
            wrong = ask(UPLOAD_TRANSFER, bytes([(number + 2) % 256]))
            same("out-of-sequence transfer", (wrong.general, wrong.extended), (0x20, [0x0006]))
            with Client(CARD_IP) as other:
                same("second session's RegisterSession", other.register_session().status, 0)
                busy = other.cip(mr_request(INITIATE_UPLOAD, epath(FILE_CLASS, EDS_INSTANCE), bytes([TRANSFER_SIZE])))
                same("a second session's Initiate_Upload during an upload", busy.general, 0x0C)
                other.unregister_session()
    same("uploaded bytes against the HTTP body", uploaded, eds)
    same("attribute 1 after the upload", client.get_attribute_single(FILE_CLASS, EDS_INSTANCE, 1).data, b"\x02")
    print(f"ok: File object: {packets} transfers of {TRANSFER_SIZE} bytes, the bytes and checksum 0x{checksum:04X} "
          f"equal the HTTP download; file name {name!r}; resend, out of sequence, second session refused")
    return name


def capture_clean():
    pcap = os.environ.get("CARD_PCAP")
    if not pcap or not shutil.which("tshark"):
        print("ok: no capture (tshark or --pcap missing): capture check skipped")
        return
    time.sleep(0.3)  # the last frames reach the file
    copy = pcap + ".eds"
    shutil.copy(pcap, copy)

    def count(display_filter):
        out = subprocess.run(["tshark", "-r", copy, "-Y", display_filter], capture_output=True, text=True, timeout=60)
        return len(out.stdout.splitlines())

    bad = f"ip.addr == {HOST_IP} && !tcp.connection.rst && (_ws.malformed || _ws.expert.severity >= warning)"
    flagged = count(bad)
    if flagged:
        details = subprocess.run(["tshark", "-r", copy, "-Y", bad, "-V"], capture_output=True, text=True, timeout=60)
        print("\n".join(line for line in details.stdout.splitlines() if re.match(r"^Frame|.*(Expert|Malformed)", line))[:4000])
        fail(f"{flagged} frames malformed or with expert warnings")
    cip = count("cip")
    if cip < 100:
        fail(f"only {cip} CIP frames in the capture")
    print(f"ok: tshark: {cip} CIP frames and the HTTP download, none malformed, no expert warning")


def main():
    eds, http_name = http_get_eds()
    if os.environ.get("EDS_FILE"):
        with open(os.environ["EDS_FILE"], "rb") as served:
            same("GET /api/eds against the file served", eds, served.read())
        same("file name", http_name, os.environ.get("EDS_NAME", os.path.basename(os.environ["EDS_FILE"])))
    with Client(CARD_IP) as client:
        same("RegisterSession", client.register_session().status, 0)
        name = upload(client, eds)
        client.unregister_session()
    same("file name: attribute 4 against Content-Disposition", name, http_name)
    capture_clean()
    print(f"ok: EDS from the card: {checks} checks")


if __name__ == "__main__":
    main()
