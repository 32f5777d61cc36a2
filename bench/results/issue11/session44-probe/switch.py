#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 44: where the estimate's model switches from the offset to the scaling (its
# modelled change of the largest component reaches kMaxOffsetChange, 10 %) against where fair()'s
# steps really change the volume by 10 % (--no-volume runs at 0.6-1.25x the model's switch), and
# the real change at the model's switch. TOOL= a fairing-denoise-tool built with
# throwaway.patch (it prints the modelled change per time step with DBG_SWITCH=1); MESHES= a
# folder of dn_NAME_clean.ply and dn_NAME_NOISE.ply.
# Usage: TOOL=… MESHES=… python3 switch.py "MESH NOISE OP STEPS" ...  (e.g. "cheese_18k n0.1_s17 umbrella 8")
import json, math, os, subprocess, sys
TOOL, M = os.environ["TOOL"], os.environ["MESHES"]
TRUTH = {"sphere2_13k": "sphere", "sphere2_3k": "sphere", "torus_10k": "torus:1:0.4"}


def run(args, env=None):
    p = subprocess.run([TOOL] + args, capture_output=True, text=True, env=env)
    return p.stdout, p.stderr


def interp(pairs, x):
    pairs = sorted(pairs)
    for (a, ca), (b, cb) in zip(pairs, pairs[1:]):
        if a <= x <= b:
            return ca + (math.log(x / a) / math.log(b / a) if b > a else 0) * (cb - ca)
    return float("nan")


def cross(pairs, level=0.1):
    pairs = sorted(pairs)
    for (a, ca), (b, cb) in zip(pairs, pairs[1:]):
        if ca <= level < cb:
            return a * (b / a) ** ((level - ca) / (cb - ca))
    return None


for m, n, op, steps in [c.split() for c in sys.argv[1:]]:
    inp, clean = "%s/dn_%s_%s.ply" % (M, m, n), "%s/dn_%s_clean.ply" % (M, m)
    tr = TRUTH.get(m, "mesh")
    out, err = run(["sweep", inp, clean, tr, op, "2", steps, "1", "--auto", "--ts", "1"],
                   dict(os.environ, DBG_SWITCH="1"))
    auto = [json.loads(l) for l in out.splitlines() if '"auto"' in l][0]
    pairs = {}
    for l in err.splitlines():
        if l.startswith("DBG lambda"):
            _, _, lam, _, c = l.split()
            pairs[float(lam)] = float(c)
    lm = cross(list(pairs.items()))
    if lm is None:
        print("%-14s %-11s %-9s auto %.4g, no model switch" % (m, n, op[:9], auto["time_step"]))
        continue
    ts = [lm * f for f in (0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.25)]
    out, _ = run(["sweep", inp, clean, tr, op, "2", steps, "1", "--no-volume", "--ts",
                  ",".join("%.6g" % t for t in ts)])
    real = [(r["time_step"], 1 / (1 + r["volume_change"] / 100) - 1)
            for r in map(json.loads, out.splitlines()) if r["kind"] == "fixed"]
    lr = cross(real)
    print("%-14s %-11s %-9s auto %.4g model switch %.4g real switch %s ratio %s | at the model's "
          "switch the real change %.4f" % (m, n, op[:9], auto["time_step"], lm,
                                           "%.4g" % lr if lr else "-",
                                           "%.3f" % (lr / lm) if lr else "-", interp(real, lm)),
          flush=True)
