#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43: screen.py's errors over the best fixed step of the same default setting
# (umbrella L2 x8, scale-dependent L2 x2, curvature L2 x4) in each set's committed extract, before
# (a) and after (b): geometric mean, cases past 10 %, and the cases that moved more than THRESHOLD.
# The flat patch is left out: its open boundary's loops take their own automatic step, which the
# extract's fixed steps do not. Usage: python3 screen_sum.py screen.jsonl [THRESHOLD]
import json, math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session41-probe"))
_argv, sys.argv = sys.argv, sys.argv[:1]
import freeze as F  # noqa: E402
sys.argv = _argv
DEFAULT = {"umbrella": 8, "scale-dependent": 2, "curvature": 4}
best = F.best_fixed(DEFAULT)
rows = [json.loads(l) for l in open(sys.argv[1])]
threshold = float(sys.argv[2]) if len(sys.argv) > 2 else 0.01
for op in DEFAULT:
    k3 = op[:3]
    la = lb = 0.0
    n = pa = pb = 0
    moved = []
    for r in rows:
        o = best.get((r["set"], r["mesh"], r["noise"], op))
        if r["mesh"].startswith("plane") or not o or r.get(k3 + "_a") is None or r.get(k3 + "_b") is None:
            continue
        a, b = r[k3 + "_a"] / o, r[k3 + "_b"] / o
        n += 1
        la += math.log(a)
        lb += math.log(b)
        pa += a > 1.1
        pb += b > 1.1
        if abs(b / a - 1) > threshold:
            moved.append("%s %s %s: sigma %.3f -> %.3f edges, time step %.3g -> %.3g, %.3f -> %.3f" % (
                r["set"], r["mesh"], r["noise"], r[k3 + "_a_sig"], r[k3 + "_b_sig"],
                r[k3 + "_a_ts"], r[k3 + "_b_ts"], a, b))
    if n == 0:  # a screen of other filters (OPS=)
        continue
    print("%s: %d cases, error / best fixed step's, geometric mean %.4f -> %.4f, past 10 %% %d -> %d,"
          " moved by more than %g: %d" % (op, n, math.exp(la / n), math.exp(lb / n), pa, pb,
                                          threshold, len(moved)))
    for m in moved:
        print("   ", m)
