#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Summary of session33-probe/oracle_probe.sh runs with SPECS="umbrella:2:4:10 umbrella:2:8:10"
(and later files whose lines replace earlier ones of the same mesh, noise and steps, e.g. a
search started nearer the oracle): per steps count, automatic rows within 10 % of their own
oracle, geometric mean, the misses, and the automatic error of x8 over x4.
    oracle8_sum.py RUN.txt [REPLACEMENTS.txt ...]"""
import math, sys

rows = {}
for path in sys.argv[1:]:
    for line in open(path):
        p = line.split()
        if len(p) < 16:
            print("skipped:", line.strip())
            continue
        rows[(p[0], p[1], p[3])] = dict(oracle=float(p[7]), auto=float(p[11]), ratio=float(p[15]))


def gmean(v):
    return math.exp(sum(map(math.log, v)) / len(v))


for s in ("x4", "x8"):
    r = {k: v["ratio"] for k, v in rows.items() if k[2] == s}
    print("%s: %d of %d within 10 %%, geometric mean %.4f; past 10 %%: %s" % (
        s, sum(x <= 1.10 for x in r.values()), len(r), gmean(r.values()),
        ", ".join("%s %s %.3f" % (k[0], k[1], x) for k, x in sorted(r.items()) if x > 1.10)))
q = [rows[k[:2] + ("x8",)]["auto"] / v["auto"] for k, v in rows.items()
     if k[2] == "x4" and k[:2] + ("x8",) in rows]
print("x8 auto / x4 auto over %d cases: geometric mean %.4f, range %.3f-%.3f"
      % (len(q), gmean(q), min(q), max(q)))
