# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 41: each filter's one click at --order 3 and 4 on the study's open meshes,
# with two CLIs: OLD (the loops' automatic step from the Lanczos model at these orders) and NEW
# (by direct solves); one JSON line per run with both errors and loop time steps.
# Usage: OLD=<CLI of 94fed4e> NEW=build/bin/implicit-fairing python3 loops.py > loops.jsonl
import json, os, subprocess
from concurrent.futures import ThreadPoolExecutor
M = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-meshes")
DT = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-build/bench/bin/fairing-denoise-tool")
TMP = os.environ.get("TMPDIR", "/tmp")
OPEN = {"plane_3k": "plane", "dragon_20k": "mesh", "b9_10k": "mesh", "mannequin_26k": "mesh",
        "shark_10k": "mesh", "blade_16k": "mesh", "lionhead_17k": "mesh"}
runs = []
for mesh, truth in OPEN.items():
    for f in sorted(os.listdir(M)):
        if f.startswith("dn_%s_" % mesh) and not f.endswith("_clean.ply"):
            for op in ("umbrella", "scale-dependent", "curvature"):
                for order in (3, 4):
                    runs.append((mesh, truth, f[:-4], op, order))
def one(r):
    mesh, truth, b, op, order = r
    out = dict(case=b, op=op, order=order); files = []
    for lab in ("OLD", "NEW"):
        o = "%s/loops_%s_%s_%d_%s.ply" % (TMP, b, op, order, lab)
        p = subprocess.run([os.environ[lab], "%s/%s.ply" % (M, b), o, "--operator", op, "--order", str(order),
                            "--threads", "1", "--json", "-q"], capture_output=True, text=True,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        if p.returncode: out[lab] = None; out[lab + "_err"] = p.stderr[-200:]; continue
        j = json.loads(p.stdout.strip().splitlines()[-1])
        out[lab + "_bts"] = j["boundary_time_step"]; out[lab + "_ts"] = j["time_step"]
        out[lab + "_warn"] = len(j.get("warnings", [])); files.append((lab, o))
    ev = subprocess.run([DT, "eval", "%s/dn_%s_clean.ply" % (M, mesh), truth, "%s/%s.ply" % (M, b)]
                        + [o for _, o in files], capture_output=True, text=True).stdout
    e = {json.loads(l)["file"]: json.loads(l) for l in ev.splitlines() if l.startswith("{")}
    for lab, o in files: out[lab] = e[o]["rms"]; os.remove(o)
    print(json.dumps(out), flush=True)
with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
    list(ex.map(one, runs))
