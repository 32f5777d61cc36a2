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
import json, os, sys
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "session47-probe"))
sys.path.insert(0, os.path.join(HERE, "..", "session48-probe"))
import bound  # noqa: E402  (its meshes, noises and seeds)
from short import auto_sweep  # noqa: E402

bound.OPS = [("curvature", "4")]


def auto_row(noisy, clean, truth, steps, s14):
    a = auto_sweep(noisy, clean, truth, "curvature", steps, "FAIRING_S14", "1" if s14 else None)
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
