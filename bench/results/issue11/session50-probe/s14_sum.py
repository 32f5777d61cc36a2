#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: summarizes s14.jsonl (s14.py): the one click's error with FAIRING_S14
# over without, by kind of mesh, the choices moved, the Lanczos steps, the best and worst runs.
# Usage: python3 s14_sum.py s14.jsonl > s14_sum.txt
import json, math, sys, collections
rows = [json.loads(l) for l in open(sys.argv[1])]
synth = {"sphere2_3k", "sphere2_13k", "torus_10k"}
g = collections.defaultdict(list)
moved, lz, worst = 0, [0, 0], []
for r in rows:
    a, b = r["rule"], r["s14"]
    k = "spheres and torus" if r["mesh"] in synth else "scans"
    ratio = b["rms"] / a["rms"]
    g[k].append(ratio)
    moved += a["time_step"] != b["time_step"]
    lz[0] += a["strength_iterations"]
    lz[1] += b["strength_iterations"]
    worst.append((ratio, r["mesh"], r["noise"], r["seed"], a["time_step"], b["time_step"]))
print("# s14.jsonl: the one click (curvature flow, four L^2 steps) with FAIRING_S14 over without; error ratio")
for k, v in g.items():
    print("%s: %d runs, gmean %.4f, min %.3f, max %.3f, worse by > 5 %%: %d, better by > 5 %%: %d"
          % (k, len(v), math.exp(sum(map(math.log, v)) / len(v)), min(v), max(v),
             sum(x > 1.05 for x in v), sum(x < 0.95 for x in v)))
print("choices moved: %d of %d; Lanczos steps %d -> %d" % (moved, len(rows), lz[0], lz[1]))
worst.sort()
print("best and worst:")
for w in worst[:3] + worst[-8:]:
    print("  %.3f %s %s seed %d: time step %.4g -> %.4g" % w)
