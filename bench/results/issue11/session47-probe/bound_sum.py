#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 47: bound.py's runs summarized. At each checkpoint of the frozen estimate,
# the bound on its final excess risk is the lesser of the converged risk's minimum and the
# residual alone at the last converged point (the residual grows with the time step, the
# divergence is not negative). Prints how often a checkpoint's bound exceeded the final value (by
# how much), and per slack where the estimate would have stopped: Lanczos steps saved, and any
# choice that would change (a frozen estimate that won stopped as a loser).
# Usage: python3 bound_sum.py bound.jsonl
import json, sys
MARGIN = {"curvature": 0.03, "scale-dependent": 0.01}
runs = [json.loads(l) for l in open(sys.argv[1])]
runs = [r for r in runs if len(r["estimates"]) >= 2]
print("runs with both estimates: %d" % len(runs))
worst, over = 0.0, 0
for r in runs:
    fz = r["estimates"][1]
    for c in fz["ck"]:
        gap = c["bound"] - fz["excess"]
        worst = max(worst, gap)
        over += gap > 0
print("checkpoints whose bound exceeds the frozen estimate's final excess: %d (largest by %.5f)"
      % (over, worst))
for slack in (0.0, 0.002, 0.005, 0.01):
    for op in MARGIN:
        total = saved = changed = stopped = 0
        for r in runs:
            if r["op"] != op:
                continue
            rec, fz = r["estimates"][0], r["estimates"][1]
            thr = rec["excess"] - MARGIN[op]
            total += fz["steps"]
            for c in fz["ck"]:
                if c["bound"] - slack > thr:
                    stopped += 1
                    saved += fz["steps"] - int(c["steps"])
                    changed += fz["excess"] < thr
                    break
        print("slack %.3f %-15s stopped early %3d of %3d, Lanczos steps %5d -> %5d (%.0f %%), "
              "choices changed %d" % (slack, op, stopped, sum(r["op"] == op for r in runs), total,
                                      total - saved, 100.0 * saved / max(total, 1), changed))
