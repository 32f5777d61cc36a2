#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 45: on every case of the seven sets (session41-probe/freeze.py's list), the
# one click of the curvature flow and of the scale-dependent filter (its operator choice and the
# estimated risks of recomputed and frozen steps, from the CLI's JSON), and the same filter with
# --recompute and with --freeze: the error of each. One JSON line per case and filter.
# Usage: CLI=build/bin/implicit-fairing python3 freeze.py > freeze.jsonl  (OPS=, JOBS= as screen.py)
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session41-probe"))
_argv, sys.argv = sys.argv, sys.argv[:1]
import freeze as F  # noqa: E402
sys.argv = _argv
CLI = os.environ.get("CLI", "build/bin/implicit-fairing")
OPS = os.environ.get("OPS", "curvature scale-dependent").split()
TMP = os.environ.get("TMPDIR", "/tmp")
RUNS = (("default", []), ("recompute", ["--recompute"]), ("freeze", ["--freeze"]))


def one(c):
    d, seed, mesh, noise, truth = c
    noisy = F.noisy_of(seed, mesh, noise)
    clean = "%s/dn_%s_clean.ply" % (F.M, mesh)
    lines = []
    for op in OPS:
        out = dict(set=d, mesh=mesh, noise=noise, op=op)
        files = []
        for lab, extra in RUNS:
            o = "%s/frz45_%s_%s_%d_%s_%s.ply" % (TMP, mesh, noise, seed, op, lab)
            p = subprocess.run([CLI, noisy, o, "--operator", op, "--threads", "1", "--json", "-q"] + extra,
                               capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
            if p.returncode:
                out[lab] = None
                continue
            j = json.loads(p.stdout.strip().splitlines()[-1])
            out[lab + "_ts"] = j["time_step"]
            if lab == "default":
                out.update(frozen=j["operator_frozen"], recomputed_risk=j["recomputed_risk"],
                           frozen_risk=j["frozen_risk"], sigma=j["noise_level_edges"])
            files.append((lab, o))
        out.update(F.evaluate(clean, truth, noisy, files))
        lines.append(json.dumps(out))
    print("\n".join(lines), flush=True)


with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
    list(ex.map(one, F.cases))
