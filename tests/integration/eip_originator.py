#!/usr/bin/python3
"""A small EtherNet/IP originator (client) for the integration tests and for manual use.

Standard library only. Encapsulation over TCP (RegisterSession, UnRegisterSession, ListIdentity,
ListServices, ListInterfaces, NOP, SendRRData carrying UCMM requests) and over UDP (ListIdentity,
ListServices, ListInterfaces to a unicast or broadcast address); message router requests
(Get_Attribute_Single/All, Set_Attribute_Single, Get_Attribute_List, Reset, Get_and_Clear, any service),
Multiple Service Packet 0x0A and Unconnected_Send 0x52; raw messages for negative cases.

Every decoder goes through Reader, which never reads past the bytes it was given (a reply shorter than
its fields say raises ProtocolError); a TCP reply is read as exactly its 24-byte header plus the length
the header announces, bounded by MAX_REPLY_DATA.

usage: eip_originator.py --host H [--port P] [--timeout S] [--source ADDR] COMMAND [ARG...]
commands (numbers are decimal or 0x-hex, data is hex):
  list-identity [--udp|--broadcast] [--max-delay MS]   ListIdentity (TCP, unicast UDP or broadcast UDP)
  list-services [--udp]  list-interfaces [--udp]  nop [HEX]
  register                                   RegisterSession, then UnRegisterSession
  get CLASS INSTANCE ATTRIBUTE               Get_Attribute_Single
  get-all CLASS INSTANCE                     Get_Attributes_All
  set CLASS INSTANCE ATTRIBUTE HEX           Set_Attribute_Single
  get-list CLASS INSTANCE ATTRIBUTE...       Get_Attribute_List (0x03)
  get-clear CLASS INSTANCE ATTRIBUTE         Get_and_Clear (0x4C)
  reset [TYPE]                               Identity Reset (the card restarts!)
  cip HEX                                    any message router request, in a session
  ucs HEX [ROUTE-HEX]                        Unconnected_Send carrying a request (route default: none)
  msp HEX HEX...                             Multiple Service Packet of requests
  raw HEX                                    send these bytes on a fresh TCP connection, print the replies
"""
import argparse
import select
import socket
import struct
import sys
import time

EIP_PORT = 44818

# Encapsulation commands.
NOP = 0x0000
LIST_SERVICES = 0x0004
LIST_IDENTITY = 0x0063
LIST_INTERFACES = 0x0064
REGISTER_SESSION = 0x0065
UNREGISTER_SESSION = 0x0066
SEND_RR_DATA = 0x006F
SEND_UNIT_DATA = 0x0070

# Encapsulation status codes.
ENCAP_SUCCESS = 0x0000
ENCAP_INVALID_COMMAND = 0x0001
ENCAP_INSUFFICIENT_MEMORY = 0x0002
ENCAP_INCORRECT_DATA = 0x0003
ENCAP_INVALID_SESSION = 0x0064
ENCAP_INVALID_LENGTH = 0x0065
ENCAP_UNSUPPORTED_PROTOCOL = 0x0069

# Common Packet Format item types.
ITEM_NULL = 0x0000
ITEM_LIST_IDENTITY = 0x000C
ITEM_CONNECTED_ADDRESS = 0x00A1
ITEM_CONNECTED_DATA = 0x00B1
ITEM_UNCONNECTED_DATA = 0x00B2
ITEM_LIST_SERVICES = 0x0100
ITEM_SOCKADDR_O_T = 0x8000
ITEM_SOCKADDR_T_O = 0x8001

# CIP services.
GET_ATTRIBUTES_ALL = 0x01
GET_ATTRIBUTE_LIST = 0x03
RESET = 0x05
MULTIPLE_SERVICE_PACKET = 0x0A
GET_ATTRIBUTE_SINGLE = 0x0E
SET_ATTRIBUTE_SINGLE = 0x10
GET_AND_CLEAR = 0x4C
UNCONNECTED_SEND = 0x52

HEADER = struct.Struct("<HHII8sI")
HEADER_SIZE = HEADER.size  # 24
# The largest reply data accepted (the card's replies are at most 624 bytes in all).
MAX_REPLY_DATA = 4096


class ProtocolError(Exception):
    """A reply that does not decode (too short, inconsistent, unexpected)."""


class ConnectionClosed(Exception):
    """The peer closed the TCP connection (FIN or RST)."""


def hexs(data):
    return data.hex(" ").upper()


def unhex(text):
    return bytes.fromhex(text.replace("|", " ").replace(":", " "))


class Reader:
    """Bounded little-endian reader: never reads past its bytes (ProtocolError instead)."""

    def __init__(self, data, what="data"):
        self.data = bytes(data)
        self.pos = 0
        self.what = what

    def take(self, n):
        if n < 0 or self.pos + n > len(self.data):
            raise ProtocolError(f"{self.what}: needs {n} bytes at offset {self.pos}, has {len(self.data) - self.pos}")
        chunk = self.data[self.pos:self.pos + n]
        self.pos += n
        return chunk

    def u8(self):
        return self.take(1)[0]

    def u16(self):
        return struct.unpack("<H", self.take(2))[0]

    def u16be(self):
        return struct.unpack(">H", self.take(2))[0]

    def u32(self):
        return struct.unpack("<I", self.take(4))[0]

    def remaining(self):
        return len(self.data) - self.pos

    def rest(self):
        return self.take(self.remaining())

    def end(self):
        if self.remaining() != 0:
            raise ProtocolError(f"{self.what}: {self.remaining()} bytes left over")


# ---- Encapsulation -------------------------------------------------------------------------------

class Encap:
    """One encapsulation message: header fields and data."""

    def __init__(self, command, data=b"", session=0, status=0, context=bytes(8), options=0, length=None):
        self.command = command
        self.data = bytes(data)
        self.session = session
        self.status = status
        self.context = bytes(context)
        self.options = options
        self.length = len(self.data) if length is None else length

    def encode(self):
        return HEADER.pack(self.command, self.length, self.session, self.status, self.context, self.options) + self.data

    def __repr__(self):
        return (f"Encap(command=0x{self.command:04X} length={self.length} session=0x{self.session:08X} "
                f"status=0x{self.status:04X} context={self.context.hex()} options={self.options} "
                f"data={hexs(self.data)})")


def encode(command, data=b"", session=0, context=bytes(8), status=0, options=0, length=None):
    """The bytes of one request (length defaults to len(data); give another for negative cases)."""
    return Encap(command, data, session, status, context, options, length).encode()


def decode_encap(message):
    """Decodes one whole message (header + exactly `length` bytes of data)."""
    if len(message) < HEADER_SIZE:
        raise ProtocolError(f"message of {len(message)} bytes is shorter than the header")
    command, length, session, status, context, options = HEADER.unpack_from(message)
    if len(message) != HEADER_SIZE + length:
        raise ProtocolError(f"header says {length} bytes of data, the message has {len(message) - HEADER_SIZE}")
    return Encap(command, message[HEADER_SIZE:], session, status, context, options)


def context_with_delay(max_delay_ms, tail=b"\x00" * 6):
    """A sender context whose bytes 0-1 carry ListIdentity's maximum delay (ms, little-endian)."""
    return struct.pack("<H", max_delay_ms) + tail[:6].ljust(6, b"\x00")


# ---- Common Packet Format ------------------------------------------------------------------------

def encode_cpf(items):
    out = struct.pack("<H", len(items))
    for item_type, data in items:
        out += struct.pack("<HH", item_type, len(data)) + bytes(data)
    return out


def decode_cpf(data):
    """[(type, data)] of a CPF; the item count must match the items and nothing may follow them."""
    r = Reader(data, "CPF")
    count = r.u16()
    items = []
    for _ in range(count):
        item_type = r.u16()
        length = r.u16()
        items.append((item_type, r.take(length)))
    r.end()
    return items


def send_rr_data_body(request, extra_items=(), interface_handle=0, timeout=0):
    items = [(ITEM_NULL, b""), (ITEM_UNCONNECTED_DATA, request)] + list(extra_items)
    return struct.pack("<IH", interface_handle, timeout) + encode_cpf(items)


def decode_send_rr_data(data):
    """(interface handle, timeout, items) of a SendRRData reply."""
    r = Reader(data, "SendRRData")
    handle = r.u32()
    timeout = r.u16()
    return handle, timeout, decode_cpf(r.rest())


def parse_identity_item(data):
    """The fields of a ListIdentity item (CIP Vol. 2 Table 2-4.4)."""
    r = Reader(data, "ListIdentity item")
    item = {"version": r.u16(), "sin_family": r.u16be(), "sin_port": r.u16be()}
    item["sin_addr"] = socket.inet_ntoa(r.take(4))
    item["sin_zero"] = r.take(8)
    item["vendor_id"] = r.u16()
    item["device_type"] = r.u16()
    item["product_code"] = r.u16()
    item["revision"] = (r.u8(), r.u8())
    item["status"] = r.u16()
    item["serial_number"] = r.u32()
    item["product_name"] = r.take(r.u8()).decode("latin-1")
    item["state"] = r.u8()
    r.end()
    return item


def parse_list_identity(data):
    items = decode_cpf(data)
    return [parse_identity_item(d) for t, d in items if t == ITEM_LIST_IDENTITY], items


def parse_list_services(data):
    services = []
    for item_type, d in decode_cpf(data):
        r = Reader(d, "ListServices item")
        version, flags = r.u16(), r.u16()
        name = r.take(16).rstrip(b"\x00").decode("latin-1")
        r.end()
        services.append({"type": item_type, "version": version, "flags": flags, "name": name})
    return services


# ---- EPATH and message router --------------------------------------------------------------------

def logical_segment(kind, value):
    """kind: 0 class, 1 instance, 2 member, 3 connection point, 4 attribute. 8/16/32-bit formats."""
    base = 0x20 | (kind << 2)
    if value <= 0xFF:
        return bytes([base, value])
    if value <= 0xFFFF:
        return bytes([base | 1, 0]) + struct.pack("<H", value)
    return bytes([base | 2, 0]) + struct.pack("<I", value)


def epath(class_id, instance=None, attribute=None, member=None):
    out = logical_segment(0, class_id)
    if instance is not None:
        out += logical_segment(1, instance)
    if attribute is not None:
        out += logical_segment(4, attribute)
    if member is not None:
        out += logical_segment(2, member)
    return out


def port_segment(port, link):
    """A port segment with a 1-byte link address (port < 15)."""
    return bytes([port & 0x0F, link])


def mr_request(service, path, data=b""):
    """Message router request: service, path size in words, path (padded to words), data."""
    path = bytes(path)
    if len(path) % 2:
        path += b"\x00"
    return bytes([service, len(path) // 2]) + path + bytes(data)


class MrReply:
    def __init__(self, service, general, extended, data):
        self.service = service
        self.general = general
        self.extended = extended
        self.data = data

    def raw(self):
        out = bytes([self.service, 0, self.general, len(self.extended)])
        for word in self.extended:
            out += struct.pack("<H", word)
        return out + self.data

    def __repr__(self):
        ext = " ".join(f"0x{w:04X}" for w in self.extended)
        return f"MrReply(service=0x{self.service:02X} general=0x{self.general:02X} extended=[{ext}] data={hexs(self.data)})"


def decode_mr_reply(data):
    r = Reader(data, "message router reply")
    service = r.u8()
    r.u8()  # reserved
    general = r.u8()
    size = r.u8()
    extended = [r.u16() for _ in range(size)]
    return MrReply(service, general, extended, r.rest())


def msp_request(requests):
    """Multiple Service Packet to the Message Router (class 2 instance 1)."""
    count = len(requests)
    offsets, offset = [], 2 + 2 * count
    for request in requests:
        offsets.append(offset)
        offset += len(request)
    data = struct.pack("<H", count) + b"".join(struct.pack("<H", o) for o in offsets) + b"".join(requests)
    return mr_request(MULTIPLE_SERVICE_PACKET, epath(0x02, 1), data)


def decode_msp_data(data):
    """The member replies of a Multiple Service Packet reply's data (count, offsets, replies)."""
    r = Reader(data, "MSP reply")
    count = r.u16()
    offsets = [r.u16() for _ in range(count)]
    replies = []
    for i, start in enumerate(offsets):
        stop = offsets[i + 1] if i + 1 < count else len(data)
        if not (2 + 2 * count <= start <= stop <= len(data)):
            raise ProtocolError(f"MSP reply offset {start}..{stop} outside the data ({len(data)} bytes)")
        replies.append(decode_mr_reply(data[start:stop]))
    return replies


def unconnected_send(embedded, route=b"", priority=0x0A, timeout_ticks=0xF0):
    """Unconnected_Send to the Connection Manager (class 6 instance 1) carrying `embedded`."""
    data = bytes([priority, timeout_ticks]) + struct.pack("<H", len(embedded)) + bytes(embedded)
    if len(embedded) % 2:
        data += b"\x00"
    data += bytes([len(route) // 2, 0]) + bytes(route)
    return mr_request(UNCONNECTED_SEND, epath(0x06, 1), data)


# ---- TCP client ----------------------------------------------------------------------------------

class Client:
    """One TCP connection to an EtherNet/IP target, with at most one session."""

    def __init__(self, host, port=EIP_PORT, timeout=3.0, source=None):
        self.host, self.port, self.timeout = host, port, timeout
        self.sock = socket.create_connection((host, port), timeout,
                                             source_address=(source, 0) if source else None)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.session = 0
        self.context = b"ipe-test"
        self.buffer = b""

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def local_port(self):
        return self.sock.getsockname()[1]

    # -- bytes

    def send(self, data):
        self.sock.sendall(data)

    def _fill(self, n, deadline):
        while len(self.buffer) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            ready, _, _ = select.select([self.sock], [], [], left)
            if not ready:
                return False
            try:
                chunk = self.sock.recv(65536)
            except (ConnectionResetError, ConnectionAbortedError) as error:
                raise ConnectionClosed(str(error)) from error
            if not chunk:
                raise ConnectionClosed("connection closed by the peer")
            self.buffer += chunk
        return True

    def receive(self, timeout=None):
        """The next whole message, or None when none arrives in time."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        if not self._fill(HEADER_SIZE, deadline):
            return None
        length = struct.unpack_from("<H", self.buffer, 2)[0]
        if length > MAX_REPLY_DATA:
            raise ProtocolError(f"reply announces {length} bytes of data (limit {MAX_REPLY_DATA})")
        if not self._fill(HEADER_SIZE + length, deadline):
            raise ProtocolError(f"reply cut short: {len(self.buffer)} of {HEADER_SIZE + length} bytes")
        message, self.buffer = self.buffer[:HEADER_SIZE + length], self.buffer[HEADER_SIZE + length:]
        return decode_encap(message)

    def receive_raw(self, timeout=None):
        """The next whole message as bytes (None on timeout)."""
        reply = self.receive(timeout)
        return None if reply is None else reply.encode()

    def expect_nothing(self, wait=0.3):
        """True when no byte arrives for `wait` seconds (and the connection stays open)."""
        return not self._fill(len(self.buffer) + 1, time.monotonic() + wait)

    def closed_by_peer(self, wait=None):
        """True when the peer closes the connection within `wait` seconds without sending anything."""
        try:
            got = self._fill(len(self.buffer) + 1, time.monotonic() + (self.timeout if wait is None else wait))
        except ConnectionClosed:
            return True
        if got:
            raise ProtocolError(f"expected the connection to close, got bytes {hexs(self.buffer)}")
        return False

    def request(self, command, data=b"", session=None, context=None, **kw):
        """Sends one request and returns its reply (ProtocolError when none comes)."""
        self.send(encode(command, data, self.session if session is None else session,
                         self.context if context is None else context, **kw))
        reply = self.receive()
        if reply is None:
            raise ProtocolError(f"no reply to command 0x{command:04X} within {self.timeout} s")
        return reply

    # -- encapsulation commands

    def register_session(self, version=1, options=0):
        reply = self.request(REGISTER_SESSION, struct.pack("<HH", version, options), session=0)
        if reply.status == ENCAP_SUCCESS:
            self.session = reply.session
        return reply

    def unregister_session(self):
        """Sends UnRegisterSession; the card answers nothing and closes. True when it did."""
        self.send(encode(UNREGISTER_SESSION, b"", self.session, self.context))
        closed = self.closed_by_peer()
        self.session = 0
        return closed

    def list_identity(self):
        return self.request(LIST_IDENTITY)

    def list_services(self):
        return self.request(LIST_SERVICES)

    def list_interfaces(self):
        return self.request(LIST_INTERFACES)

    def nop(self, data=b""):
        self.send(encode(NOP, data, self.session, self.context))

    def send_rr_data(self, request, extra_items=(), timeout=0):
        """(encapsulation reply, message router reply or None) of one UCMM request."""
        reply = self.request(SEND_RR_DATA, send_rr_data_body(request, extra_items, timeout=timeout))
        if reply.status != ENCAP_SUCCESS:
            return reply, None
        _, _, items = decode_send_rr_data(reply.data)
        if len(items) < 2 or items[0] != (ITEM_NULL, b"") or items[1][0] != ITEM_UNCONNECTED_DATA:
            raise ProtocolError(f"SendRRData reply items {items}")
        return reply, decode_mr_reply(items[1][1])

    def cip(self, request):
        """The message router reply to one request (ProtocolError on an encapsulation error)."""
        reply, mr = self.send_rr_data(request)
        if mr is None:
            raise ProtocolError(f"SendRRData answered with encapsulation status 0x{reply.status:04X}")
        return mr

    # -- services

    def get_attribute_single(self, class_id, instance, attribute):
        return self.cip(mr_request(GET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute)))

    def get_attributes_all(self, class_id, instance):
        return self.cip(mr_request(GET_ATTRIBUTES_ALL, epath(class_id, instance)))

    def set_attribute_single(self, class_id, instance, attribute, value):
        return self.cip(mr_request(SET_ATTRIBUTE_SINGLE, epath(class_id, instance, attribute), value))

    def get_attribute_list(self, class_id, instance, attributes):
        data = struct.pack("<H", len(attributes)) + b"".join(struct.pack("<H", a) for a in attributes)
        return self.cip(mr_request(GET_ATTRIBUTE_LIST, epath(class_id, instance), data))

    def get_and_clear(self, class_id, instance, attribute):
        return self.cip(mr_request(GET_AND_CLEAR, epath(class_id, instance, attribute)))

    def reset(self, reset_type=None):
        return self.cip(mr_request(RESET, epath(0x01, 1), b"" if reset_type is None else bytes([reset_type])))

    def multiple_service_packet(self, requests):
        """(MSP reply, member replies or [] when the reply has no member data)."""
        reply = self.cip(msp_request(requests))
        members = decode_msp_data(reply.data) if reply.general in (0x00, 0x1E) and reply.data else []
        return reply, members

    def unconnected_send(self, embedded, route=b""):
        return self.cip(unconnected_send(embedded, route))


# ---- UDP -----------------------------------------------------------------------------------------

def udp_exchange(host, request, port=EIP_PORT, broadcast=False, wait=1.0, source=None, max_replies=None,
                 bind_port=0):
    """Sends one datagram and collects replies for `wait` seconds: [(seconds after sending, (ip, port), Encap)].
    Stops early after max_replies. A datagram that does not decode raises ProtocolError."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        if broadcast:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_BROADCAST, 1)
        sock.bind((source or "", bind_port))
        sent = time.monotonic()
        sock.sendto(request, (host, port))
        replies = []
        deadline = sent + wait
        while max_replies is None or len(replies) < max_replies:
            left = deadline - time.monotonic()
            if left <= 0:
                break
            ready, _, _ = select.select([sock], [], [], left)
            if not ready:
                break
            data, peer = sock.recvfrom(65535)
            replies.append((time.monotonic() - sent, peer, decode_encap(data)))
        return replies


def list_identity_udp(host, port=EIP_PORT, broadcast=False, max_delay_ms=0, wait=None, source=None,
                      max_replies=None):
    """ListIdentity over UDP. A broadcast is answered after a random delay up to the max delay in the
    sender context (0 means 2000 ms): the default wait covers it."""
    if wait is None:
        wait = ((max_delay_ms or 2000) / 1000.0 + 1.0) if broadcast else 1.0
    context = context_with_delay(max_delay_ms, b"ipe-li")
    return udp_exchange(host, encode(LIST_IDENTITY, context=context), port, broadcast, wait, source, max_replies)


# ---- CLI -----------------------------------------------------------------------------------------

def number(text):
    return int(text, 0)


def print_reply(reply):
    print(reply)
    if reply.status != ENCAP_SUCCESS or not reply.data:
        return
    if reply.command == LIST_IDENTITY:
        for item in parse_list_identity(reply.data)[0]:
            print("  " + " ".join(f"{k}={v}" for k, v in item.items() if k != "sin_zero"))
    elif reply.command == LIST_SERVICES:
        for service in parse_list_services(reply.data):
            print(f"  {service}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0], usage=__doc__.split("usage: ")[1])
    parser.add_argument("--host", required=True)
    parser.add_argument("--port", type=int, default=EIP_PORT)
    parser.add_argument("--timeout", type=float, default=3.0)
    parser.add_argument("--source", help="local address to send from")
    parser.add_argument("--udp", action="store_true", help="discovery commands over unicast UDP")
    parser.add_argument("--broadcast", action="store_true", help="discovery commands to a broadcast address")
    parser.add_argument("--max-delay", type=int, default=0, help="ListIdentity max delay in ms (sender context)")
    parser.add_argument("command")
    parser.add_argument("args", nargs="*")
    a = parser.parse_args(argv)
    discovery = {"list-identity": LIST_IDENTITY, "list-services": LIST_SERVICES,
                 "list-interfaces": LIST_INTERFACES}
    arity = {"get": (3, 3), "get-all": (2, 2), "get-clear": (3, 3), "get-list": (3, 99), "set": (4, 99),
             "reset": (0, 1), "cip": (1, 99), "ucs": (1, 2), "msp": (1, 99), "raw": (1, 99)}
    if a.command in arity and not arity[a.command][0] <= len(a.args) <= arity[a.command][1]:
        parser.error(f"{a.command}: wrong number of arguments (see the usage)")
    try:
        if a.command in discovery and (a.udp or a.broadcast):
            if a.command == "list-identity":
                replies = list_identity_udp(a.host, a.port, a.broadcast, a.max_delay, source=a.source)
            else:
                replies = udp_exchange(a.host, encode(discovery[a.command]), a.port, a.broadcast, a.timeout, a.source)
            for delay, peer, reply in replies:
                print(f"from {peer[0]}:{peer[1]} after {delay * 1000:.0f} ms:")
                print_reply(reply)
            return 0 if replies else 1
        if a.command == "raw":
            with Client(a.host, a.port, a.timeout, a.source) as c:
                c.send(unhex(" ".join(a.args)))
                while True:
                    reply = c.receive()
                    if reply is None:
                        break
                    print(hexs(reply.encode()))
            return 0
        with Client(a.host, a.port, a.timeout, a.source) as c:
            if a.command in discovery:
                print_reply(c.request(discovery[a.command]))
                return 0
            if a.command == "nop":
                c.nop(unhex(" ".join(a.args)))
                print("no reply expected:", "none came" if c.expect_nothing() else "a reply came!")
                return 0
            reply = c.register_session()
            print(f"RegisterSession: status 0x{reply.status:04X} handle 0x{reply.session:08X}")
            if reply.status != ENCAP_SUCCESS:
                return 1
            n = [number(x) for x in a.args] if a.command in ("get", "get-all", "get-list", "get-clear", "reset") else []
            if a.command == "register":
                print("UnRegisterSession: connection closed" if c.unregister_session() else "still open")
                return 0
            if a.command == "get":
                mr = c.get_attribute_single(*n)
            elif a.command == "get-all":
                mr = c.get_attributes_all(*n)
            elif a.command == "get-list":
                mr = c.get_attribute_list(n[0], n[1], n[2:])
            elif a.command == "get-clear":
                mr = c.get_and_clear(*n)
            elif a.command == "reset":
                mr = c.reset(n[0] if n else None)
            elif a.command == "set":
                mr = c.set_attribute_single(number(a.args[0]), number(a.args[1]), number(a.args[2]),
                                            unhex(" ".join(a.args[3:])))
            elif a.command == "cip":
                mr = c.cip(unhex(" ".join(a.args)))
            elif a.command == "ucs":
                mr = c.unconnected_send(unhex(a.args[0]), unhex(a.args[1]) if len(a.args) > 1 else b"")
            elif a.command == "msp":
                mr, members = c.multiple_service_packet([unhex(x) for x in a.args])
                print(mr)
                for member in members:
                    print("  ", member)
                return 0 if mr.general == 0 else 1
            else:
                parser.error(f"unknown command {a.command}")
            print(mr)
            return 0 if mr.general == 0 else 1
    except (OSError, ProtocolError, ConnectionClosed) as error:
        print(f"eip_originator: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
