#!/usr/bin/python3
"""tools/check-layers on a copy of the tree: the copy as it is passes; every upward include added to it
(a header, a source, a new file, a CMake data path) fails the check with its file and line named.

    check_layers_test.py SOURCE_DIR
"""

import os
import shutil
import subprocess
import sys
import tempfile

# What the check reads: the layers' folders (the ones that exist) and lwIP's headers, to resolve them.
COPIED = ["base", "config", "hal", "drive_link", "net", "web", "modbus", "cip", "firmware", "sim",
          "third_party/lwip/src/include"]

# (file, include line, what the message must name): one upward include of each kind.
UPWARD = [
    ("hal/include/hal/clock.h", '#include "drive_link/link_client.h"', "layer hal may not include"),
    ("web/json.cc", '#include "sim/inverter_model.h"', "layer web may not include"),
    ("cip/epath.cc", '#include "net/arp.h"', "layer cip may not include"),
    ("modbus/connection.cc", '#include "lwip/tcp.h"', "layer modbus may not include"),
    ("firmware/card/card_report.cc", '#include "lwip/priv/tcp_priv.h"', "layer firmware may not include"),
    ("firmware/card/card.cc", '#include "control_server.h"', "layer firmware may not include"),
    ("net/CMakeLists.txt", 'set(X "${CMAKE_SOURCE_DIR}/sim/register_table.cc")', "layer net may not include"),
]


def run_check(source_dir, root):
    return subprocess.run([sys.executable, os.path.join(source_dir, "tools", "check-layers"), "--root", root],
                          capture_output=True, text=True, check=False)


def fail(message, result=None):
    print("FAIL:", message)
    if result is not None:
        print("exit", result.returncode, "\nstderr:\n" + result.stderr)
    sys.exit(1)


def append_line(path, line):
    with open(path, encoding="utf-8") as f:
        count = sum(1 for _ in f)
    with open(path, "a", encoding="utf-8") as f:
        f.write(line + "\n")
    return count + 1  # the number of the line added


def main():
    source_dir = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory(prefix="check-layers-") as root:
        for folder in COPIED:
            if os.path.isdir(os.path.join(source_dir, folder)):
                shutil.copytree(os.path.join(source_dir, folder), os.path.join(root, folder),
                                ignore=shutil.ignore_patterns("build", ".git"))
        clean = run_check(source_dir, root)
        if clean.returncode != 0:
            fail("the unchanged copy does not pass", clean)

        expected = []
        for path, line, message in UPWARD:
            number = append_line(os.path.join(root, path), line)
            expected.append((f"{path}:{number}: {message}", line))
        # A new file in the lowest layer (the vocabulary) including the HAL.
        base = "base/include/base" if os.path.isdir(os.path.join(root, "base")) else "hal/base/include/base"
        with open(os.path.join(root, base, "upward.h"), "w", encoding="utf-8") as f:
            f.write('#pragma once\n#include "hal/clock.h"\n')
        expected.append((f"{base}/upward.h:2: layer base may not include hal/include/hal/clock.h", ""))

        result = run_check(source_dir, root)
        if result.returncode == 0:
            fail("upward includes passed the check", result)
        lines = result.stderr.splitlines()
        for message, _ in expected:
            if not any(l.startswith(message) for l in lines):
                fail(f"no line starting with {message!r}", result)
        violations = [l for l in lines if not l.startswith("check-layers:")]
        if len(violations) != len(expected):
            fail(f"{len(violations)} violations reported, {len(expected)} added", result)
    print(f"ok: the copy passes; {len(expected)} upward includes fail it, each named by file and line")


if __name__ == "__main__":
    main()
