# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 41 (not kept): the curvature flow at fixed time steps with throwaway.patch's
# variants. Usage: I=<CLI built with the patch> VARS='floor5=EXP_MASS_FLOOR:0.5 ...'
#   python3 sweep_variants.py NOISY-BASENAME MESH TRUTH TS1,TS2,...
import json, os, subprocess, sys
M = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-meshes")
DT = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-build/bench/bin/fairing-denoise-tool")
CLI = os.environ.get("I", "build/bin/implicit-fairing")
TMP = os.environ.get("TMPDIR", "/tmp")
b, mesh, truth = sys.argv[1:4]; tss = [float(x) for x in sys.argv[4].split(",")]
variants = [(v.split("=")[0], dict([v.split("=")[1].split(":")]) if ":" in v else {}, []) for v in os.environ["VARS"].split()]
noisy = "%s/%s.ply" % (M, b); clean = "%s/dn_%s_clean.ply" % (M, mesh)
res = {}
files = []
for lab, env, args in variants:
    for ts in tss:
        o = TMP + "/w_%s_%s_%g.ply" % (b, lab, ts)
        p = subprocess.run([CLI, noisy, o, "--operator", "curvature", "--threads", "1", "-q", "--time-step", repr(ts)] + args,
                           capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1", **env))
        if p.returncode == 0: files.append((lab, ts, o))
ev = subprocess.run([DT, "eval", clean, truth, noisy] + [o for *_, o in files], capture_output=True, text=True).stdout
e = {json.loads(l)["file"]: json.loads(l) for l in ev.splitlines() if l.startswith("{")}
for lab, ts, o in files: res.setdefault(lab, []).append("%g:%.4f" % (ts, e[o]["rms"])); os.remove(o)
for lab in res: print(b, lab, " ".join(res[lab]))
