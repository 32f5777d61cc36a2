#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 47: how early the frozen estimate of Options::freeze_when_better can stop
# once it cannot win. With a bench build of the engine patched to print, at each checkpoint of
# search(), the converged risk's minimum and the residual alone at the last converged point
# (FAIRING_DBG_CK; debug.patch), runs the curvature flow's and the scale-dependent filter's
# one-click default through `fairing-denoise-tool sweep ... --auto` on synthetic shapes and
# libcgal-demo scans at four noises, two draws, and prints one JSON line per run: the recomputed
# estimate's final excess risk, the frozen one's checkpoints and final excess risk.
# Usage: DT=<bench build>/bin/fairing-denoise-tool BT=<...>/fairing-bench-tool W=<work dir>
#        python3 bound.py > bound.jsonl
import json, os, re, subprocess, sys, threading
from concurrent.futures import ThreadPoolExecutor
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", ".."))
from cgal_demo import cgal_demo_off  # noqa: E402
DT, BT = os.environ["DT"], os.environ["BT"]
W = os.environ.get("W", "/tmp/w47")
os.makedirs(W, exist_ok=True)
SYNTH = {"sphere2_3k": (["sphere2", "3"], "sphere"), "sphere2_13k": (["sphere2", "4"], "sphere"),
         "torus_10k": (["torus", "10000"], "torus:1:0.4")}
SCANS = {"elephant_6k": "elephant", "fandisk_13k": "fandisk", "camel_20k": "camel",
         "dragon_20k": "ChineseDragon-10kv", "bull_12k": "bull", "femur_8k": "femur",
         "cheese_18k": "cheese", "knot2_12k": "knot2", "turbine_18k": "turbine",
         "blade_16k": "blade", "homer_10k": "homer"}
NOISES = [("n0.1", "0.1", "normal"), ("n0.25", "0.25", "normal"), ("n0.5", "0.5", "normal"),
          ("iso0.25", "0.25", "iso")]
SEEDS = [int(s) for s in os.environ.get("SEEDS", "3 5").split()]
OPS = [("curvature", "4"), ("scale-dependent", "2")]


def clean_of(name):
    p = "%s/%s_clean.ply" % (W, name)
    if not os.path.exists(p):
        if name in SYNTH:
            subprocess.run([DT, "make"] + SYNTH[name][0] + [p], check=True, capture_output=True)
        else:
            off = cgal_demo_off(W, SCANS[name], also=list(SCANS.values()))
            subprocess.run([BT, "convert", off, p], check=True, capture_output=True)
    return p


def parse(err):
    blocks, ck = [], []
    for line in err.splitlines():
        if line.startswith("CK "):
            f = line.split()
            ck.append({f[i]: float(f[i + 1]) for i in range(1, len(f) - 1, 2)})
        elif line.startswith("FINAL "):
            f = line.split()
            blocks.append(dict(excess=float(f[2]), ts=float(f[4]), steps=int(f[6]), ck=ck))
            ck = []
    return blocks


def noisy_of(name, noise, seed):
    """The noisy draw (made once; written under a temporary name first, since the two filters'
    runs of a case may ask for it at once) and the clean mesh's truth for the sweep."""
    tag, sigma, kind = noise
    clean = clean_of(name)
    noisy = "%s/%s_%s_s%d.ply" % (W, name, tag, seed)
    if not os.path.exists(noisy):
        part = "%s.%d.ply" % (noisy[:-len(".ply")], threading.get_ident())
        subprocess.run([DT, "noise", clean, part, sigma, str(seed), kind], check=True,
                       capture_output=True)
        os.replace(part, noisy)
    return clean, noisy, SYNTH[name][1] if name in SYNTH else "mesh"


def run_all(one):
    """one(case) for every case, two at a time (JOBS), one printed line each."""
    for n in SCANS:  # fetch the scans once, before the parallel runs
        clean_of(n)
    cases = [(m, nz, s, o) for m in list(SYNTH) + list(SCANS) for nz in NOISES for s in SEEDS
             for o in OPS]
    with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
        for line in ex.map(one, cases):
            print(line, flush=True)


def one(case):
    name, noise, seed, (op, steps) = case
    tag = noise[0]
    clean, noisy, truth = noisy_of(name, noise, seed)
    p = subprocess.run([DT, "sweep", noisy, clean, truth, op, "2", steps, "1", "--auto", "--ts",
                        "1e-9"], capture_output=True, text=True,
                       env=dict(os.environ, FAIRING_DBG_CK="1", OMP_NUM_THREADS="1"))
    rows = [json.loads(l) for l in p.stdout.splitlines() if l.startswith("{")]
    auto = [r for r in rows if r.get("kind") == "auto"]
    return json.dumps(dict(mesh=name, noise=tag, seed=seed, op=op, estimates=parse(p.stderr),
                           rms=auto[0]["rms"] if auto else None))


if __name__ == "__main__":
    run_all(one)
