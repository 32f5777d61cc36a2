# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 42: cap.jsonl against each set's oracle of the curvature default (L^2 x4,
# the best fixed step) and its one-click CLI row. Usage: python3 cap_sum.py cap.jsonl [OP ORDER]
# (OP ORDER: the oracle of another filter's four steps, e.g. scale-dependent 1).
import json, math, os, sys
from collections import defaultdict
HERE = os.path.dirname(os.path.abspath(__file__))
R = os.path.join(HERE, "..", "..")
rows = [json.loads(l) for l in open(sys.argv[1])]
OP, ORDER = (sys.argv[2], int(sys.argv[3])) if len(sys.argv) > 3 else ("curvature", 2)
oracle, cli = {}, {}
for d in sorted({r["set"] for r in rows}):
    f = R + "/" + d + ".jsonl" if d == "denoise" else R + "/" + d + "/denoise.jsonl"
    for l in list(open(f))[1:]:
        x = json.loads(l)
        k = (d, x.get("mesh"), x.get("noise"))
        if x.get("method") == "ours" and x.get("kind") == "fixed" and x.get("op") == OP \
                and x.get("order") == ORDER and x.get("steps") == 4:
            oracle[k] = min(oracle.get(k, 1e9), x["rms"])
        if x.get("method") == "ours CLI auto" and x.get("op") == OP:
            cli[k] = x["rms"]
labels = ["auto"] + sorted({k for r in rows for k in r if k.startswith("cap") and
                            not k.endswith("_ts")}, key=lambda s: float(s[3:]))
group = defaultdict(lambda: defaultdict(list))
print("%-14s %-22s %-8s %5s %9s" % ("set", "mesh", "noise", "reach", "rise") +
      "".join("%9s" % l for l in labels))
for r in rows:
    k = (r["set"], r["mesh"], r["noise"])
    if k not in oracle or "auto" not in r: continue
    kind = "scan" if r["truth"] == "mesh" else r["truth"].split(":")[0]
    vals = [r.get(l, r["auto"]) / oracle[k] for l in labels]
    for l, v in zip(labels, vals): group[kind][l].append(v)
    if r.get("reach", 1) > 1:
        print("%-14s %-22s %-8s %5.2f %9.2e" % (r["set"], r["mesh"], r["noise"], r["reach"],
              r["rise"]) + "".join("%9.3f" % v for v in vals))
print()
for kind, g in sorted(group.items()):
    print("%-8s %3d cases" % (kind, len(g["auto"])) + "".join(
        "  %s %.4f (%d past 1.1, worst %.3f)" % (l, math.exp(sum(map(math.log, v)) / len(v)),
                                                 sum(x > 1.1 for x in v), max(v))
        for l, v in g.items()))
mismatch = [(k, r["auto"], cli.get(k)) for r in rows
            for k in [(r["set"], r["mesh"], r["noise"])] if k in cli and "auto" in r
            and abs(r["auto"] / cli[k] - 1) > 1e-3]
print("one-click rows differing from the committed CLI row by > 0.1 %:", len(mismatch))
for m in mismatch[:10]: print("  ", m)
