#!/usr/bin/python3
"""Validates the simulated inverter's register table and generates its C++ form.

The one table is drive_link/registers/registers.csv (one row per register of the VF-MB1/VF-S15,
keyed by the 16-bit communication number). This script checks every row and writes a header with a
constexpr array of sim::RegisterInfo sorted by number, which register_table.cc includes.

    gen_register_table.py --csv registers.csv --out build/.../register_table.inc
    gen_register_table.py --csv registers.csv --check              # validate only
    gen_register_table.py --csv registers.csv --assumed-markdown   # the docs/simulator.md list

Columns (header row required, in this order):
  number                 4 hex digits, e.g. 0009, C500, FA06; a last digit A-F is refused (such
                         numbers do not exist on VF-MB1/S15, seed 000 section 8.9 note (5))
  title                  panel title, lower case: acc, c500, fa06, f856 (unique, case-insensitive)
  function               short text, printable ASCII
  storage                eeprom | ram | monitor | trip-hold
  access                 rw (hosts may write) | ro (nobody writes; the drive produces it) |
                         option (the option card writes it; hosts only read)
  min,max,default        VF-MB1 values, and VF-S15 values too unless the s15_ columns are filled
  s15_min,s15_max,s15_default   all blank, or all three set when VF-S15 differs
  unit                   "-" (plain number or code), "bits", "char", or "<step> <unit>" with step
                         1, 0.1, 0.01 or 0.001 and unit Hz s % V A kW kWh h degC pps rpm
  write_during_run       yes | no
  effective_after_reset  yes | no (the manuals' (*3) mark: takes effect after power-on or f899 = 1)
  models                 both | vf-mb1 | vf-s15
  source                 seed and section; values the seeds leave open are listed in one last
                         segment "assumed: ...", which the docs list is built from

Standard library only; run with /usr/bin/python3. Exit status 1 with one line per problem.
"""

import argparse
import csv
import os
import re
import sys
import tempfile

COLUMNS = [
    "number", "title", "function", "storage", "access", "min", "max", "default",
    "s15_min", "s15_max", "s15_default", "unit", "write_during_run", "effective_after_reset",
    "models", "source",
]
STORAGE = {
    "eeprom": "StorageClass::kEeprom",
    "ram": "StorageClass::kRamOnly",
    "monitor": "StorageClass::kMonitor",
    "trip-hold": "StorageClass::kTripHold",
}
ACCESS = {"rw": "Access::kReadWrite", "ro": "Access::kReadOnly", "option": "Access::kOption"}
MODELS = {"both": "ModelMask::kBoth", "vf-mb1": "ModelMask::kVfMb1", "vf-s15": "ModelMask::kVfS15"}
UNITS = {
    "Hz": "Unit::kHertz", "s": "Unit::kSecond", "%": "Unit::kPercent", "V": "Unit::kVolt",
    "A": "Unit::kAmpere", "kW": "Unit::kKilowatt", "kWh": "Unit::kKilowattHour",
    "h": "Unit::kHour", "degC": "Unit::kDegreeCelsius", "pps": "Unit::kPulsesPerSecond",
    "rpm": "Unit::kRpm",
}
STEPS = {"1": 0, "0.1": 1, "0.01": 2, "0.001": 3}
BOOLS = {"yes": True, "no": False}
NUMBER_RE = re.compile(r"^[0-9A-F]{4}$")
TITLE_RE = re.compile(r"^[a-z][a-z0-9]*$")
INT_RE = re.compile(r"^-?[0-9]+$")


class Row:
    """One validated CSV row, ready to be written as C++."""

    def __init__(self, line, fields):
        self.line = line
        self.number = int(fields["number"], 16)
        self.title = fields["title"]
        self.function = fields["function"]
        self.storage = fields["storage"]
        self.access = fields["access"]
        self.mb1 = tuple(int(fields[k]) for k in ("min", "max", "default"))
        if fields["s15_min"]:
            self.s15 = tuple(int(fields[k]) for k in ("s15_min", "s15_max", "s15_default"))
        else:
            self.s15 = self.mb1
        self.unit = fields["unit"]
        self.write_during_run = BOOLS[fields["write_during_run"]]
        self.effective_after_reset = BOOLS[fields["effective_after_reset"]]
        self.models = fields["models"]
        self.source = fields["source"]


def parse_unit(text):
    """Returns (C++ Unit enumerator, decimals) or None."""
    if text == "-":
        return "Unit::kNone", 0
    if text == "bits":
        return "Unit::kBits", 0
    if text == "char":
        return "Unit::kAscii", 0
    parts = text.split(" ")
    if len(parts) == 2 and parts[0] in STEPS and parts[1] in UNITS:
        return UNITS[parts[1]], STEPS[parts[0]]
    return None


def assumed_part(source):
    """The text after the one 'assumed:' marker, or None."""
    index = source.find("assumed:")
    return None if index < 0 else source[index + len("assumed:"):].strip()


def check_title_matches_number(number_text, title):
    """Names that encode their number must agree with it: c500 <-> C500, fa06 <-> FA06, f856 <-> 0856."""
    if number_text[0] == "C":
        return title == "c" + number_text[1:]
    if number_text[0] == "F":
        return title == number_text.lower()
    if re.match(r"^f[0-9]{3}$", title):
        return number_text == "0" + title[1:]
    return True


def validate(path):
    """Reads and checks the CSV. Returns (rows sorted by number, list of error strings)."""
    errors = []
    rows = []
    with open(path, newline="", encoding="utf-8") as handle:
        reader = csv.reader(handle)
        try:
            header = next(reader)
        except StopIteration:
            return [], ["%s: empty file" % path]
        if header != COLUMNS:
            return [], ["%s:1: header must be %s" % (path, ",".join(COLUMNS))]
        for line, values in enumerate(reader, start=2):
            where = "%s:%d" % (path, line)
            if not values or all(not v for v in values):
                errors.append("%s: empty line" % where)
                continue
            if len(values) != len(COLUMNS):
                errors.append("%s: %d fields, expected %d" % (where, len(values), len(COLUMNS)))
                continue
            fields = dict(zip(COLUMNS, values))
            problems = check_fields(fields)
            if problems:
                errors.extend("%s (%s): %s" % (where, fields["title"] or fields["number"], p)
                              for p in problems)
                continue
            rows.append(Row(line, fields))

    by_number = {}
    by_title = {}
    for row in rows:
        if row.number in by_number:
            errors.append("%s:%d: number %04X already on line %d"
                          % (path, row.line, row.number, by_number[row.number].line))
        by_number.setdefault(row.number, row)
        key = row.title.lower()
        if key in by_title:
            errors.append("%s:%d: title %s already on line %d"
                          % (path, row.line, row.title, by_title[key].line))
        by_title.setdefault(key, row)
    rows.sort(key=lambda r: r.number)
    return rows, errors


def validate_or_report(path):
    """The rows of a valid CSV; None after printing every problem to stderr (the generators' exit 1)."""
    rows, errors = validate(path)
    if not errors:
        return rows
    for error in errors:
        print(error, file=sys.stderr)
    print("%s: %d problem(s)" % (path, len(errors)), file=sys.stderr)
    return None


def check_fields(f):
    """Problems of one row, as strings (empty when the row is valid)."""
    p = []
    for key in COLUMNS:
        if f[key] != f[key].strip():
            p.append("%s has leading or trailing blanks" % key)
    number = f["number"]
    if not NUMBER_RE.match(number):
        p.append("number %r is not 4 upper-case hex digits" % number)
    elif number[3] in "ABCDEF":
        p.append("number %s ends in A-F; such numbers do not exist on VF-MB1/S15" % number)
    title = f["title"]
    if not TITLE_RE.match(title):
        p.append("title %r is not a lower-case letter followed by letters/digits" % title)
    elif NUMBER_RE.match(number) and not check_title_matches_number(number, title):
        p.append("title %s does not match number %s" % (title, number))
    for key in ("function", "source"):
        if not f[key]:
            p.append("%s is empty" % key)
    if not all(" " <= ch <= "~" for ch in f["function"]):
        p.append("function must be printable ASCII (it becomes a C++ string)")
    storage, access = f["storage"], f["access"]
    if storage not in STORAGE:
        p.append("storage %r is not one of %s" % (storage, ", ".join(STORAGE)))
    if access not in ACCESS:
        p.append("access %r is not one of %s" % (access, ", ".join(ACCESS)))
    for key in ("write_during_run", "effective_after_reset"):
        if f[key] not in BOOLS:
            p.append("%s %r is not yes or no" % (key, f[key]))
    if f["models"] not in MODELS:
        p.append("models %r is not one of %s" % (f["models"], ", ".join(MODELS)))
    if parse_unit(f["unit"]) is None:
        p.append("unit %r is not '-', 'bits', 'char' or '<step> <unit>'" % f["unit"])
    if p:
        return p

    # Storage, access and flags must agree.
    readonly_storage = storage in ("monitor", "trip-hold")
    if readonly_storage and access == "rw":
        p.append("a %s register cannot be written by hosts (access must be ro or option)" % storage)
    if not readonly_storage and access == "ro":
        p.append("a %s register with access ro makes no sense; use monitor" % storage)
    if readonly_storage and (f["write_during_run"] == "yes" or f["effective_after_reset"] == "yes"):
        p.append("a %s register must have write_during_run no and effective_after_reset no" % storage)
    if storage == "ram" and f["effective_after_reset"] == "yes":
        p.append("a RAM-only register cannot take effect after a reset (a reset clears it)")
    if number[:2] in ("FB", "FC", "FD", "FE") and not readonly_storage:
        p.append("FB/FC/FD/FE numbers are monitors (storage monitor or trip-hold)")
    if number[:2] == "FA" and readonly_storage:
        p.append("FA numbers are command registers, not monitors")
    if (number[0] == "C" or number[0] == "0") and readonly_storage:
        p.append("parameters (0xxx, Cxxx) are not monitors; use ram with access option for displays")

    # Ranges.
    s15 = [f["s15_min"], f["s15_max"], f["s15_default"]]
    if any(s15) and not all(s15):
        p.append("s15_min, s15_max and s15_default are all blank or all set")
        return p
    if all(s15) and f["models"] == "vf-mb1":
        p.append("a VF-MB1-only register has no VF-S15 values")
    sets = [("", [f["min"], f["max"], f["default"]])]
    if all(s15):
        sets.append(("s15_", s15))
    for prefix, (lo, hi, default) in sets:
        if not all(INT_RE.match(v) for v in (lo, hi, default)):
            p.append("%smin/%smax/%sdefault must be decimal integers" % (prefix, prefix, prefix))
            continue
        lo, hi, default = int(lo), int(hi), int(default)
        if not lo <= default <= hi:
            p.append("%smin <= %sdefault <= %smax does not hold (%d, %d, %d)"
                     % (prefix, prefix, prefix, lo, default, hi))
        if lo < 0 and (lo < -32768 or hi > 32767):
            p.append("a signed register must stay within -32768..32767")
        if lo >= 0 and hi > 65535:
            p.append("an unsigned register must stay within 0..65535")
    if all(s15) and all(INT_RE.match(v) for v in s15 + [f["min"]]):
        if (int(f["min"]) < 0) != (int(s15[0]) < 0):
            p.append("VF-MB1 and VF-S15 must agree on signedness")

    # The 'assumed:' marker: at most one, and it ends the source.
    source = f["source"]
    if source.count("assumed:") > 1:
        p.append("source has more than one 'assumed:' segment")
    elif "assumed" in source.replace("assumed:", ""):
        p.append("source says 'assumed' without the 'assumed:' marker")
    elif assumed_part(source) is not None and not assumed_part(source):
        p.append("source has an empty 'assumed:' segment")
    return p


def cxx_string(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def generate(rows, csv_name):
    out = [
        "// Generated by tools/gen_register_table.py from %s. Do not edit; edit the CSV." % csv_name,
        "// %d registers, sorted by communication number." % len(rows),
        "#pragma once",
        "",
        '#include "sim/register_table.h"',
        "",
        "namespace sim::generated {",
        "",
        "inline constexpr RegisterInfo kRegisters[] = {",
    ]
    for r in rows:
        unit, decimals = parse_unit(r.unit)
        out.append(
            "    {0x%04X, %s, %s, %s, %s, {%d, %d, %d}, {%d, %d, %d}, {%s, %d}, %s, %s, %s},"
            % (r.number, cxx_string(r.title), cxx_string(r.function), STORAGE[r.storage],
               ACCESS[r.access], r.mb1[0], r.mb1[1], r.mb1[2], r.s15[0], r.s15[1], r.s15[2],
               unit, decimals, "true" if r.write_during_run else "false",
               "true" if r.effective_after_reset else "false", MODELS[r.models]))
    out += ["};", "", "}  // namespace sim::generated", ""]
    return "\n".join(out)


def write_if_changed(path, text):
    """Writes atomically, and not at all when the content is the same (keeps the build quiet)."""
    try:
        with open(path, encoding="utf-8") as handle:
            if handle.read() == text:
                return
    except FileNotFoundError:
        pass
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".register_table.")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def assumed_markdown(rows):
    """One table line per run of neighbouring rows that share the same assumptions."""
    runs = []  # [first row, last row, text]
    previous = None
    for r in rows:
        part = assumed_part(r.source)
        if part:
            if runs and runs[-1][2] == part and runs[-1][1] is previous:
                runs[-1][1] = r
            else:
                runs.append([r, r, part])
        previous = r
    lines = ["| Number | Title | Assumed |", "| --- | --- | --- |"]
    for first, last, text in runs:
        if first is last:
            number, title = "%04X" % first.number, first.title
        else:
            number = "%04X-%04X" % (first.number, last.number)
            title = "%s-%s" % (first.title, last.title)
        lines.append("| %s | %s | %s |" % (number, title, text.replace("|", "/")))
    return "\n".join(lines) + "\n"


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--csv", required=True, help="the register table (registers.csv)")
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--out", help="write the generated C++ header here")
    mode.add_argument("--check", action="store_true", help="validate only")
    mode.add_argument("--assumed-markdown", action="store_true",
                      help="print a Markdown table of every assumed value")
    args = parser.parse_args(argv)

    rows = validate_or_report(args.csv)
    if rows is None:
        return 1
    if args.out:
        write_if_changed(args.out, generate(rows, os.path.basename(args.csv)))
    elif args.assumed_markdown:
        sys.stdout.write(assumed_markdown(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
