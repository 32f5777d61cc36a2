#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 53: the search's stopping rule against the Lanczos steps and the error.
# With a bench build of the engine patched as in knobs.patch (its constants read from FAIRING_*
# variables), runs the curvature flow's and the scale-dependent filter's one-click default
# through `fairing-denoise-tool sweep ... --auto` on the meshes and noises of
# ../session47-probe/bound.py, once per variant of VARIANTS (comma-separated; each a blank-
# separated list of NAME=value, empty for the engine as it is), and prints one JSON line per run:
# each variant's automatic RMS error, time step and Lanczos steps.
# Usage: DT=<bench build>/bin/fairing-denoise-tool BT=<...>/fairing-bench-tool W=<work dir>
#        VARIANTS=",FAIRING_FLAT=0.001" python3 knobs.py > knobs.jsonl
import json, os, subprocess, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "session47-probe"))
from bound import DT, noisy_of, run_all  # noqa: E402  (its meshes, noises, seeds and filters)

VARIANTS = [v.strip() for v in os.environ.get("VARIANTS", "").split(",")]


def setting(noisy, clean, truth, op, steps, variant):
    """The automatic row of the bench build's one-click sweep (order 2, one thread) with the
    variant's assignments (NAME=value, blank-separated) in the environment."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("FAIRING_")}
    env["OMP_NUM_THREADS"] = "1"
    env.update(a.split("=", 1) for a in variant.split())
    p = subprocess.run([DT, "sweep", noisy, clean, truth, op, "2", steps, "1", "--auto", "--ts",
                        "1e-9"], capture_output=True, text=True, env=env)
    auto = [json.loads(l) for l in p.stdout.splitlines()
            if l.startswith("{") and json.loads(l).get("kind") == "auto"]
    a = auto[0] if auto else {}
    return dict(rms=a.get("rms"), ts=a.get("time_step"), lanczos=a.get("strength_iterations"))


def one(case):
    name, noise, seed, (op, steps) = case
    clean, noisy, truth = noisy_of(name, noise, seed)
    return json.dumps(dict(mesh=name, noise=noise[0], seed=seed, op=op,
                           runs={v: setting(noisy, clean, truth, op, steps, v)
                                 for v in VARIANTS}))


if __name__ == "__main__":
    run_all(one)
