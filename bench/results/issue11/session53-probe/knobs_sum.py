#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 53: per variant of a knobs.py screen against its first (the engine as it
# is): the Lanczos steps per filter, the choices moved, the geometric mean of the automatic
# choice's RMS error over the first's, and the runs moved most either way.
# Usage: python3 knobs_sum.py knobs.jsonl
import json, math, sys

rows = [json.loads(l) for l in open(sys.argv[1])]
names = list(rows[0]["runs"])
base = names[0]
for name in names[1:]:
    of = [r for r in rows if r["runs"][base]["rms"] is not None
          and r["runs"][name]["rms"] is not None]
    print("%r against %r: %d runs" % (name, base, len(of)))
    for op in ("curvature", "scale-dependent"):
        a = sum(r["runs"][base]["lanczos"] for r in of if r["op"] == op)
        b = sum(r["runs"][name]["lanczos"] for r in of if r["op"] == op)
        print("  %s: Lanczos steps %d -> %d (%+.1f %%)" % (op, a, b, 100 * (b / a - 1)))
    ratios = sorted(((r["runs"][name]["rms"] / r["runs"][base]["rms"], r) for r in of),
                    key=lambda t: t[0])
    moved = sum(r["runs"][base]["ts"] != r["runs"][name]["ts"] for r in of)
    gmean = math.exp(sum(math.log(q) for q, _ in ratios) / len(ratios))
    print("  choices moved %d, error ratio geometric mean %.4f, past 1.02: %d, below 0.98: %d"
          % (moved, gmean, sum(q > 1.02 for q, _ in ratios), sum(q < 0.98 for q, _ in ratios)))
    for q, r in ratios[:3] + ratios[-3:]:
        print("  %.4f %s %s seed %d %s: time step %.4g -> %.4g, Lanczos %d -> %d"
              % (q, r["mesh"], r["noise"], r["seed"], r["op"], r["runs"][base]["ts"],
                 r["runs"][name]["ts"], r["runs"][base]["lanczos"], r["runs"][name]["lanczos"]))
