#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43: each filter's one click with two CLIs (A= before, B= after) on every
# case of the seven sets (session41-probe/freeze.py's list): the noise estimate, the time step
# and the error of each, one JSON line per case. OPS= the filters, JOBS= parallel runs (2).
# Usage: A=/tmp/old/implicit-fairing B=build/bin/implicit-fairing python3 screen.py > screen.jsonl
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session41-probe"))
_argv, sys.argv = sys.argv, sys.argv[:1]
import freeze as F  # noqa: E402
sys.argv = _argv
CLIS = {"a": os.environ["A"], "b": os.environ["B"]}
OPS = os.environ.get("OPS", "umbrella scale-dependent curvature").split()
TMP = os.environ.get("TMPDIR", "/tmp")


def one(c):
    d, seed, mesh, noise, truth = c
    noisy = F.noisy_of(seed, mesh, noise)
    clean = "%s/dn_%s_clean.ply" % (F.M, mesh)
    out = dict(set=d, mesh=mesh, noise=noise)
    files = []
    for op in OPS:
        for lab, cli in CLIS.items():
            o = "%s/scr_%s_%s_%d_%s_%s.ply" % (TMP, mesh, noise, seed, op, lab)
            p = subprocess.run([cli, noisy, o, "--operator", op, "--threads", "1", "--json", "-q"],
                               capture_output=True, text=True,
                               env=dict(os.environ, OMP_NUM_THREADS="1"))
            k = op[:3] + "_" + lab
            if p.returncode:
                out[k] = None
                continue
            j = json.loads(p.stdout.strip().splitlines()[-1])
            out[k + "_ts"] = j["time_step"]
            out[k + "_sig"] = j["noise_level_edges"]
            files.append((k, o))
    out.update(F.evaluate(clean, truth, noisy, files))
    print(json.dumps(out), flush=True)


with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
    list(ex.map(one, F.cases))
