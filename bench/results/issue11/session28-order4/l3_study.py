#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 28: the umbrella's L^3 with 1, 2 and 4 steps on the study's meshes and
noises (oracle of a log search and the automatic choice, fairing-denoise-tool sweep), against
the committed study's extract (the umbrella's L^2 x4 oracle and automatic rows, the best peer at
its best). Measurement aid, not part of any build.

    l3_study.py BIN STUDY_JSONL OUT_JSONL [SEED_SUFFIX] [OP] [ORDER]

SEED_SUFFIX: '' for seed 1, '_s2' for the seed-2 meshes (and a seed-2 extract as STUDY_JSONL)."""
import json
import os
import subprocess
import sys

bin_dir, study, out_path = sys.argv[1:4]
suffix = sys.argv[4] if len(sys.argv) > 4 else ""
op = sys.argv[5] if len(sys.argv) > 5 else "umbrella"
order = sys.argv[6] if len(sys.argv) > 6 else "3"
meshes_dir = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-meshes")
rows = [json.loads(l) for l in open(study)]
meta = rows[0]["meta"]
done = set()
if os.path.exists(out_path):
    done = {(r["mesh"], r["noise"], r["steps"]) for r in map(json.loads, open(out_path))}
with open(out_path, "a") as out:
    for m in meta["meshes"]:
        if m["name"].startswith("plane"):
            continue
        for noise in ("n0.1", "n0.25", "n0.5", "iso0.25"):
            noisy = os.path.join(meshes_dir, "dn_%s_%s%s.ply" % (m["name"], noise, suffix))
            clean = os.path.join(meshes_dir, "dn_%s_clean.ply" % m["name"])
            if not os.path.exists(noisy):
                continue
            for steps in (1, 2, 4):
                if (m["name"], noise, steps) in done:
                    continue
                x0 = {1: 20.0, 2: 5.0, 4: 2.0}[steps] if op == "umbrella" else 1000.0 / steps
                res = subprocess.run([os.path.join(bin_dir, "fairing-denoise-tool"), "sweep", noisy, clean,
                                      m["truth"], op, order, str(steps), repr(x0), "--auto"],
                                     capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
                if res.returncode != 0:
                    print(json.dumps(dict(mesh=m["name"], noise=noise, steps=steps, error=res.stderr[-300:])),
                          file=out, flush=True)
                    continue
                pts = [json.loads(l) for l in res.stdout.splitlines() if l.startswith("{")]
                fixed = [p for p in pts if p["kind"] == "fixed" and p.get("rms") is not None]
                failed = sum(1 for p in pts if p["kind"] == "fixed" and p.get("rms") is None)
                auto = [p for p in pts if p["kind"] == "auto" and p.get("rms") is not None]
                if not fixed:
                    print(json.dumps(dict(mesh=m["name"], noise=noise, steps=steps, error="every time step failed",
                                          failed_time_steps=failed)), file=out, flush=True)
                    continue
                best = min(fixed, key=lambda p: p["rms"])
                print(json.dumps(dict(mesh=m["name"], noise=noise, op=op, order=int(order), steps=steps,
                                      oracle=best["rms"], oracle_ts=best["time_step"],
                                      auto=auto[0]["rms"] if auto else None,
                                      auto_ts=auto[0]["time_step"] if auto else None,
                                      volume_change=auto[0]["volume_change"] if auto else None,
                                      failed_time_steps=failed)),
                      file=out, flush=True)
