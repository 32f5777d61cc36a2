#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 51: the sketch's draw on the study's sketched meshes (more data vertices
than the sketch's 8,192 rows). Each default filter's automatic step (fairing-denoise-tool sweep
--auto, the engine's) for XSEED = 0 .. SEEDS-1 (a bench build with rows_and_seed_5fdf95d.patch;
XSEED=0 is the engine), against the oracle of the study's committed extract (the least error of
its fixed steps of the same setting). Prints one JSON line per run, then a summary per setting.
Usage: DT=<patched build>/bin/fairing-denoise-tool python3 draws.py [SEEDS]"""
import collections, json, os, subprocess, sys

SEEDS = int(sys.argv[1]) if len(sys.argv) > 1 else 6
DT = os.environ["DT"]
M = os.path.expanduser(os.environ.get("M", "~/.cache/filter_implicit_fairing/bench-meshes"))
EXTRACT = os.path.join(os.path.dirname(__file__), "..", "..", "denoise.jsonl")
MESHES = ["sphere2_51k", "camel_20k", "dragon_20k", "elephant_loop1_22k"]
NOISES = ["n0.1", "n0.25", "n0.5", "iso0.25"]
SETTINGS = [("umbrella", 2, 8), ("scale-dependent", 2, 2), ("curvature", 2, 4)]

lines = [json.loads(l) for l in open(EXTRACT)]
truth = {m["name"]: m["truth"] for m in lines[0]["meta"]["meshes"]}
oracle, study_auto = {}, {}
for r in lines[1:]:
    if r.get("method") != "ours" or "op" not in r:
        continue
    key = (r["mesh"], r["noise"], r["op"], r["order"], r["steps"])
    if r.get("kind") == "fixed":
        oracle[key] = min(oracle.get(key, float("inf")), r["rms"])
    elif r.get("kind") == "auto":
        study_auto[key] = r["rms"]

ratios = collections.defaultdict(list)
for mesh in MESHES:
    for noise in NOISES:
        for op, order, steps in SETTINGS:
            key = (mesh, noise, op, order, steps)
            for seed in range(SEEDS):
                out = subprocess.run(
                    [DT, "sweep", f"{M}/dn_{mesh}_{noise}.ply", f"{M}/dn_{mesh}_clean.ply",
                     truth[mesh], op, str(order), str(steps), "0", "--auto"],
                    env=dict(os.environ, XSEED=str(seed), OMP_NUM_THREADS="1"),
                    capture_output=True, text=True, check=True).stdout
                auto = next(json.loads(l) for l in out.splitlines() if '"kind":"auto"' in l)
                ratio = auto["rms"] / oracle[key]
                ratios[(op, order, steps)].append(ratio)
                print(json.dumps({"mesh": mesh, "noise": noise, "op": op, "order": order,
                                  "steps": steps, "xseed": seed, "time_step": auto["time_step"],
                                  "rms": auto["rms"], "oracle": oracle[key],
                                  "study_auto": study_auto.get(key), "ratio": round(ratio, 4),
                                  "lanczos": auto["strength_iterations"]}), flush=True)
for (op, order, steps), r in ratios.items():
    print(f"# {op} L{order} x{steps}: {len(r)} runs, past 1.10: {sum(x > 1.10 for x in r)}, "
          f"worst {max(r):.3f}", flush=True)
