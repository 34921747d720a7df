"""Modbus TCP negative conformance cases (docs/conformance.md "Modbus TCP"; the answers are docs/modbus.md's).

The card runs with c500 = 0, IO scanning on (c604 = 1) for the master HOST_IP only (c600-c603), c523 = 0
(no loss supervision), c101 = 1, acc = 50 and dec = 60 (0x0032, 0x003C). Negative cases come from NEG_IP;
unit 255 cases that need the master come from HOST_IP. Nothing here writes a command word other than 0.

A table row: (name, request PDU, answer PDU) on unit 1 unless a unit is given; every row gets its own
transaction id, which the answer must echo with protocol id 0 and the request's unit id.
"""
import os
import struct
import time

from conformance import CLOSED, Case, Chunk, Failure, Link, Protocol, Quiet, card_alive, hexs, unhex

CARD = os.environ.get("CARD_IP", "127.0.0.1")
HOST = os.environ.get("HOST_IP", "127.0.0.1")
NEG = os.environ.get("NEG_IP", HOST)
PORT = 502
ACC, DEC = 0x0032, 0x003C   # --param acc=50 dec=60 (tests/conformance/CMakeLists.txt)

_tid = [0x1000]


def next_tid():
    _tid[0] += 1
    return _tid[0]


def adu(unit, pdu, tid, protocol=0, length=None):
    """An MBAP header and PDU; `length` (unit id + PDU) may lie on purpose."""
    pdu = unhex(pdu) if isinstance(pdu, str) else bytes(pdu)
    return struct.pack(">HHHB", tid, protocol, len(pdu) + 1 if length is None else length, unit) + pdu


def framer(buffer):
    """Length of the first ADU in `buffer` (7-byte MBAP header + length - 1)."""
    if len(buffer) < 6:
        return None
    return 6 + struct.unpack_from(">H", buffer, 4)[0]


def exchange(area, name, request, answer, unit=1, on="neg"):
    tid = next_tid()
    return Case(area, name, adu(unit, request, tid), [adu(unit, answer, tid)], on=on)


def table(area, rows, on="neg"):
    out = []
    for row in rows:
        name, request, answer = row[:3]
        unit = row[3] if len(row) > 3 else 1
        out.append(exchange(area, name, request, answer, unit, on))
    return out


# ---- Functions the addressed server does not serve: exception 01 (docs/modbus.md "Units and functions") --

FUNCTIONS = [
    ("FC 01 Read Coils", "01 00 00 00 01", "81 01"),
    ("FC 02 Read Discrete Inputs", "02 00 00 00 01", "82 01"),
    ("FC 04 Read Input Registers", "04 00 09 00 01", "84 01"),
    ("FC 05 Write Single Coil", "05 00 00 FF 00", "85 01"),
    ("FC 07 Read Exception Status", "07", "87 01"),
    ("FC 08 Diagnostics (echo)", "08 00 00 12 34", "88 01"),
    ("FC 0B Get Comm Event Counter", "0B", "8B 01"),
    ("FC 0F Write Multiple Coils", "0F 00 00 00 08 01 FF", "8F 01"),
    ("FC 11 Report Server ID", "11", "91 01"),
    ("FC 14 Read File Record", "14 07 06 00 01 00 00 00 01", "94 01"),
    ("FC 16 Mask Write Register", "16 00 09 FF FF 00 00", "96 01"),
    ("FC 18 Read FIFO Queue", "18 00 09", "98 01"),
    ("function 0 (not a function)", "00", "80 01"),
    ("function 0x7F", "7F 00 00", "FF 01"),
    ("FC 2B with MEI type 0x0D (CANopen)", "2B 0D 00 00", "AB 01"),
    ("FC 2B with MEI type 0x00", "2B 00", "AB 01"),
    # 0x80-0xFF are exception codes, not functions; the card answers function | 0x80 and 01 (decided).
    ("function 0x83 (an exception code as request)", "83 00 09 00 01", "83 01"),
    ("function 0xFF", "FF", "FF 01"),
    ("FC 01 to unit 0", "01 00 00 00 01", "81 01", 0),
    ("FC 01 to unit 248", "01 00 00 00 01", "81 01", 248),
    ("FC 23 to the drive (unit 1: IO scanning only on 255)", "17 00 09 00 01 00 09 00 01 02 00 32", "97 01"),
    ("FC 06 to the option board (read-only, unit 251)", "06 00 01 00 00", "86 01", 251),
    ("FC 16 to the option board", "10 00 01 00 01 02 00 00", "90 01", 251),
    ("FC 23 to the option board", "17 00 00 00 01 00 00 00 01 02 00 00", "97 01", 251),
    ("FC 04 to the option board", "04 00 00 00 01", "84 01", 251),
    ("FC 01 to IO scanning (unit 255)", "01 00 00 00 01", "81 01", 255),
    ("FC 04 to IO scanning (unit 255)", "04 00 00 00 01", "84 01", 255),
]

# ---- Unit ids without a server: 0A gateway path unavailable, before the function is looked at ------------

UNITS = [(f"unit {u}, FC 03", "03 00 09 00 01", "83 0A", u) for u in (249, 250, 252, 253, 254)] + [
    ("unit 249, FC 01 (the unit is judged before the function)", "01 00 00 00 01", "81 0A", 249),
    ("unit 254, FC 43", "2B 0E 01 00", "AB 0A", 254),
]

# ---- Quantities and PDU lengths: 03 (docs/modbus.md "Exceptions": layout, count 0 or above the limit) ----

QUANTITIES = [
    ("FC 03 count 0", "03 00 09 00 00", "83 03"),
    ("FC 03 count 64 (limit 63)", "03 00 09 00 40", "83 03"),
    ("FC 03 count 125 (Modbus maximum, above the card's 63)", "03 00 09 00 7D", "83 03"),
    ("FC 03 count 0xFFFF", "03 00 09 FF FF", "83 03"),
    ("FC 03 PDU cut after the address", "03 00 09", "83 03"),
    ("FC 03 function byte only", "03", "83 03"),
    ("FC 03 one byte too many", "03 00 09 00 01 00", "83 03"),
    ("FC 06 PDU cut (4 bytes)", "06 00 09 00", "86 03"),
    ("FC 06 one byte too many", "06 00 09 00 32 00", "86 03"),
    ("FC 16 count 0", "10 00 09 00 00 00", "90 03"),
    ("FC 16 count 64 (limit 63)", "10 00 09 00 40 80" + " 00 32" * 64, "90 03"),
    ("FC 16 byte count 3 for one register", "10 00 09 00 01 03 00 32 00", "90 03"),
    ("FC 16 byte count 2, four data bytes", "10 00 09 00 01 02 00 32 00 3C", "90 03"),
    ("FC 16 byte count 4, two data bytes", "10 00 09 00 02 04 00 32", "90 03"),
    ("FC 16 byte count 0 for one register", "10 00 09 00 01 00", "90 03"),
    ("FC 16 cut before the byte count", "10 00 09 00 01", "90 03"),
    ("FC 43 read device id code 0", "2B 0E 00 00", "AB 03"),
    ("FC 43 read device id code 4 (individual access, not served)", "2B 0E 04 00", "AB 03"),
    ("FC 43 read device id code 5", "2B 0E 05 00", "AB 03"),
    ("FC 43 without the object id", "2B 0E 01", "AB 03"),
    ("FC 43 one byte too many", "2B 0E 01 00 00", "AB 03"),
    ("FC 03 count 0 to the option board", "03 00 00 00 00", "83 03", 251),
    ("FC 03 count 64 to the option board", "03 00 00 00 40", "83 03", 251),
]

QUANTITIES_MASTER = [
    ("FC 23 read count 0", "17 00 01 00 00 00 01 00 01 02 00 00", "97 03", 255),
    ("FC 23 read count 21 (limit 20)", "17 00 00 00 15 00 01 00 01 02 00 00", "97 03", 255),
    ("FC 23 write count 0", "17 00 01 00 01 00 01 00 00 00", "97 03", 255),
    ("FC 23 write count 21 (limit 20)", "17 00 01 00 01 00 00 00 15 2A" + " 00 00" * 21, "97 03", 255),
    ("FC 23 byte count 4 for one word", "17 00 01 00 01 00 01 00 01 04 00 00 00 00", "97 03", 255),
    ("FC 23 cut after the write address", "17 00 01 00 01 00 01", "97 03", 255),
    ("FC 03 count 64 to IO scanning", "03 00 00 00 40", "83 03", 255),
    ("FC 06 to IO scanning, PDU cut", "06 00 01 00", "86 03", 255),
]

# ---- Addresses: 02 ----------------------------------------------------------------------------------------

ADDRESSES = [
    ("FC 03 from FFF9, 2 registers (the second past FFF9)", "03 FF F9 00 02", "83 02"),
    ("FC 03 from FFFA, 2 registers (the start as given, the second past FFF9)", "03 FF FA 00 02", "83 02"),
    ("FC 06 to a monitor (FE00)", "06 FE 00 00 00", "86 02"),
    ("FC 06 to a monitor (FD01)", "06 FD 01 00 00", "86 02"),
    ("FC 06 to a number ending A (000A)", "06 00 0A 00 32", "86 02"),
    ("FC 06 to a number ending F (00FF)", "06 00 FF 00 32", "86 02"),
    ("FC 06 to a number the inverter does not have (0001)", "06 00 01 00 01", "86 02"),
    ("FC 06 to FA06, a scanner target while c604 = 1", "06 FA 06 00 00", "86 02"),
    ("FC 06 to FA07, a scanner target while c604 = 1", "06 FA 07 00 00", "86 02"),
    ("FC 16 from 000B (ending B)", "10 00 0B 00 01 02 00 32", "90 02"),
    ("FC 16 over a monitor (FBF9, FC00)", "10 FB F9 00 02 04 00 00 00 00", "90 02"),
    ("FC 16 from FFF9, 2 registers", "10 FF F9 00 02 04 00 00 00 00", "90 02"),
    ("FC 16 to FA06 among others (scanner target)", "10 FA 06 00 01 02 00 00", "90 02"),
    ("option board register 50 (map 0-49)", "03 00 32 00 01", "83 02", 251),
    ("option board registers 49-50", "03 00 31 00 02", "83 02", 251),
    ("option board register FFFF", "03 FF FF 00 01", "83 02", 251),
]

ADDRESSES_MASTER = [
    ("IO scanning FC 03 word 32 (words 0-31)", "03 00 20 00 01", "83 02", 255),
    ("IO scanning FC 03 words 31-32", "03 00 1F 00 02", "83 02", 255),
    ("IO scanning FC 06 word 32", "06 00 20 00 00", "86 02", 255),
    ("IO scanning FC 16 words 30-32", "10 00 1E 00 03 06 00 00 00 00 00 00", "90 02", 255),
    ("IO scanning FC 23 write words 31-32", "17 00 01 00 01 00 1F 00 02 04 00 00 00 00", "97 02", 255),
    ("IO scanning FC 23 read word 32", "17 00 20 00 01 00 07 00 01 02 00 00", "97 02", 255),
]

# ---- Values: 03 for a value the inverter refuses; reads of numbers that do not exist: 0x8000 -------------

VALUES = [
    ("FC 06 acc = 0 (range 1-60000)", "06 00 09 00 00", "86 03"),
    ("FC 06 acc = 60001", "06 00 09 EA 61", "86 03"),
    ("FC 06 fmsl = 19 (range 0-18)", "06 00 05 00 13", "86 03"),
    ("FC 16 acc = 0, dec = 60: stops at acc", "10 00 09 00 02 04 00 00 00 3C", "90 03"),
    ("FC 03 of 0001 (no such register): 0x8000", "03 00 01 00 01", "03 02 80 00"),
    ("FC 03 from 000A: 0x8000, then 0010 (dec) (§8.9 (5))", "03 00 0A 00 02", f"03 04 80 00 {DEC >> 8:02X} {DEC & 0xFF:02X}"),
    ("FC 03 of 00A0 (the inverter refuses it): 0x8000", "03 00 A0 00 01", "03 02 80 00"),
    ("FC 03 of FFFA (a start ending A is used as given): 0x8000", "03 FF FA 00 01", "03 02 80 00"),
    ("FC 03 of FFFF: 0x8000", "03 FF FF 00 01", "03 02 80 00"),
    ("FC 03 of 0009 and 0010: acc and dec unchanged by the refused writes", "03 00 09 00 02",
     f"03 04 00 {ACC:02X} 00 {DEC:02X}"),
]

# ---- IO scanning from another client than the master (c600-c603): 01 -------------------------------------

ACCESS = [
    ("FC 03 to unit 255 from a non-master", "03 00 01 00 01", "83 01", 255),
    ("FC 23 to unit 255 from a non-master", "17 00 01 00 01 00 01 00 01 02 00 00", "97 01", 255),
    ("FC 06 to unit 255 from a non-master", "06 00 01 00 00", "86 01", 255),
    ("bad FC 23 from a non-master: 01 before the data check", "17 00 01 00 00 00 01 00 01 02 00 00", "97 01", 255),
]

# The master lock (docs/modbus.md "Unit 255", docs/security.md): while c604 = 1 with a master, the control
# registers (FA00-FAFF, cmod, fmod, f207, f899) refuse writes from other clients with 02, before the value.
MASTER_LOCK = [
    ("FC 06 FA23 from a non-master", "06 FA 23 00 00", "86 02"),
    ("FC 06 FA00 from a non-master", "06 FA 00 00 00", "86 02"),
    ("FC 06 cmod = 5 from a non-master: 02 before the value", "06 00 03 00 05", "86 02"),
    ("FC 06 f899 = 1 from a non-master", "06 08 99 00 01", "86 02"),
    ("FC 16 F9F9-FA00 from a non-master: nothing written", "10 F9 F9 00 02 04 00 00 00 00", "90 02"),
]

MASTER_LOCK_MASTER = [
    ("FC 06 cmod = 5 from the master (range 0-4)", "06 00 03 00 05", "86 03"),
]


# ---- The order of checks: unit, function (01), data (03), address (02), execution (04) ---------------------

ORDER = [
    ("FC 03 count 0 from FFFA: 03 before 02", "03 FF FA 00 00", "83 03"),
    ("FC 03 count 64 from FFF9: 03 before 02", "03 FF F9 00 40", "83 03"),
    ("FC 06 to a monitor, PDU cut: 03 before 02", "06 FE 00 00", "86 03"),
    ("FC 16 to 000B with a bad byte count: 03 before 02", "10 00 0B 00 01 04 00 32", "90 03"),
    ("FC 16 to the option board with a bad byte count: 01 before 03", "10 00 01 00 01 04 00 00", "90 01", 251),
    ("FC 43 code 9 to unit 252: 0A before 03", "2B 0E 09 00", "AB 0A", 252),
]


def probe_pair(tid=0xBEEF):
    """Unit 251 register 1 (c500 = 0): a request with a known answer."""
    return adu(251, "03 00 01 00 01", tid), adu(251, "03 02 00 00", tid)


def read_acc(tid):
    return adu(1, "03 00 09 00 01", tid)


def acc_answer(tid, unit=1):
    return adu(unit, f"03 02 00 {ACC:02X}", tid)


def framing_cases():
    area = "MBAP framing"
    cases = []
    t = next_tid
    # Headers that cannot be true: nothing can be delimited after them, the card closes (FIN) without answering.
    for name, protocol, length in [("protocol id 1", 1, 6), ("protocol id 0xFFFF", 0xFFFF, 6),
                                   ("length 0", 0, 0), ("length 1 (unit id, no function)", 0, 1),
                                   ("length 255 (PDU over 253 bytes)", 0, 255), ("length 0xFFFF", 0, 0xFFFF)]:
        cases.append(Case(area, f"{name}: closed, no answer",
                          adu(1, "03 00 09 00 01", t(), protocol, length), [CLOSED], on="neg"))
    cases.append(Case(area, "protocol id 2 judged on 6 header bytes (no unit id yet): closed",
                      adu(1, "", t(), 2, 6)[:6], [CLOSED], on="neg"))
    a, b = t(), t()
    cases.append(Case(area, "a request, then protocol id 2 in the same segment: answered, then closed",
                      read_acc(a) + adu(1, "03 00 09 00 01", b, 2), [acc_answer(a), CLOSED],
                      on="neg"))
    a, b, c = t(), t(), t()
    cases.append(Case(area, "two requests, then length 0: both answered, then closed",
                      read_acc(a) + probe_pair(b)[0] + adu(1, "", c, 0, 0)[:7],
                      [acc_answer(a), probe_pair(b)[1], CLOSED], on="neg"))
    # Length lies. Too short: the ADU ends early and is judged as it is (03); the byte left over starts the
    # next header, which the next bytes complete.
    a = t()
    cases.append(Case(area, "length 5 for a 6-byte FC 03: the cut PDU is 03; the stray byte waits for a header",
                      adu(1, "03 00 09 00 01", a, length=5), [adu(1, "83 03", a, length=3)], probe=False, on="neg"))
    a = t()
    cases.append(Case(area, "length 5 for FC 03, and the stray byte + 5 more make protocol id 0x0700: 03, closed",
                      [adu(1, "03 00 09 00 07", a, length=5), Chunk(unhex("00 07 00 06 01"))],
                      [adu(1, "83 03", a, length=3), CLOSED], on="neg"))
    # Too long: the card waits for the rest (no answer meanwhile), then judges the longer PDU.
    a = t()
    cases.append(Case(area, "length 8 for FC 03: nothing until 2 more bytes come, then 03 for the long PDU",
                      [adu(1, "03 00 09 00 01", a, length=8), Quiet(0.3), Chunk(unhex("00 00"))],
                      [adu(1, "83 03", a)], on="neg"))
    a = t()
    cases.append(Case(area, "length 0x00FE with 5 bytes sent: nothing comes, the connection stays open",
                      [adu(1, "03 00 09 00 01", a, length=0xFE), Quiet(0.3)], [], probe=False, on="neg"))
    # Segmentation.
    a = t()
    request = read_acc(a)
    cases.append(Case(area, "FC 03 one byte per segment", [Chunk(request[i:i + 1]) for i in range(len(request))],
                      [acc_answer(a)], on="neg"))
    a = t()
    request = read_acc(a)
    cases.append(Case(area, "FC 03 split inside the header (3 + 9)", [Chunk(request[:3]), Chunk(request[3:])],
                      [acc_answer(a)], on="neg"))
    a = t()
    request = read_acc(a)
    cases.append(Case(area, "FC 03 split after the unit id (7 + 5)", [Chunk(request[:7]), Chunk(request[7:])],
                      [acc_answer(a)], on="neg"))
    a = t()
    request = adu(1, "10 00 09 00 01 02 00 00", a)
    cases.append(Case(area, "FC 16 with an invalid value split in 3 segments: 03 once",
                      [Chunk(request[:5]), Chunk(request[5:10]), Chunk(request[10:])], [adu(1, "90 03", a)],
                      on="neg"))
    a, b = t(), t()
    cases.append(Case(area, "one ADU and a half, then the rest: two answers",
                      [Chunk(read_acc(a) + probe_pair(b)[0][:4]), Chunk(probe_pair(b)[0][4:])],
                      [acc_answer(a), probe_pair(b)[1]], on="neg"))
    tids = [t() for _ in range(3)]
    cases.append(Case(area, "three ADUs in one segment: three answers in order",
                      b"".join(read_acc(x) for x in tids), [acc_answer(x) for x in tids],
                      on="neg"))
    mixed = [("03 00 09 00 01", f"03 02 00 {ACC:02X}", 1), ("01 00 00 00 01", "81 01", 1),
             ("03 00 01 00 01", "03 02 00 00", 251), ("03 00 09 00 00", "83 03", 1),
             ("03 00 09 00 01", "83 0A", 250), ("06 FE 00 00 00", "86 02", 1),
             ("2B 0E 05 00", "AB 03", 1), ("03 00 0A 00 01", "03 02 80 00", 1)]
    tids = [t() for _ in mixed]
    cases.append(Case(area, "eight good and bad ADUs in one segment: eight answers in order",
                      b"".join(adu(u, q, x) for (q, _, u), x in zip(mixed, tids)),
                      [adu(u, r, x) for (_, r, u), x in zip(mixed, tids)], on="neg"))
    tids = [t() for _ in range(40)]
    cases.append(Case(area, "40 ADUs in one segment (480 bytes): 40 answers in order",
                      b"".join(probe_pair(x)[0] for x in tids), [probe_pair(x)[1] for x in tids], on="neg"))
    cases.append(Case(area, "transaction id 0xFFFF and unit 248 echoed",
                      adu(248, "03 00 09 00 01", 0xFFFF), [acc_answer(0xFFFF, 248)], on="neg"))
    cases.append(Case(area, "transaction id 0 echoed", adu(0, "03 00 09 00 01", 0), [acc_answer(0, 0)],
                      on="neg"))
    return cases


class ModbusProtocol(Protocol):
    name = "Modbus TCP conformance"

    def connect(self, case):
        return Link(CARD, PORT, framer, source=HOST if case.on == "master" else NEG)

    def release(self, case, link, failed):
        link.close()

    def probe(self, link):
        return probe_pair()

    def other_cases(self):
        return [("client lifecycle", "a client closes with ten drive reads pending: the next client is served",
                 close_while_pending),
                ("client lifecycle", "a client closes after half an ADU: the next client is served", close_mid_adu)]

    def health(self):
        return [("a new client reads acc and dec", health_read),
                ("a new client writes acc (FC 06) and the inverter has it", health_write),
                ("FC 16 writes acc and dec back, FC 03 reads them", health_write_multiple),
                ("IO scanning FC 23 from the master", health_io_scanning),
                ("FC 43 basic identification of the option board", health_identification),
                ("every connection of the suite is closed (modbus.clients 0)", health_clients),
                ("the card process is alive", card_alive)]


def served_after(first_bytes):
    """Sends `first_bytes` on one connection and closes it at once; a new client must then be served."""
    link = Link(CARD, PORT, framer, source=NEG)
    link.send(first_bytes)
    link.close()
    link = Link(CARD, PORT, framer, source=NEG)
    try:
        request, answer = probe_pair()
        link.send(read_acc(0x4444) + request)
        got = [link.receive(), link.receive()]
        if got != [acc_answer(0x4444), answer]:
            raise Failure(f"next client: got {[hexs(g) for g in got]}")
    finally:
        link.close()


def close_while_pending():
    served_after(adu(1, "03 00 09 00 0A", next_tid()))


def close_mid_adu():
    served_after(adu(1, "03 00 09 00 0A", next_tid())[:8])


def cases():
    out = []
    out += table("function (01)", FUNCTIONS)
    out += table("unit without server (0A)", UNITS)
    out += table("quantity and length (03)", QUANTITIES)
    out += table("quantity and length (03)", QUANTITIES_MASTER, on="master")
    out += table("address (02)", ADDRESSES)
    out += table("address (02)", ADDRESSES_MASTER, on="master")
    out += table("value (03, 0x8000)", VALUES)
    out += table("IO scanning access (01)", ACCESS)
    out += table("master lock (02)", MASTER_LOCK)
    out += table("master lock (02)", MASTER_LOCK_MASTER, on="master")
    out += table("order of checks", ORDER)
    out += framing_cases()
    return out


def protocol():
    return ModbusProtocol()


# ---- Health after the suite ---------------------------------------------------------------------------

def healthy_exchange(unit, request, answer, what):
    tid = next_tid()
    link = Link(CARD, PORT, framer, source=HOST)
    try:
        link.send(adu(unit, request, tid))
        got = link.receive()
        if got != adu(unit, answer, tid):
            raise Failure(f"{what}: got {hexs(got)}, expected {hexs(adu(unit, answer, tid))}")
    finally:
        link.close()


def health_read():
    healthy_exchange(1, "03 00 09 00 02", f"03 04 00 {ACC:02X} 00 {DEC:02X}", "FC 03 acc, dec")


def health_write():
    from eip_io import SimControl
    healthy_exchange(1, "06 00 09 00 4D", "06 00 09 00 4D", "FC 06 acc = 77")
    control = SimControl(os.environ["CARD_CONTROL"])
    try:
        got = control.get("acc")
    finally:
        control.close()
    if got != 77:
        raise Failure(f"the inverter's acc is {got} after FC 06 acc = 77")


def health_write_multiple():
    healthy_exchange(1, f"10 00 09 00 02 04 00 {ACC:02X} 00 {DEC:02X}", "10 00 09 00 02", "FC 16 acc, dec")
    healthy_exchange(1, "03 00 09 00 02", f"03 04 00 {ACC:02X} 00 {DEC:02X}", "FC 03 acc, dec after FC 16")


def health_io_scanning():
    # Writes 0 to command words 1-2 (FA06, FA07: stop) and reads 2 monitor words (FD01, FD00 of a
    # stopped drive are not known exactly: only the layout is checked).
    tid = next_tid()
    link = Link(CARD, PORT, framer, source=HOST)
    try:
        link.send(adu(255, "17 00 01 00 02 00 01 00 02 04 00 00 00 00", tid))
        got = link.receive()
    finally:
        link.close()
    if got is None or got[:9] != adu(255, "17 04", tid, length=7)[:9] or len(got) != 13:
        raise Failure(f"FC 23: got {hexs(got)}")


def health_identification():
    healthy_exchange(251, "2B 0E 01 00",
                     "2B 0E 01 02 00 00 03 00 07" + b"TOSHIBA".hex() + "01 07" + b"IPE002Z".hex() + "02 04"
                     + b"0106".hex(), "FC 43 of unit 251")


def health_clients():
    from eip_io import SimControl
    deadline = time.monotonic() + 3
    while True:
        control = SimControl(os.environ["CARD_CONTROL"])
        try:
            clients = control.stats().get("modbus.clients")
        finally:
            control.close()
        if clients == "0":
            return
        if time.monotonic() > deadline:
            raise Failure(f"modbus.clients = {clients} after every client closed")
        time.sleep(0.1)


