# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 42: how far the curvature flow's one-standard-error rule reaches beyond the
# risk's minimizer, and the error of a reach capped at K times the minimizer (K in CAPS), on every
# case of the study's seven sets. I= a CLI built with throwaway.patch (FAIRING_DUMP_CHOOSE).
# Usage: I=/tmp/eb/bin/implicit-fairing python3 cap.py > cap.jsonl
# The cap's runs give the surface step explicitly, which fixes open meshes' loops (--boundary
# auto); ENGINE_CAP=1 caps the engine's own choice instead (FAIRING_CAP), the loops automatic.
# OP= and ARGS= run another filter or setting (default: the curvature flow's one click).
# CASES=FILE runs the lines "SET MESH NOISE NOISY CLEAN TRUTH" of FILE instead (held-out meshes).
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "session41-probe"))
import freeze as F  # noqa: E402  (cases, noisy_of, M, DT; its own run is guarded below)

OP = os.environ.get("OP", "curvature")  # the filter, and further CLI options (ARGS="--order 1")
ARGS = os.environ.get("ARGS", "").split()
CAPS = [float(k) for k in os.environ.get("CAPS", "1 1.5 2").split()]


def run(noisy, out, extra, dump=False, cap=None):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    if dump: env["FAIRING_DUMP_CHOOSE"] = "1"
    if cap: env["FAIRING_CAP"] = repr(cap)
    p = subprocess.run([F.CLI, noisy, out, "--operator", OP, "--threads", "1", "--json", "-q"]
                       + ARGS + extra, capture_output=True, text=True, env=env)
    if p.returncode != 0: return None, p.stderr
    return json.loads(p.stdout.strip().splitlines()[-1]), p.stderr


def one(c):
    d, mesh, noise, noisy, clean, truth = c
    tag = "%s/c_%s_%s_%s" % (F.TMP, mesh, noise, d)
    out = dict(set=d, mesh=mesh, noise=noise, truth=truth)
    j, err = run(noisy, tag + "_auto.ply", [], dump=True)
    if j is None:
        out["error"] = err[:200]; print(json.dumps(out), flush=True); return
    # The surface's choice: the last rule-1 dump (the curvature flow's L^2 steps).
    lines = [l.split() for l in err.splitlines() if l.startswith("CHOOSE rule=1")]
    out["dumps"] = len(lines)
    files = [("auto", tag + "_auto.ply")]
    out["auto_ts"] = j["time_step"]
    if lines:
        f = lines[-1]
        best = int(f[2].split("=")[1]); s2 = float(f[4].split("=")[1])
        pts = [tuple(map(float, x.split(":"))) for x in f[5:]]
        grid = [p[0] for p in pts]; risk = [p[1] for p in pts]; tr = [p[2] for p in pts]
        strongest = best
        for g in range(best + 1, len(grid)):
            if risk[g] <= risk[best] + s2 * (2 * abs(tr[best] - tr[g])) ** 0.5: strongest = g
        out.update(best=best, strongest=strongest, top=len(grid) - 1,
                   reach=grid[strongest] / grid[best], grid_ratio=grid[-1] / grid[0],
                   df=tr[best], ddf=tr[best] - tr[strongest],
                   rise=(risk[strongest] - risk[best]) / (s2 * float(f[3].split("=")[1])))
        unit = j["time_step"] / grid[strongest]
        for k in CAPS:
            if grid[strongest] > k * grid[best] * 1.0001:
                ts = k * grid[best] * unit
                o = "%s_cap%g.ply" % (tag, k)
                # ENGINE_CAP=1: the engine's own choice capped (FAIRING_CAP), so that open
                # meshes keep their loops' automatic step; else the surface step given.
                jj, _ = (run(noisy, o, [], cap=k) if os.environ.get("ENGINE_CAP")
                         else run(noisy, o, ["--time-step", repr(ts)]))
                if jj is not None: files.append(("cap%g" % k, o)); out["cap%g_ts" % k] = ts
    ev = subprocess.run([F.DT, "eval", clean, truth, noisy] + [o for _, o in files],
                        capture_output=True, text=True).stdout
    e = {json.loads(l)["file"]: json.loads(l) for l in ev.splitlines() if l.startswith("{")}
    for lab, o in files:
        out[lab] = e[o]["rms"]; os.remove(o)
    print(json.dumps(out), flush=True)


with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
    if os.environ.get("CASES"):
        cases = [l.split() for l in open(os.environ["CASES"]) if l.strip()]
    else:
        cases = [(d, mesh, noise, F.noisy_of(seed, mesh, noise),
                  "%s/dn_%s_clean.ply" % (F.M, mesh), truth) for d, seed, mesh, noise, truth in F.cases]
    list(ex.map(one, cases))
