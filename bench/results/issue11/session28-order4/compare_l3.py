#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 28: l3_study.py's rows against a study extract: per case the umbrella's
L^2 x4 (the default) oracle and automatic error, L^3 x1/x2/x4 oracle and automatic error, and
the best peer at its best (measurement aid).

    compare_l3.py STUDY_JSONL L3_JSONL [OP] [ORDER STEPS]   (default: umbrella 2 4)"""
import collections
import json
import math
import sys

study = [json.loads(l) for l in open(sys.argv[1])][1:]
l3 = [json.loads(l) for l in open(sys.argv[2]) if '"error"' not in l]
op = sys.argv[3] if len(sys.argv) > 3 else "umbrella"
base_order, base_steps = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (2, 4)
kind = {m["name"]: m["kind"] for m in json.loads(open(sys.argv[1]).readline())["meta"]["meshes"]}
ours = collections.defaultdict(dict)
peer = {}
for r in study:
    if r.get("rms") is None or r.get("noise") in (None, "clean"):
        continue
    key = (r["mesh"], r["noise"])
    if r["method"] == "ours" and r.get("op") == op and r.get("order") == base_order and r.get("steps") == base_steps:
        if r["kind"] == "fixed":
            ours[key]["oracle"] = min(ours[key].get("oracle", 1e9), r["rms"])
        elif r["kind"] == "auto":
            ours[key]["auto"] = r["rms"]
    elif not r["method"].startswith("ours") and r["method"] not in ("invariant", "cost"):
        peer[key] = min(peer.get(key, (1e9, "")), (r["rms"], r["method"]))
by = collections.defaultdict(dict)
for r in l3:
    by[(r["mesh"], r["noise"])][r["steps"]] = r
print("| mesh | noise | L%d x%d oracle / auto | x1 oracle / auto | x2 oracle / auto | x4 oracle / auto | best peer |"
      % (base_order, base_steps))
print("|---|---|---|---|---|---|---|")
ratios = collections.defaultdict(list)
for key in sorted(by, key=lambda k: (kind.get(k[0], ""), k)):
    b = ours.get(key, {})
    cells = []
    for s in (1, 2, 4):
        r = by[key].get(s)
        cells.append("%.4f / %.4f" % (r["oracle"], r["auto"]) if r else "-")
        if r and b.get("auto"):
            ratios[(kind.get(key[0]), s)].append(r["auto"] / b["auto"])
    p = peer.get(key)
    print("| %s | %s | %s | %s | %s |" % (key[0], key[1],
          "%.4f / %.4f" % (b.get("oracle", math.nan), b.get("auto", math.nan)), " | ".join(cells),
          "%.4f (%s)" % p if p else "-"))
print()
for (k, s), v in sorted(ratios.items()):
    g = math.exp(sum(map(math.log, v)) / len(v))
    print("%s x%d: automatic error / the default's automatic error: gmean %.4f, range %.4f-%.4f (%d cases)"
          % (k, s, g, min(v), max(v), len(v)))
