#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Every tracked source file names its licence: the SPDX licence identifier line near its top
that matches LICENSE (GPL-3.0-or-later). Exit 77 (skipped) outside a git checkout."""
import os
import subprocess
import sys

EXPECTED = "SPDX-License-Identifier: GPL-3.0-or-later"
SOURCE_ENDINGS = (".cpp", ".cc", ".h", ".hpp", ".py", ".sh", ".cmake")


def is_source(path):
    if path.endswith(SOURCE_ENDINGS) or os.path.basename(path) == "CMakeLists.txt":
        return True
    try:  # scripts without an ending, such as .ci/run
        with open(path, "rb") as f:
            return f.readline().startswith(b"#!")
    except OSError:
        return False


def main():
    root = sys.argv[1]
    listed = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True)
    if listed.returncode != 0:
        print("not a git checkout: skipped")
        return 77
    missing, checked = [], 0
    for rel in filter(None, listed.stdout.decode().split("\0")):
        path = os.path.join(root, rel)
        if not os.path.isfile(path) or not is_source(path):
            continue
        checked += 1
        with open(path, encoding="utf-8", errors="replace") as f:
            head = [next(f, "") for _ in range(5)]
        if not any(EXPECTED in line for line in head):
            missing.append(rel)
    with open(os.path.join(root, "LICENSE"), encoding="utf-8") as f:
        if "GNU GENERAL PUBLIC LICENSE" not in f.read(200):
            print("LICENSE is not the GNU GPL that the SPDX lines name")
            return 1
    if missing:
        print("%d of %d source files lack '%s' in their first 5 lines (scripts/add-spdx.sh adds "
              "it):\n  %s" % (len(missing), checked, EXPECTED, "\n  ".join(missing)))
        return 1
    print("%d source files carry '%s'" % (checked, EXPECTED))
    return 0


if __name__ == "__main__":
    sys.exit(main())
