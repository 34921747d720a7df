"""Message router and object cases (docs/conformance.md "EtherNet/IP": CIP). Each row is one request over
SendRRData on the suite's shared session and the exact message router reply; the order of checks is
docs/ethernetip.md "Error order", the object rules its "Objects" and docs/drive-objects.md.

No row carries a valid value for a setting that matters: a row that should fail must not change the card
(the one valid Set pair, DHCP and back for the 0x0C case, restores what it changed).
"""
import socket
import struct

from conformance import Case
from eip_originator import epath, mr_request, msp_request, port_segment, unconnected_send
from eip_suite import H, Msg, OWN, SEND_RR_DATA, rr, rr_reply

GET, GET_ALL, SET, RESET, GET_CLEAR = 0x0E, 0x01, 0x10, 0x05, 0x4C
IDENTITY, ROUTER, ASSEMBLY, CM, PORT, TCPIP, LINK = 0x01, 0x02, 0x04, 0x06, 0xF4, 0xF5, 0xF6
MOTOR, SUPERVISOR, DRIVE, PARAM64, PARAM65 = 0x28, 0x29, 0x2A, 0x64, 0x65


def status(service, general):
    """An error reply without additional status or data."""
    return bytes([service | 0x80, 0, general, 0])


def svc(service, class_id, instance, attribute=None, data=b"", member=None):
    return mr_request(service, epath(class_id, instance, attribute, member), H(data))


def get(c, i, a, data=b""):
    return svc(GET, c, i, a, data)


def set_(c, i, a, data):
    return svc(SET, c, i, a, data)


def ip_le(text):
    return socket.inet_aton(text)[::-1]


def cip_string(text):
    data = struct.pack("<H", len(text)) + text.encode("latin-1")
    return data + (b"\x00" if len(text) % 2 else b"")


def interface_config(ip, mask, gateway, ns1="0.0.0.0", ns2="0.0.0.0", domain=""):
    """TCP/IP attribute 5: address, mask, gateway, two name servers (UDINT), domain name (STRING)."""
    return b"".join(ip_le(a) for a in (ip, mask, gateway, ns1, ns2)) + cip_string(domain)


def rows_unsupported():
    s = "service not supported (0x08) before path and data"
    member = epath(IDENTITY, 1, 9) + bytes([0x28, 0x01])
    return s, [
        ("Set on Identity (no Set service)", set_(IDENTITY, 1, 1, "79 01"), status(SET, 0x08)),
        ("Set on Identity, unknown attribute 99", set_(IDENTITY, 1, 99, "00"), status(SET, 0x08)),
        ("Set_Attributes_All 0x02 on Identity", svc(0x02, IDENTITY, 1, data="00 00"), status(0x02, 0x08)),
        ("Get_Attribute_List 0x03 on Identity (no object offers it)", svc(0x03, IDENTITY, 1, data="01 00 01 00"),
         status(0x03, 0x08)),
        ("Set_Attribute_List 0x04 on TCP/IP", svc(0x04, TCPIP, 1, data="01 00 08 00 01"), status(0x04, 0x08)),
        ("Start 0x06 on Identity", svc(0x06, IDENTITY, 1), status(0x06, 0x08)),
        ("Stop 0x07 on Identity", svc(0x07, IDENTITY, 1), status(0x07, 0x08)),
        ("Create 0x08 on the Assembly class", svc(0x08, ASSEMBLY, 0, data="00 00"), status(0x08, 0x08)),
        ("Delete 0x09 on Assembly 20", svc(0x09, ASSEMBLY, 20), status(0x09, 0x08)),
        ("Apply_Attributes 0x0D on TCP/IP", svc(0x0D, TCPIP, 1), status(0x0D, 0x08)),
        ("Restore 0x15 on Identity", svc(0x15, IDENTITY, 1), status(0x15, 0x08)),
        ("Save 0x16 on TCP/IP", svc(0x16, TCPIP, 1), status(0x16, 0x08)),
        ("Get_Member 0x18 with a member segment and data", mr_request(0x18, member, H("FF")), status(0x18, 0x08)),
        ("Set_Member 0x19 on attribute 99 with a member and data", mr_request(0x19, epath(IDENTITY, 1, 99) +
                                                                             bytes([0x28, 0x01]), H("01 02")),
         status(0x19, 0x08)),
        ("Insert_Member 0x1A", mr_request(0x1A, member), status(0x1A, 0x08)),
        ("Remove_Member 0x1B", mr_request(0x1B, member), status(0x1B, 0x08)),
        ("class-level Reset on Identity", svc(RESET, IDENTITY, 0), status(RESET, 0x08)),
        ("class-level Set on TCP/IP", set_(TCPIP, 0, 1, "01 00"), status(SET, 0x08)),
        ("class-level Get_and_Clear on Ethernet Link", svc(GET_CLEAR, LINK, 0, 4), status(GET_CLEAR, 0x08)),
        ("class-level Set on Assembly", set_(ASSEMBLY, 0, 1, "02 00"), status(SET, 0x08)),
        ("Get_Attributes_All on the Message Router instance", svc(GET_ALL, ROUTER, 1), status(GET_ALL, 0x08)),
        ("Get_Attributes_All on the Message Router class", svc(GET_ALL, ROUTER, 0), status(GET_ALL, 0x08)),
        ("Set on the Message Router", set_(ROUTER, 1, 2, "10 00"), status(SET, 0x08)),
        ("Get_and_Clear on Identity", svc(GET_CLEAR, IDENTITY, 1, 1), status(GET_CLEAR, 0x08)),
        ("Get_Attributes_All on Assembly 20", svc(GET_ALL, ASSEMBLY, 20), status(GET_ALL, 0x08)),
        ("Set on Port", set_(PORT, 1, 7, "00 00"), status(SET, 0x08)),
        ("object-specific service 0x4B on TCP/IP", svc(0x4B, TCPIP, 1), status(0x4B, 0x08)),
        ("Forward_Open to Identity", svc(0x54, IDENTITY, 1, data=bytes(36)), status(0x54, 0x08)),
        ("Forward_Open to the Connection Manager class", svc(0x54, CM, 0, data=bytes(36)), status(0x54, 0x08)),
        ("Get_Attributes_All on the Connection Manager", svc(GET_ALL, CM, 1), status(GET_ALL, 0x08)),
        ("Set on the Connection Manager", set_(CM, 1, 1, "00 00"), status(SET, 0x08)),
        ("Multiple Service Packet to Identity", svc(0x0A, IDENTITY, 1, data="01 00 04 00" + get(1, 1, 1).hex()),
         status(0x0A, 0x08)),
        ("Multiple Service Packet to the Message Router class", svc(0x0A, ROUTER, 0, data="00 00"), status(0x0A, 0x08)),
        ("Multiple Service Packet to a Message Router attribute", svc(0x0A, ROUTER, 1, 1, "00 00"), status(0x0A, 0x08)),
        ("Unconnected_Send to Identity", svc(0x52, IDENTITY, 1, data="0A F0 00 00 00 00"), status(0x52, 0x08)),
        ("Unconnected_Send to the Connection Manager class", svc(0x52, CM, 0, data="0A F0 00 00 00 00"),
         status(0x52, 0x08)),
        ("a reply code (0x8E) as request", mr_request(0x8E, epath(IDENTITY, 1, 1)),
         status(0x8E, 0x08)),
        ("a reply code with an invalid segment: 0x08 first", H("8E 01 43 01"), status(0x8E, 0x08)),
        ("Get_Attributes_All on the Control Supervisor (none, §4.6)", svc(GET_ALL, SUPERVISOR, 1), status(GET_ALL, 0x08)),
        ("Get_Attributes_All on the AC/DC Drive", svc(GET_ALL, DRIVE, 1), status(GET_ALL, 0x08)),
        ("class-level Set on Parameter 0x65", set_(PARAM65, 0, 1, "01 00"), status(SET, 0x08)),
        ("Get_Attributes_All on a parameter instance", svc(GET_ALL, PARAM65, 0x0009), status(GET_ALL, 0x08)),
    ]


def rows_path():
    s = "path segment error (0x04)"
    p = status(GET, 0x04)
    return s, [
        ("request of the service byte only", H("0E"), p),
        ("path size 0", H("0E 00"), p),
        ("path size larger than the request", H("0E 03 20 01 24"), p),
        ("path size 255 words on a 6-byte path (OpENer #563)", H("0E FF 20 01 24 01 30 01"), p),
        ("class without an instance", H("0E 01 20 01"), p),
        ("instance before the class", H("0E 02 24 01 20 01"), p),
        ("attribute before the instance", H("0E 03 20 01 30 01 24 01"), p),
        ("two class segments", H("0E 03 20 01 20 01 24 01"), p),
        ("two instance segments", H("0E 04 20 01 24 01 24 01 30 01"), p),
        ("two attribute segments", H("0E 04 20 01 24 01 30 01 30 01"), p),
        ("attribute after a member", H("0E 04 20 01 24 01 28 01 30 01"), p),
        ("reserved logical format 3", H("0E 02 23 01 24 01"), p),
        ("16-bit class segment cut by the path size", H("0E 01 21 00"), p),
        ("32-bit instance segment cut", H("0E 03 20 01 26 00 01 00"), p),
        ("32-bit class segment (only 8/16-bit are defined for a class)", H("0E 04 22 00 01 00 00 00 24 01"), p),
        ("32-bit attribute segment (only 8/16-bit are defined)", H("0E 05 20 01 24 01 32 00 01 00 00 00"), p),
        ("electronic key in a request path", H("0E 08 34 04 79 01 02 00 00 7D 01 08 20 01 24 01 30 01"), p),
        ("service ID segment", H("0E 03 38 0E 20 01 24 01"), p),
        ("extended logical segment", H("0E 03 3C 00 20 01 24 01"), p),
        ("network segment", H("0E 03 43 01 20 01 24 01"), p),
        ("ANSI symbolic segment", H("0E 05 91 03 61 62 63 00 20 01 24 01"), p),
        ("simple data segment", H("0E 03 80 00 20 01 24 01"), p),
        ("port segment in front of the class", H("0E 03 01 00 20 01 24 01"), p),
        ("reserved segment type 0xE0", H("0E 03 E0 00 20 01 24 01"), p),
        ("ANSI symbol running past the path", H("0E 02 91 09 61 62"), p),
    ]


def rows_class_instance_attribute():
    c, i, a = "class unknown (0x05)", "instance unknown (0x16)", "attribute unknown (0x14)"
    out = []
    for class_id in (0x00, 0x03, 0x05, 0x07, 0x38, 0x43, 0x70, 0xFF, 0x0300, 0xFFFF):
        out.append((c, f"class 0x{class_id:02X}", get(class_id, 1, 1), status(GET, 0x05)))
    out.append((c, "Set on class 0x70 (the class is judged before the service)", set_(0x70, 1, 1, "00"),
                status(SET, 0x05)))
    out.append((c, "a member segment (no object has members)", svc(GET, IDENTITY, 1, 1, member=1), status(GET, 0x05)))
    for class_id, instance, what in ((IDENTITY, 2, "Identity 2"), (IDENTITY, 0xFFFF, "Identity 0xFFFF (16-bit)"),
                                     (IDENTITY, 0x10000, "Identity 0x10000 (32-bit)"), (ROUTER, 2, "Message Router 2"),
                                     (ASSEMBLY, 103, "Assembly 103"), (ASSEMBLY, 0xFFFF, "Assembly 0xFFFF"),
                                     (CM, 2, "Connection Manager 2"), (PORT, 2, "Port 2"), (TCPIP, 2, "TCP/IP 2"),
                                     (LINK, 3, "Ethernet Link 3"), (MOTOR, 2, "Motor Data 2"),
                                     (SUPERVISOR, 2, "Control Supervisor 2"), (DRIVE, 2, "AC/DC Drive 2"),
                                     (0x48, 2, "QoS 2")):
        out.append((i, what, get(class_id, instance, 1), status(GET, 0x16)))
    out += [
        (i, "Set on Identity 2 (the instance is judged before the service)", set_(IDENTITY, 2, 1, "00"),
         status(SET, 0x16)),
        (i, "File 1 (the EDS is instance 0xC8, the only one)", get(0x37, 1, 1), status(GET, 0x16)),
        (i, "Parameter 0x0F 187 (the parameter table has 186 rows)", get(0x0F, 187, 1),
         status(GET, 0x16)),
        (i, "parameter 0x65 instance 000A (A-F endings are no registers)", get(PARAM65, 0x000A, 3), status(GET, 0x16)),
        (i, "parameter 0x65 instance 0001 (the inverter has none)", get(PARAM65, 0x0001, 3), status(GET, 0x16)),
        (i, "parameter 0x64 instance 0x1000 (outside its windows)", get(PARAM64, 0x1000, 3), status(GET, 0x16)),
        (i, "parameter 0x64 instance 0x4001 (number 0001)", get(PARAM64, 0x4001, 3), status(GET, 0x16)),
        (i, "parameter 0x65 instance 0x10000", get(PARAM65, 0x10000, 3), status(GET, 0x16)),
    ]
    for class_id, instance, attribute, what in ((IDENTITY, 1, 8, "Identity 8"), (IDENTITY, 1, 0xFF, "Identity 255"),
                                                (IDENTITY, 1, 0x100, "Identity 0x100 (16-bit)"),
                                                (IDENTITY, 0, 5, "Identity class attribute 5"),
                                                (ROUTER, 1, 1, "Message Router 1"), (TCPIP, 1, 7, "TCP/IP 7"),
                                                (TCPIP, 1, 12, "TCP/IP 12"), (TCPIP, 1, 13, "TCP/IP 13"),
                                                (LINK, 1, 11, "Ethernet Link 11"), (PORT, 1, 5, "Port 5"),
                                                (PORT, 0, 10, "Port class attribute 10"), (ASSEMBLY, 20, 1, "Assembly 20 attribute 1"),
                                                (CM, 1, 99, "Connection Manager 99"), (CM, 0, 99, "Connection Manager class 99"),
                                                (SUPERVISOR, 1, 99, "Control Supervisor 99"),
                                                (PARAM65, 0x0009, 1, "parameter acc attribute 1 (only 3)")):
        out.append((a, what, get(class_id, instance, attribute), status(GET, 0x14)))
    out += [
        (a, "Get_Attribute_Single without an attribute", svc(GET, IDENTITY, 1), status(GET, 0x14)),
        (a, "Get_and_Clear of Ethernet Link attribute 1", svc(GET_CLEAR, LINK, 1, 1), status(GET_CLEAR, 0x14)),
        (a, "Get_and_Clear without an attribute", svc(GET_CLEAR, LINK, 1), status(GET_CLEAR, 0x14)),
        (a, "Set of TCP/IP without an attribute", svc(SET, TCPIP, 1, data="01"), status(SET, 0x14)),
        (a, "Set of TCP/IP attribute 7", set_(TCPIP, 1, 7, bytes(6)), status(SET, 0x14)),
        (a, "Set of TCP/IP attribute 99", set_(TCPIP, 1, 99, "00"), status(SET, 0x14)),
    ]
    return out


def rows_not_settable():
    s = "attribute not settable (0x0E)"
    rows = [(f"TCP/IP {n}", set_(TCPIP, 1, n, d)) for n, d in ((1, bytes(4)), (2, bytes(4)),
                                                                (4, "02 00 20 F6 24 01"))]
    rows += [(f"Ethernet Link {n}", set_(LINK, 1, n, d)) for n, d in ((1, "64 00 00 00"), (2, bytes(4)), (3, bytes(6)),
                                                                       (4, bytes(48)), (5, bytes(48)), (7, "02"),
                                                                       (8, "01"), (9, "01"),
                                                                       (10, "04 4C 65 66 74"))]
    rows += [("Assembly 20 attribute 4 (size)", set_(ASSEMBLY, 20, 4, "04 00")),
             ("Assembly 70 data (an input)", set_(ASSEMBLY, 70, 3, bytes(4))),
             ("parameter FE00 (a monitor)", set_(PARAM65, 0xFE00, 3, "00 00")),
             ("parameter FD01 (a monitor)", set_(PARAM65, 0xFD01, 3, "00 00"))]
    return s, [(name, request, status(SET, 0x0E)) for name, request in rows]


def rows_data_size():
    s = "too much / not enough data (0x15 / 0x13)"
    long_, short = 0x15, 0x13
    rows = [
        ("Get with a data byte", get(IDENTITY, 1, 1, "00"), status(GET, long_)),
        ("class-level Get with a data byte", get(IDENTITY, 0, 1, "00"), status(GET, long_)),
        ("Get_Attributes_All with data", svc(GET_ALL, IDENTITY, 1, data="00"), status(GET_ALL, long_)),
        ("class-level Get_Attributes_All with data", svc(GET_ALL, IDENTITY, 0, data="00"), status(GET_ALL, long_)),
        ("Get_and_Clear with data", svc(GET_CLEAR, LINK, 1, 4, "00"), status(GET_CLEAR, long_)),
        ("Reset with 2 bytes", svc(RESET, IDENTITY, 1, data="00 00"), status(RESET, long_)),
        ("parameter Get with data", get(PARAM65, 0x0009, 3, "00"), status(GET, long_)),
    ]
    sets = [
        ("TCP/IP 3, 3 bytes", TCPIP, 1, 3, "00 00 00", short), ("TCP/IP 3, 5 bytes", TCPIP, 1, 3, bytes(5), long_),
        ("TCP/IP 3, no data", TCPIP, 1, 3, b"", short),
        ("TCP/IP 5, 19 bytes", TCPIP, 1, 5, bytes(19), short),
        ("TCP/IP 5, domain name length 10 with 4 characters", TCPIP, 1, 5, bytes(20) + H("0A 00") + b"abcd", short),
        ("TCP/IP 5, a byte after the domain name", TCPIP, 1, 5, bytes(22) + b"\x00", long_),
        ("TCP/IP 6, length 5 with 3 characters", TCPIP, 1, 6, H("05 00") + b"abc", short),
        ("TCP/IP 6, odd name without its pad byte", TCPIP, 1, 6, H("03 00") + b"abc", short),
        ("TCP/IP 6, a byte after the pad", TCPIP, 1, 6, cip_string("abc") + b"\x00", long_),
        ("TCP/IP 6, length byte only", TCPIP, 1, 6, b"\x03", short),
        ("TCP/IP 6, length 0xFFFF with 4 characters (OpENer PR #586)", TCPIP, 1, 6, H("FF FF") + b"abcd", short),
        ("TCP/IP 5, domain name length 0xFFFF", TCPIP, 1, 5, bytes(20) + H("FF FF") + b"ab", short),
        ("TCP/IP 8 (TTL), no data", TCPIP, 1, 8, b"", short), ("TCP/IP 8 (TTL), 2 bytes", TCPIP, 1, 8, "01 00", long_),
        ("TCP/IP 9, 7 bytes", TCPIP, 1, 9, bytes(7), short), ("TCP/IP 9, 9 bytes", TCPIP, 1, 9, bytes(9), long_),
        ("TCP/IP 10, no data", TCPIP, 1, 10, b"", short), ("TCP/IP 10, 2 bytes", TCPIP, 1, 10, "00 00", long_),
        ("TCP/IP 11, 34 bytes", TCPIP, 1, 11, bytes(34), short), ("TCP/IP 11, 36 bytes", TCPIP, 1, 11, bytes(36), long_),
        ("Ethernet Link 6, 3 bytes", LINK, 1, 6, "01 00 00", short), ("Ethernet Link 6, 5 bytes", LINK, 1, 6, bytes(5), long_),
        ("Ethernet Link 6, no data", LINK, 2, 6, b"", short),
        ("Assembly 20 data, 3 bytes", ASSEMBLY, 20, 3, bytes(3), short),
        ("Assembly 20 data, 5 bytes", ASSEMBLY, 20, 3, bytes(5), long_),
        ("parameter acc, 1 byte", PARAM65, 0x0009, 3, "32", short),
        ("parameter acc, 3 bytes", PARAM65, 0x0009, 3, "32 00 00", long_),
        ("Control Supervisor Run1, 2 bytes", SUPERVISOR, 1, 3, "00 00", long_),
        ("Control Supervisor Run1, no data", SUPERVISOR, 1, 3, b"", short),
    ]
    rows += [(name, set_(c, i, a, d), status(SET, code)) for name, c, i, a, d, code in sets]
    return s, rows


def rows_values():
    s = "invalid value (0x09, 0x20)"
    v = status(SET, 0x09)
    cfg = interface_config
    rows = [
        ("TCP/IP 3 = 3", set_(TCPIP, 1, 3, "03 00 00 00"), v),
        ("TCP/IP 3 with the DNS bit (the card has no resolver)", set_(TCPIP, 1, 3, "10 00 00 00"), v),
        ("TCP/IP 3 = 0x12", set_(TCPIP, 1, 3, "12 00 00 00"), v),
        ("TCP/IP 3 with bit 31", set_(TCPIP, 1, 3, "00 00 00 80"), v),
        ("TCP/IP 5 mask with a hole", set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.0.255.0", "192.168.0.1")), v),
        ("TCP/IP 5 the network address", set_(TCPIP, 1, 5, cfg("192.168.0.0", "255.255.255.0", "0.0.0.0")), v),
        ("TCP/IP 5 the broadcast address", set_(TCPIP, 1, 5, cfg("192.168.0.255", "255.255.255.0", "0.0.0.0")), v),
        ("TCP/IP 5 mask /32", set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.255", "0.0.0.0")), v),
        ("TCP/IP 5 mask /31 (one host bit)", set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.254", "0.0.0.0")), v),
        ("TCP/IP 5 gateway on another subnet", set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.0", "192.168.1.1")), v),
        ("TCP/IP 5 gateway = the address itself", set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.0", "192.168.0.10")), v),
        ("TCP/IP 5 multicast address", set_(TCPIP, 1, 5, cfg("224.0.0.10", "255.255.255.0", "0.0.0.0")), v),
        ("TCP/IP 5 address 0 with a mask", set_(TCPIP, 1, 5, cfg("0.0.0.0", "255.255.255.0", "0.0.0.0")), v),
        ("TCP/IP 5 name server 255.255.255.255",
         set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.0", "192.168.0.1", "255.255.255.255")), v),
        ("TCP/IP 5 domain name of 49 characters",
         set_(TCPIP, 1, 5, cfg("192.168.0.10", "255.255.255.0", "192.168.0.1", domain="d" * 49)), v),
        ("TCP/IP 6 host name with a space", set_(TCPIP, 1, 6, cip_string("a b")), v),
        ("TCP/IP 6 host name of 17 characters (never cut)", set_(TCPIP, 1, 6, cip_string("A" * 17)), v),
        ("TCP/IP 6 host name with '_'", set_(TCPIP, 1, 6, cip_string("a_b")), v),
        ("TCP/IP 6 host name with a non-ASCII byte", set_(TCPIP, 1, 6, cip_string("ab\xe9")), v),
        ("TCP/IP 8 TTL 0", set_(TCPIP, 1, 8, "00"), v),
        ("TCP/IP 9 allocation control 2", set_(TCPIP, 1, 9, "02 00 01 00 00 01 C0 EF"), v),
        ("TCP/IP 9 allocation 1 with 0 groups", set_(TCPIP, 1, 9, "01 00 00 00 00 01 C0 EF"), v),
        ("TCP/IP 9 allocation 0 with a count", set_(TCPIP, 1, 9, "00 00 05 00 00 00 00 00"), v),
        ("TCP/IP 9 start 192.168.1.1 (not multicast)", set_(TCPIP, 1, 9, "01 00 01 00 01 01 A8 C0"), v),
        ("TCP/IP 9 start 224.0.0.5 (link-local block)", set_(TCPIP, 1, 9, "01 00 01 00 05 00 00 E0"), v),
        ("TCP/IP 9 range past 239.255.255.255 (257 groups from .0)", set_(TCPIP, 1, 9, "01 00 01 01 00 FF FF EF"), v),
        ("TCP/IP 9 reserved byte 1", set_(TCPIP, 1, 9, "01 01 01 00 00 01 C0 EF"), v),
        ("TCP/IP 10 SelectAcd 2", set_(TCPIP, 1, 10, "02"), v),
        ("TCP/IP 10 SelectAcd 0xFF", set_(TCPIP, 1, 10, "FF"), v),
        ("TCP/IP 11 last conflict not all zero", set_(TCPIP, 1, 11, H("00 00 00 01") + bytes(31)), v),
        ("Ethernet Link 6 auto-negotiate with a forced speed", set_(LINK, 2, 6, "01 00 64 00"), v),
        ("Ethernet Link 6 forced 1000 Mbit/s", set_(LINK, 1, 6, "02 00 E8 03"), v),
        ("Ethernet Link 6 forced speed 0", set_(LINK, 1, 6, "02 00 00 00"), v),
        ("Ethernet Link 6 reserved control bit 2", set_(LINK, 1, 6, "05 00 00 00"), v),
        ("Identity Reset type 2", svc(RESET, IDENTITY, 1, data="02"), status(RESET, 0x20)),
        ("Identity Reset type 0xFF", svc(RESET, IDENTITY, 1, data="FF"), status(RESET, 0x20)),
        ("parameter acc = 0 (range 1-60000)", set_(PARAM65, 0x0009, 3, "00 00"), v),
        ("Control Supervisor Run1 = 2 (BOOL)", set_(SUPERVISOR, 1, 3, "02"), v),
        ("AC/DC Drive PowerScaling = 1", set_(DRIVE, 1, 26, "01 00"), v),
    ]
    return s, rows


def rows_msp():
    s = "Multiple Service Packet"
    g = get(IDENTITY, 1, 1)
    innermost = msp_request([g])
    middle = msp_request([innermost])
    return s, [
        ("without a count: 0x13", svc(0x0A, ROUTER, 1), status(0x0A, 0x13)),
        ("count 2 with one offset: 0x13", svc(0x0A, ROUTER, 1, data="02 00 06 00"), status(0x0A, 0x13)),
        ("an offset into the offset table: 0x13", svc(0x0A, ROUTER, 1, data="01 00 02 00" + g.hex()), status(0x0A, 0x13)),
        ("an offset past the end: 0x13", svc(0x0A, ROUTER, 1, data="01 00 0D 00" + g.hex()), status(0x0A, 0x13)),
        ("an offset at the end (an empty member): 0x13", svc(0x0A, ROUTER, 1, data="01 00 0C 00" + g.hex()),
         status(0x0A, 0x13)),
        ("an offset into the middle of the member: that part answers 0x04",
         svc(0x0A, ROUTER, 1, data="01 00 0A 00" + g.hex()), H("8A 00 1E 00 01 00 04 00 B0 00 04 00")),
        ("two equal offsets: 0x20", svc(0x0A, ROUTER, 1, data="02 00 06 00 06 00" + g.hex() * 2), status(0x0A, 0x20)),
        ("offsets going down: 0x20", svc(0x0A, ROUTER, 1, data="02 00 0E 00 06 00" + g.hex() * 2), status(0x0A, 0x20)),
        ("a failing member: 0x1E with every reply", msp_request([g, get(IDENTITY, 1, 9)]),
         H("8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 79 01 8E 00 14 00")),
        ("a member of one byte: 0x1E, the member 0x04", msp_request([g, H("0E")]),
         H("8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 79 01 8E 00 04 00")),
        ("a member with an unsupported service: 0x1E, the member 0x08", msp_request([set_(IDENTITY, 1, 1, "00")]),
         H("8A 00 1E 00 01 00 04 00 90 00 08 00")),
        ("nested three deep: the innermost 0x02", msp_request([middle]),
         H("8A 00 1E 00 01 00 04 00 8A 00 1E 00 01 00 04 00 8A 00 02 00")),
        ("count 0: answered with count 0", svc(0x0A, ROUTER, 1, data="00 00"), H("8A 00 00 00 00 00")),
        ("60 Get_Attributes_All whose replies cannot fit in one reply: 0x11",
         msp_request([svc(GET_ALL, IDENTITY, 1)] * 60), status(0x0A, 0x11)),
    ]


def rows_unconnected_send():
    s = "Unconnected_Send"
    g = get(IDENTITY, 1, 1)
    ucs = lambda data: svc(0x52, CM, 1, data=data)  # noqa: E731
    return s, [
        ("route to port 1 slot 3: 0x01/0x0312", unconnected_send(g, port_segment(1, 3)), H("D2 00 01 01 12 03 01 00")),
        ("route out of port 2: 0x01/0x0312", unconnected_send(g, port_segment(2, 5)), H("D2 00 01 01 12 03 01 00")),
        ("route via port 3: 0x01/0x0311", unconnected_send(g, port_segment(1, 0) + port_segment(3, 1)),
         H("D2 00 01 01 11 03 02 00")),
        ("route via extended port 18: 0x01/0x0311", unconnected_send(g, H("0F 12 00 00")), H("D2 00 01 01 11 03 02 00")),
        ("port 1 with a 2-byte link address: 0x01/0x0312", unconnected_send(g, H("11 02 00 00")),
         H("D2 00 01 01 12 03 02 00")),
        ("route that is not a port segment: 0x01/0x0315", unconnected_send(g, H("20 01")), H("D2 00 01 01 15 03 01 00")),
        ("route with a cut port segment: 0x01/0x0315", unconnected_send(g, H("11 05")), H("D2 00 01 01 15 03 01 00")),
        ("cut after the embedded size: 0x13", ucs("0A F0 08"), status(0x52, 0x13)),
        ("embedded size 0: 0x13", ucs("0A F0 00 00 00 00"), status(0x52, 0x13)),
        ("embedded size past the data: 0x13", ucs("0A F0 20 00" + g.hex() + "00 00"), status(0x52, 0x13)),
        ("route size past the data: 0x13", ucs("0A F0 08 00" + g.hex() + "02 00 01 00"), status(0x52, 0x13)),
        ("no route size: 0x13", ucs("0A F0 08 00" + g.hex()), status(0x52, 0x13)),
        ("a byte after the route: 0x15", unconnected_send(g, port_segment(1, 0)) + b"\x00", status(0x52, 0x15)),
        ("an embedded error is the reply", unconnected_send(get(IDENTITY, 1, 8)), status(GET, 0x14)),
        ("nested three deep: 0x02", unconnected_send(unconnected_send(msp_request([g]))), status(0x0A, 0x02)),
    ]


def rows_state_conflict():
    s = "state conflict (0x0C)"
    valid = interface_config("192.168.0.10", "255.255.255.0", "192.168.0.1")
    return s, [
        ("(setup) TCP/IP 3 = DHCP is stored", set_(TCPIP, 1, 3, "02 00 00 00"), H("90 00 00 00")),
        ("TCP/IP 5 while DHCP is stored: 0x0C", set_(TCPIP, 1, 5, valid), status(SET, 0x0C)),
        ("(restore) TCP/IP 3 = stored", set_(TCPIP, 1, 3, "00 00 00 00"), H("90 00 00 00")),
    ]


def cases():
    out = []
    for rows in (rows_unsupported, rows_path, rows_not_settable, rows_data_size, rows_values, rows_msp,
                 rows_unconnected_send, rows_state_conflict):
        area, table = rows()
        out += [cip_case(area, name, request, reply) for name, request, reply in table]
    out += [cip_case(area, name, request, reply) for area, name, request, reply in rows_class_instance_attribute()]
    return out


def cip_case(area, name, request, reply):
    request = H(request)
    return Case(area, name, Msg(SEND_RR_DATA, rr(request), OWN), rr_reply(reply), on="shared")
