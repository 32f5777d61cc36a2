#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: the recomputed L^2 steps' movement and divergence on the first step's
# operator instead of the steps' mean (s14.patch, behind FAIRING_S14 in a bench build), the later
# steps' residual unchanged. Runs the curvature flow's one-click default (four L^2 steps, frozen
# and recomputed compared) through `fairing-denoise-tool sweep ... --auto` on the meshes, noises
# and seeds of ../session47-probe/bound.py, without and with it; one JSON line per run.
# Usage: DT=<bench build>/bin/fairing-denoise-tool BT=<...>/fairing-bench-tool W=<work dir>
#        python3 s14.py > s14.jsonl
import json, os, subprocess, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "session47-probe"))
import bound  # noqa: E402  (its meshes, noises and seeds)

bound.OPS = [("curvature", "4")]


def auto_row(noisy, clean, truth, steps, s14):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env.pop("FAIRING_S14", None)
    if s14:
        env["FAIRING_S14"] = "1"
    p = subprocess.run([bound.DT, "sweep", noisy, clean, truth, "curvature", "2", steps, "1",
                        "--auto", "--ts", "1e-9"], capture_output=True, text=True, env=env)
    auto = [json.loads(l) for l in p.stdout.splitlines()
            if l.startswith("{") and json.loads(l).get("kind") == "auto"]
    a = auto[0] if auto else {}
    return {k: a.get(k) for k in ("rms", "time_step", "strength_iterations", "operator_frozen",
                                  "recomputed_risk", "frozen_risk")}


def one(case):
    name, noise, seed, (op, steps) = case
    clean, noisy, truth = bound.noisy_of(name, noise, seed)
    return json.dumps(dict(mesh=name, noise=noise[0], seed=seed, op=op,
                           rule=auto_row(noisy, clean, truth, steps, False),
                           s14=auto_row(noisy, clean, truth, steps, True)))


if __name__ == "__main__":
    bound.run_all(one)
