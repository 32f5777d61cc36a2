#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 48: a settled checkpoint within SHORT_POINTS grid points (1 by default) of
# the margin (kMargin) calling the next one 1.15x on instead of 1.4x. With a bench build of the
# engine patched as in short.patch (the rule behind FAIRING_SHORT), runs the curvature flow's and
# the scale-dependent filter's one-click default through `fairing-denoise-tool sweep ... --auto`
# on the meshes and noises of ../session47-probe/bound.py, without and with the rule, and prints
# one JSON line per run: the automatic choice's RMS error, time step and Lanczos steps each way.
# Usage: DT=<bench build>/bin/fairing-denoise-tool BT=<...>/fairing-bench-tool W=<work dir>
#        python3 short.py > short.jsonl
import json, os, subprocess, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "session47-probe"))
from bound import DT, noisy_of, run_all  # noqa: E402  (its meshes, noises, seeds and filters)


def auto_sweep(noisy, clean, truth, op, steps, variable, value):
    """The automatic row of the bench build's one-click sweep (order 2, one thread), with the
    environment variable `variable` set to `value` (None: unset)."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env.pop(variable, None)
    if value is not None:
        env[variable] = value
    p = subprocess.run([DT, "sweep", noisy, clean, truth, op, "2", steps, "1", "--auto", "--ts",
                        "1e-9"], capture_output=True, text=True, env=env)
    auto = [json.loads(l) for l in p.stdout.splitlines()
            if l.startswith("{") and json.loads(l).get("kind") == "auto"]
    return auto[0] if auto else {}


def auto_row(noisy, clean, truth, op, steps, short):
    a = auto_sweep(noisy, clean, truth, op, steps, "FAIRING_SHORT",
                   os.environ.get("SHORT_POINTS", "1") if short else None)
    return dict(rms=a.get("rms"), ts=a.get("time_step"), lanczos=a.get("strength_iterations"))


def one(case):
    name, noise, seed, (op, steps) = case
    clean, noisy, truth = noisy_of(name, noise, seed)
    return json.dumps(dict(mesh=name, noise=noise[0], seed=seed, op=op,
                           rule=auto_row(noisy, clean, truth, op, steps, False),
                           short=auto_row(noisy, clean, truth, op, steps, True)))


if __name__ == "__main__":
    run_all(one)
