# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 42: the held-out cases (heldout.sh) without an oracle sweep: each run's error
# against the best of the points measured (the one click, explicit steps at 0.5-2x the risk's
# minimizer from cap_heldout.jsonl, the engine's capped choices from ecap_heldout.jsonl; on the
# flat patch only the automatic runs, whose loops the explicit ones fix).
# Usage: python3 heldout_sum.py cap_heldout.jsonl ecap_heldout.jsonl
import json, math, sys
from collections import defaultdict
explicit = {(r["set"], r["mesh"], r["noise"]): r for r in map(json.loads, open(sys.argv[1]))}
group = defaultdict(lambda: defaultdict(list))
for r in map(json.loads, open(sys.argv[2])):
    k = (r["set"], r["mesh"], r["noise"])
    kind = r["truth"].split(":")[0]
    pts = [r["auto"], r.get("cap1.5", r["auto"]), r.get("cap2", r["auto"])]
    if kind != "plane":
        pts += [explicit[k][x] for x in ("cap0.5", "cap0.7", "cap1", "cap1.5", "cap2")
                if x in explicit[k]]
    best = min(pts)
    v = {x: r.get(x, r["auto"]) / best for x in ("auto", "cap1.5", "cap2")}
    if r.get("reach", 1) > 1.45 or v["auto"] > 1.1:
        print("%-6s %-16s %-6s reach %.2f  " % (k + (r.get("reach", 1),)) +
              "  ".join("%s %.3f" % i for i in v.items()))
    for x in v: group[kind][x].append(v[x])
for kind, d in sorted(group.items()):
    print("%-7s %2d cases  " % (kind, len(d["auto"])) + "  ".join(
        "%s %.4f (worst %.3f)" % (x, math.exp(sum(map(math.log, l)) / len(l)), max(l))
        for x, l in d.items()))
