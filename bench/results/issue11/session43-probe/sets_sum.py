#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43: each set's extract at git revision REV against the working tree's: the
# automatic rows within 10 % of their oracle (the best of the same filter, order and steps' fixed
# steps), the one-click defaults past 10 %, and on scans the best one click of ours over the best
# peer at its best (at most 1, within 1 %, geometric mean), and each mesh's range of that ratio.
# Usage (repository root): python3 sets_sum.py REV [SET ...]
import json, math, subprocess, sys
from collections import defaultdict
SETS = ["denoise", "denoise-seed2", "denoise-seed8", "denoise-noise", "heldout-s11", "heldout-s13",
        "heldout-s17"]
DEFAULT = {"umbrella": 8, "scale-dependent": 2, "curvature": 4}


def path(d):
    return "bench/results/denoise.jsonl" if d == "denoise" else "bench/results/%s/denoise.jsonl" % d


def oracles(rows):
    """The best fixed step's error per (mesh, noise, op, order, steps) of an extract's rows."""
    best = {}
    for r in rows:
        if r.get("method") == "ours" and r.get("kind") == "fixed" and r.get("rms") is not None:
            k = (r["mesh"], r["noise"], r["op"], r["order"], r["steps"])
            best[k] = min(best.get(k, math.inf), r["rms"])
    return best


def summary(lines):
    rows = [json.loads(l) for l in lines if l.strip()]
    kind = {m["name"]: m["kind"] for m in rows[0]["meta"]["meshes"]}
    best = oracles(rows[1:])
    auto = [r["rms"] / best[k] for r in rows[1:] if r.get("kind") == "auto"
            for k in [(r["mesh"], r["noise"], r["op"], r["order"], r["steps"])] if k in best]
    past = []
    ours, peer = defaultdict(lambda: math.inf), defaultdict(lambda: math.inf)
    for r in rows[1:]:
        if r.get("rms") is None: continue
        c = (r["mesh"], r["noise"])
        if r.get("method") == "ours CLI auto":
            k = c + (r["op"], r["order"], r["steps"])
            if r["order"] == 2 and r["steps"] == DEFAULT[r["op"]] and k in best and r["rms"] > 1.1 * best[k]:
                past.append(("%s %s %s" % (r["mesh"], r["noise"], r["op"]), r["rms"] / best[k]))
            ours[c] = min(ours[c], r["rms"])
        elif not r.get("method", "").startswith("ours"):
            peer[c] = min(peer[c], r["rms"])
    scans = {c: ours[c] / peer[c] for c in ours if c in peer and kind.get(c[0]) == "scan"}
    per = defaultdict(list)
    for c in ours:
        if c in peer and not c[0].startswith("plane"): per[c[0]].append(ours[c] / peer[c])
    return dict(within=sum(a <= 1.1 for a in auto), rows=len(auto), past=dict(past),
                le1=sum(v <= 1 for v in scans.values()), le101=sum(v <= 1.01 for v in scans.values()),
                n=len(scans), gmean=math.exp(sum(map(math.log, scans.values())) / max(1, len(scans))),
                per={m: (min(v), max(v)) for m, v in sorted(per.items())})


if __name__ == "__main__":
    rev = sys.argv[1]
    for d in sys.argv[2:] or SETS:
        old = summary(subprocess.run(["git", "show", "%s:%s" % (rev, path(d))], capture_output=True,
                                     text=True, check=True).stdout.splitlines())
        new = summary(open(path(d)).read().splitlines())
        print("== %s: automatic rows within 10 %%: %d -> %d of %d" % (d, old["within"], new["within"], new["rows"]))
        print("   one-click defaults past 10 %%: %d -> %d" % (len(old["past"]), len(new["past"])))
        for a in sorted(set(old["past"]) | set(new["past"])):
            f = lambda p: "%.3f" % p[a] if a in p else "-"
            print("     %s: %s -> %s" % (a, f(old["past"]), f(new["past"])))
        if new["n"]:
            print("   scans, best one click / best peer: <= 1 %d -> %d, <= 1.01 %d -> %d of %d, gmean %.4f -> %.4f"
                  % (old["le1"], new["le1"], old["le101"], new["le101"], new["n"], old["gmean"], new["gmean"]))
            for m in new["per"]:
                o, w = old["per"].get(m, (0, 0)), new["per"][m]
                if o != w: print("     %s %.3f-%.3f -> %.3f-%.3f" % (m, o[0], o[1], w[0], w[1]))
