# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""compare.py RUN.jsonl FIXED.jsonl [STUDY.jsonl]: a loop variant's one-click rows (runs/) against
the fixed boundary's on the same inputs, and with STUDY (a bench/denoise.sh run on those inputs)
the best of our three filters against the best peer at its best setting."""
import collections, json, math, os, sys

load = lambda f: {r["case"]: r for r in map(json.loads, open(f)) if r.get("rms") is not None}
curve, fixed = load(sys.argv[1]), load(sys.argv[2])
ratios = collections.defaultdict(list)
for case in sorted(curve):
    if case in fixed:
        ratios[case.split("_n0")[0].split("_iso")[0]].append(curve[case]["rms"] / fixed[case]["rms"])
allr = [x for v in ratios.values() for x in v]
print("%d rows; curve / fixed: gmean %.3f, worst %.3f, %d worse than 1.001" %
      (len(allr), math.exp(sum(map(math.log, allr)) / len(allr)), max(allr), sum(x > 1.001 for x in allr)))
for m, v in sorted(ratios.items()):
    print("  %-14s %.3f-%.3f" % (m, min(v), max(v)))
if len(sys.argv) > 3:
    best = {}
    for r in map(json.loads, open(sys.argv[3])):
        m = r.get("method") or ""
        if "mesh" not in r or r.get("rms") is None or m.startswith("ours"):
            continue
        k = (r["mesh"], r["noise"])
        if k not in best or r["rms"] < best[k][0]:
            best[k] = (r["rms"], m)
    for (mesh, noise), (peer, name) in sorted(best.items()):
        ours = [d[c]["rms"] for d in (curve,) for c in d if c.startswith("%s_%s_" % (mesh, noise))]
        fx = [fixed[c]["rms"] for c in fixed if c.startswith("%s_%s_" % (mesh, noise))]
        if ours and fx:
            print("%-14s %-8s best peer %.4f (%s): fixed %.3f, curve %.3f" %
                  (mesh, noise, peer, name, min(fx) / peer, min(ours) / peer))
