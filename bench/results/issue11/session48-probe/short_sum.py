#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 48: per screen of short.py, the Lanczos steps per filter without and with
# the rule, the choices it moved, the geometric mean of the one click's RMS error with the rule
# over without, and the runs it moved most.
# Usage: python3 short_sum.py short1.jsonl short2.jsonl
import json, math, sys

for path in sys.argv[1:]:
    rows = [json.loads(l) for l in open(path)]
    rows = [r for r in rows if r["rule"]["rms"] is not None and r["short"]["rms"] is not None]
    print("%s: %d runs" % (path, len(rows)))
    for op in ("curvature", "scale-dependent"):
        of = [r for r in rows if r["op"] == op]
        a = sum(r["rule"]["lanczos"] for r in of)
        b = sum(r["short"]["lanczos"] for r in of)
        print("  %s: Lanczos steps %d -> %d (%+.1f %%)" % (op, a, b, 100 * (b / a - 1)))
    ratios = sorted(((r["short"]["rms"] / r["rule"]["rms"], r) for r in rows),
                    key=lambda t: t[0])
    moved = sum(r["rule"]["ts"] != r["short"]["ts"] for r in rows)
    gmean = math.exp(sum(math.log(q) for q, _ in ratios) / len(ratios))
    print("  choices moved %d, error ratio geometric mean %.4f" % (moved, gmean))
    for q, r in ratios[:2] + ratios[-2:]:
        print("  %.4f %s %s seed %d %s: time step %.4g -> %.4g, Lanczos %d -> %d"
              % (q, r["mesh"], r["noise"], r["seed"], r["op"], r["rule"]["ts"], r["short"]["ts"],
                 r["rule"]["lanczos"], r["short"]["lanczos"]))
