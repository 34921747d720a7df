#!/usr/bin/env python3
"""Static RAM of the card on Cortex-M4, measured from ARM objects (not from the x86-64 host build).

Recompiles every device-path source of a configured build (the entries of its compile_commands.json
built with -fno-rtti, plus lwIP's C files) with arm-none-eabi-gcc 12 and the card's flags, then prints:
  - sizeof(firmware::Card) and its members (from the DWARF of a small translation unit including
    firmware/card/card.h), members of 1 KiB and more broken down one level further;
  - lwIP's static memory (.bss/.data symbols of its objects: ram_heap, memp pools, PBUF_POOL, ...);
  - the other static (.bss/.data) symbols of the device code;
  - the total against the budget (docs/lwip.md "Memory budget").
Figures only; nothing is asserted. Usage: tools/bench/ram_footprint.py [--build build/host] [--budget 81920]
"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile

ARM_FLAGS = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-Os",
             "-ffunction-sections", "-fdata-sections"]
CXX_FLAGS = ["-std=c++20", "-fno-exceptions", "-fno-rtti"]
C_FLAGS = ["-std=gnu11"]
DEVICE_C_DIRS = ("/third_party/lwip/", "/firmware/lwip_port/")


def include_args(command):
  args, out, words = [], [], shlex.split(command)
  for i, word in enumerate(words):
    if word in ("-I", "-isystem", "-D"):
      out += [word, words[i + 1]]
    elif word.startswith(("-I", "-D")):
      out.append(word)
  return out


def device_entries(build):
  entries = json.load(open(os.path.join(build, "compile_commands.json")))
  for e in entries:
    is_c = e["file"].endswith(".c")
    if (is_c and any(d in e["file"] for d in DEVICE_C_DIRS)) or (not is_c and "-fno-rtti" in e["command"]):
      yield e["file"], is_c, include_args(e["command"])


def compile_one(source, is_c, includes, out_dir, extra=()):
  obj = os.path.join(out_dir, source.strip("/").replace("/", "_") + ".o")
  compiler = "arm-none-eabi-gcc" if is_c else "arm-none-eabi-g++"
  flags = ARM_FLAGS + (C_FLAGS if is_c else CXX_FLAGS) + list(extra)
  result = subprocess.run([compiler, *flags, *includes, "-c", source, "-o", obj], capture_output=True, text=True)
  if result.returncode != 0:
    sys.exit(f"{source}: ARM compile failed\n{result.stderr[-3000:]}")
  return source, obj


def ram_symbols(obj):
  """(name, size) of every .bss/.data symbol (nm types b, B, d, D)."""
  out = subprocess.run(["arm-none-eabi-nm", "-S", "-C", obj], capture_output=True, text=True).stdout
  for line in out.splitlines():
    m = re.match(r"[0-9a-f]+ ([0-9a-f]+) ([bBdD]) (.*)", line)
    if m:
      yield m.group(3), int(m.group(1), 16)


# ---- DWARF: members of one class, from `readelf --debug-dump=info` ----
def parse_dies(text):
  dies, stack = {}, []
  current = None
  for line in text.splitlines():
    m = re.match(r"\s*<(\d+)><([0-9a-f]+)>: Abbrev Number: (\d+)(?: \((\w+)\))?", line)
    if m:
      level, offset = int(m.group(1)), int(m.group(2), 16)
      if m.group(3) == "0":
        current = None
        continue
      del stack[level:]
      current = {"tag": m.group(4), "attrs": {}, "children": [], "parent": stack[-1] if stack else None}
      dies[offset] = current
      if stack:
        dies[stack[-1]]["children"].append(offset)
      stack.append(offset)
      continue
    a = re.match(r"\s*<[0-9a-f]+>\s+(DW_AT_\w+)\s*:\s*(.*)", line)
    if a and current is not None:
      current["attrs"][a.group(1)] = a.group(2).split("): ")[-1].strip()
  return dies


def qualified_name(dies, offset):
  parts = []
  while offset is not None:
    die = dies[offset]
    if die["tag"] in ("DW_TAG_namespace", "DW_TAG_class_type", "DW_TAG_structure_type", "DW_TAG_union_type"):
      parts.append(die["attrs"].get("DW_AT_name", "(anonymous)"))
    offset = die["parent"]
  return "::".join(reversed(parts))


def type_of(dies, attrs):
  ref = attrs.get("DW_AT_type")
  while ref:
    offset = int(ref.strip("<>"), 16)
    die = dies[offset]
    if die["tag"] in ("DW_TAG_typedef", "DW_TAG_const_type", "DW_TAG_volatile_type") and "DW_AT_type" in die["attrs"]:
      if die["tag"] == "DW_TAG_typedef" and die["attrs"].get("DW_AT_name", "").endswith("_t"):
        return die["attrs"]["DW_AT_name"], None
      ref = die["attrs"]["DW_AT_type"]
      continue
    if die["tag"] in ("DW_TAG_class_type", "DW_TAG_structure_type", "DW_TAG_union_type"):
      return qualified_name(dies, offset), offset
    return die["attrs"].get("DW_AT_name", die["tag"].replace("DW_TAG_", "")), None
  return "?", None


def definitions(dies):
  found = {}
  for offset, die in dies.items():
    if "DW_AT_byte_size" in die["attrs"] and "DW_AT_declaration" not in die["attrs"] and \
        die["tag"] in ("DW_TAG_class_type", "DW_TAG_structure_type"):
      found.setdefault(qualified_name(dies, offset), offset)
  return found


def members(dies, defs, class_offset):
  """[(name, type, size incl. padding, type's definition offset)] in layout order."""
  die = dies[class_offset]
  size = int(die["attrs"]["DW_AT_byte_size"], 0)
  rows = []
  for child in die["children"]:
    c = dies[child]
    if c["tag"] in ("DW_TAG_member", "DW_TAG_inheritance") and "DW_AT_data_member_location" in c["attrs"]:
      type_name, type_offset = type_of(dies, c["attrs"])
      if type_name in defs:
        type_offset = defs[type_name]
      name = c["attrs"].get("DW_AT_name", "(base)")
      rows.append([int(c["attrs"]["DW_AT_data_member_location"], 0), name, type_name, type_offset])
  rows.sort()
  out = []
  for i, (offset, name, type_name, type_offset) in enumerate(rows):
    end = rows[i + 1][0] if i + 1 < len(rows) else size
    out.append((name, type_name, end - offset, type_offset))
  return out


def card_layout(build, includes, out_dir, expand_from, depth_limit):
  source = os.path.join(out_dir, "card_size.cc")
  with open(source, "w") as f:
    f.write('#include "card/card.h"\nextern "C" { const unsigned ipe_card_size = sizeof(firmware::Card); }\n')
  _, obj = compile_one(source, False, includes, out_dir, ["-g", "-femit-class-debug-always",
                                                         "-fno-eliminate-unused-debug-types"])
  text = subprocess.run(["arm-none-eabi-readelf", "--debug-dump=info", obj], capture_output=True, text=True).stdout
  dies = parse_dies(text)
  defs = definitions(dies)
  card = defs["firmware::Card"]
  print(f"sizeof(firmware::Card) on Cortex-M4: {int(dies[card]['attrs']['DW_AT_byte_size'], 0)} bytes")

  def show(class_offset, depth):
    for name, type_name, size, type_offset in sorted(members(dies, defs, class_offset), key=lambda r: -r[2]):
      if size < 16 and depth > 0:
        continue
      print(f"  {'  ' * depth}{size:>8}  {name}  ({type_name})")
      inner = members(dies, defs, type_offset) if type_offset is not None else []
      if len(inner) == 1 and inner[0][0] == "_M_elems":  # a std::array: its type says it all
        continue
      if size >= expand_from and type_offset is not None and depth < depth_limit:
        show(type_offset, depth + 1)
  show(card, 0)
  return int(dies[card]["attrs"]["DW_AT_byte_size"], 0)


def main():
  parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
  parser.add_argument("--build", default="build/host", help="a configured build (its compile_commands.json)")
  parser.add_argument("--budget", type=int, default=80 * 1024, help="bytes for Card + lwIP + other statics")
  parser.add_argument("--expand-from", type=int, default=1024, help="break down members this large")
  parser.add_argument("--depth", type=int, default=2, help="levels of members below Card's own")
  parser.add_argument("--jobs", type=int, default=2)
  args = parser.parse_args()

  entries = list(device_entries(args.build))
  card_includes = next(inc for src, _, inc in entries if src.endswith("firmware/card/card.cc"))
  with tempfile.TemporaryDirectory(prefix="ram_footprint_") as out_dir:
    card = card_layout(args.build, card_includes, out_dir, args.expand_from, args.depth)
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
      objects = list(pool.map(lambda e: compile_one(*e, out_dir), entries))
    lwip, ours = [], []
    for source, obj in objects:
      target = lwip if any(d in source for d in DEVICE_C_DIRS) else ours
      target += [(size, name, os.path.basename(source)) for name, size in ram_symbols(obj)]

  for title, rows in (("lwIP static memory (.bss/.data)", lwip), ("Other device statics (.bss/.data)", ours)):
    print(f"\n{title}: {sum(r[0] for r in rows)} bytes")
    for size, name, source in sorted(rows, reverse=True):
      if size >= 64:
        print(f"  {size:>8}  {name}  ({source})")
    small = [r for r in rows if r[0] < 64]
    if small:
      print(f"  {sum(r[0] for r in small):>8}  {len(small)} symbols under 64 bytes")
  total = card + sum(r[0] for r in lwip) + sum(r[0] for r in ours)
  print(f"\nTotal static RAM: {total} bytes ({total / 1024:.1f} KiB); budget {args.budget} bytes "
        f"({args.budget / 1024:.0f} KiB): {'within' if total <= args.budget else 'OVER'} by "
        f"{abs(args.budget - total)} bytes")


if __name__ == "__main__":
  main()
