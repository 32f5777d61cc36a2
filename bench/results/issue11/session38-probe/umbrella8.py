#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The umbrella's L^2 x4 and x8 rows of a set's extracts, and one click against the best peer.

    umbrella8.py OLD_EXTRACT NEW_EXTRACT [OLD NEW ...]

OLD: the set's extract before `--add umbrella:2:8` (one-click rows with 4 umbrella steps), NEW:
after (x8 oracles and automatic rows, one-click rows of the CLI with 8). Prints, per setting, the
automatic rows within 10 % of their own oracle (geometric mean, worst), the x8 automatic error
over the x4 one, and for the scans the best one-click result of ours over the best peer at its
best (at most 1, within 1 %, geometric mean, worst) before and after; with several pairs, the
same over all of them at the end."""
import json, math, sys


def load(path):
    rows = [json.loads(l) for l in open(path)]
    meta = rows[0]["meta"]
    kind = {m["name"]: m["kind"] for m in meta["meshes"]}
    oracle, auto, cli, peer = {}, {}, {}, {}
    for r in rows[1:]:
        if r.get("rms") is None or r.get("error"):
            continue
        m = r.get("method", "")
        if m == "ours" and r.get("kind") in ("fixed", "auto"):
            k = (r["mesh"], r["noise"], r["op"], r["order"], r["steps"])
            store = oracle if r["kind"] == "fixed" else auto
            if r["kind"] == "auto" or k not in oracle or r["rms"] < oracle[k]["rms"]:
                store[k] = r
        elif m == "ours CLI auto":
            cli[(r["mesh"], r["noise"], r["op"])] = r
        elif m.startswith(("MeshLab", "CGAL", "OpenMesh")):
            k = (r["mesh"], r["noise"])
            if k not in peer or r["rms"] < peer[k]["rms"]:
                peer[k] = r
    return kind, oracle, auto, cli, peer


def gmean(v):
    return math.exp(sum(map(math.log, v)) / len(v)) if v else float("nan")


total = {"before (x4)": [], "after (x8)": []}
for old_path, new_path in zip(sys.argv[1::2], sys.argv[2::2]):
    print("==", new_path)
    _, _, _, cli_old, _ = load(old_path)
    kind, oracle, auto, cli, peer = load(new_path)
    for steps in (4, 8):
        q = {k[:2]: auto[k]["rms"] / oracle[k]["rms"] for k in auto
             if k[2:] == ("umbrella", 2, steps) and k in oracle}
        for group in ("scan", "known"):
            v = [x for c, x in q.items() if (kind[c[0]] == "scan") == (group == "scan")
                 and not c[0].startswith("plane")]
            if v:
                worst = max((x, c) for c, x in q.items() if x in v)
                print("umbrella L2 x%d, %s: %d of %d within 10 %% of its oracle, gmean %.4f, worst %.3f (%s %s)"
                      % (steps, group, sum(x <= 1.10 for x in v), len(v), gmean(v), worst[0], *worst[1]))
        misses = sorted((x, c) for c, x in q.items() if x > 1.10)
        if misses:
            print("  past 10 %%: %s" % ", ".join("%s %s %.3f" % (c[0], c[1], x) for x, c in misses))
    r84 = [auto[k[:4] + (8,)]["rms"] / auto[k]["rms"] for k in auto
           if k[2:] == ("umbrella", 2, 4) and k[:4] + (8,) in auto and not k[0].startswith("plane")]
    if r84:
        print("x8 auto / x4 auto: gmean %.4f, range %.3f-%.3f over %d cases"
              % (gmean(r84), min(r84), max(r84), len(r84)))
    o84 = [oracle[k[:4] + (8,)]["rms"] / oracle[k]["rms"] for k in oracle
           if k[2:] == ("umbrella", 2, 4) and k[:4] + (8,) in oracle and not k[0].startswith("plane")]
    if o84:
        print("x8 oracle / x4 oracle: gmean %.4f, range %.3f-%.3f" % (gmean(o84), min(o84), max(o84)))
    for label, c in (("before (x4)", cli_old), ("after (x8)", cli)):
        by_case = {}
        for (m, n, op), r in c.items():
            if (m, n) in peer and kind[m] == "scan":
                by_case[(m, n)] = min(by_case.get((m, n), 9e9), r["rms"] / peer[(m, n)]["rms"])
        v = list(by_case.values())
        total[label] += v
        if v:
            steps = sorted({r.get("steps") for (m, n, op), r in c.items() if op == "umbrella"})
            print("one click / best peer on scans, %s, umbrella steps %s: %d cases, <= 1 in %d, <= 1.01 in %d,"
                  " gmean %.4f, worst %.3f" % (label, steps, len(v), sum(x <= 1 for x in v),
                                               sum(x <= 1.01 for x in v), gmean(v), max(v)))
        shapes = {}
        for (m, n, op), r in c.items():
            if (m, n) in peer and kind[m] != "scan" and not m.startswith("plane"):
                shapes[(m, n)] = min(shapes.get((m, n), 9e9), r["rms"] / peer[(m, n)]["rms"])
        if shapes:
            print("  shapes: %.3f-%.3f" % (min(shapes.values()), max(shapes.values())))
if len(sys.argv) > 3:
    for label, v in total.items():
        print("all pairs, one click / best peer on scans, %s: %d cases, <= 1 in %d, <= 1.01 in %d, "
              "gmean %.4f" % (label, len(v), sum(x <= 1 for x in v), sum(x <= 1.01 for x in v), gmean(v)))
