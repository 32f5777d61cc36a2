#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 45: freeze.py's runs per filter and kind of mesh: the recomputed estimated
# risk less the frozen one (quantiles), frozen / recomputed error, and what each margin would
# choose, against each set's best fixed (recomputed) step of the same default setting (geometric
# mean, cases past 10 %). Usage: python3 freeze_sum.py freeze.jsonl [MARGIN,...]
import json, math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session41-probe"))
_argv, sys.argv = sys.argv, sys.argv[:1]
import freeze as F  # noqa: E402
sys.argv = _argv
DEFAULT = {"scale-dependent": 2, "curvature": 4}
best = F.best_fixed(DEFAULT)  # the extracts' fixed rows (freeze.py's runs are one-click)
rows = [json.loads(l) for l in open(sys.argv[1])]
margins = [float(x) for x in sys.argv[2].split(",")] if len(sys.argv) > 2 else [0, 0.002, 0.01, 0.02, 0.03]


def kind(mesh):
    k = mesh.split("_")[0].rstrip("0123456789")
    return k if k in ("sphere", "torus", "plane") else "scan"


gm = lambda v: math.exp(sum(map(math.log, v)) / len(v)) if v else float("nan")
for op in DEFAULT:
    ok = [r for r in rows if r["op"] == op and r.get("recompute") and r.get("freeze")
          and r.get("recomputed_risk") is not None]
    print("== %s: %d cases" % (op, len(ok)))
    for k in ("sphere", "torus", "plane", "scan"):
        v = sorted((r["recomputed_risk"] - r["frozen_risk"], r["freeze"] / r["recompute"])
                   for r in ok if kind(r["mesh"]) == k)
        if not v:
            continue
        q = [v[int(p * (len(v) - 1))][0] for p in (0, 0.1, 0.5, 0.9, 1)]
        print("  %-6s %3d: risk recomputed - frozen min/10%%/median/90%%/max %s; frozen / recomputed"
              " error %.3f (%.3f-%.3f)" % (k, len(v), " ".join("%.4f" % x for x in q),
                                          gm([x[1] for x in v]), min(x[1] for x in v), max(x[1] for x in v)))
    for m in margins:
        for grp in ("known", "scan"):
            sel = [r for r in ok if (kind(r["mesh"]) == "scan") == (grp == "scan") and not r["mesh"].startswith("plane")
                   and (r["set"], r["mesh"], r["noise"], op) in best]
            if not sel:
                continue
            o = lambda r: best[(r["set"], r["mesh"], r["noise"], op)]
            pick = lambda r: r["freeze"] if r["recomputed_risk"] - r["frozen_risk"] > m else r["recompute"]
            a = [r["recompute"] / o(r) for r in sel]
            b = [pick(r) / o(r) for r in sel]
            print("  margin %-6g %-5s %3d cases: frozen %3d, one click / best fixed step %.4f -> %.4f, past 10 %% %d -> %d"
                  % (m, grp, len(sel), sum(r["recomputed_risk"] - r["frozen_risk"] > m for r in sel), gm(a), gm(b),
                     sum(x > 1.1 for x in a), sum(x > 1.1 for x in b)))
    default = [r for r in ok if r.get("default")]
    agree = sum((r["default"] == r["freeze"]) == r["frozen"] for r in default)
    print("  the CLI's own choice matches its reported flag in %d of %d" % (agree, len(default)))
