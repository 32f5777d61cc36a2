# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 41: the curvature flow's one click, recomputed (the default) and with
# --freeze, on every case of every study set (the cases with an 'ours CLI auto' row); one JSON
# line per case with both errors and time steps. I= the CLI; JOBS= parallel runs (2).
# Usage: I=build/bin/implicit-fairing python3 freeze.py > freeze.jsonl
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
HERE = os.path.dirname(os.path.abspath(__file__))
R = os.path.join(HERE, "..", "..")
SETS = [("denoise", 1), ("denoise-seed2", 2), ("denoise-seed8", 8), ("denoise-noise", 7),
        ("heldout-s11", 11), ("heldout-s13", 13), ("heldout-s17", 17)]
M = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-meshes")
DT = os.path.expanduser("~/.cache/filter_implicit_fairing/bench-build/bench/bin/fairing-denoise-tool")
CLI = os.environ.get("I", "build/bin/implicit-fairing")  # the CLI to run
TMP = os.environ.get("TMPDIR", "/tmp")
EXTRA = sys.argv[1:]  # variants: each "label=args with spaces"
STUDY = {"n0.1", "n0.25", "n0.5", "iso0.25"}
cases = []
for d, seed in SETS:
    f = R + "/" + d + ".jsonl" if d == "denoise" else R + "/" + d + "/denoise.jsonl"
    rows = [json.loads(l) for l in open(f)]
    truth = {m["name"]: m["truth"] for m in rows[0]["meta"]["meshes"]}
    seen = set()
    for r in rows[1:]:
        if r.get("method") == "ours CLI auto" and (r["mesh"], r["noise"]) not in seen:
            seen.add((r["mesh"], r["noise"]))
            cases.append((d, seed, r["mesh"], r["noise"], truth[r["mesh"]]))
def noisy_of(seed, mesh, noise):
    s = "" if seed == 1 else "_s%d" % seed
    p = "%s/dn_%s_%s%s.ply" % (M, mesh, noise, s)
    if os.path.exists(p): return p
    sig = noise.lstrip("niso")
    kind = "iso" if noise.startswith("iso") else "normal"
    return "%s/dn_%s_%s_%s%s%s.ply" % (M, mesh, noise, sig, kind, s)
def evaluate(clean, truth, noisy, files):
    """fairing-denoise-tool eval of the outputs in files ((label, path), ...): {label: rms};
    the outputs are removed."""
    ev = subprocess.run([DT, "eval", clean, truth, noisy] + [o for _, o in files],
                        capture_output=True, text=True).stdout
    e = {json.loads(l)["file"]: json.loads(l) for l in ev.splitlines() if l.startswith("{")}
    for _, o in files:
        os.remove(o)
    return {lab: e[o]["rms"] for lab, o in files}
def best_fixed(steps_of):
    """The best fixed L^2 step's error per (set, mesh, noise, op) in each set's committed extract,
    for the filters of steps_of ({op: steps})."""
    best = {}
    for d, _ in SETS:
        f = os.path.join(R, "denoise.jsonl" if d == "denoise" else d + "/denoise.jsonl")
        for l in open(f):
            r = json.loads(l)
            if (r.get("method") != "ours" or r.get("order") != 2 or r.get("op") not in steps_of
                    or r.get("steps") != steps_of[r["op"]] or r.get("kind") == "auto"):
                continue
            k = (d, r["mesh"], r["noise"], r["op"])
            best[k] = min(best.get(k, float("inf")), r["rms"])
    return best
variants = [("default", []), ("freeze", ["--freeze"])] + [
    (v.split("=", 1)[0], v.split("=", 1)[1].split()) for v in EXTRA]
def one(c):
    d, seed, mesh, noise, truth = c
    noisy = noisy_of(seed, mesh, noise)
    clean = "%s/dn_%s_clean.ply" % (M, mesh)
    out = dict(set=d, mesh=mesh, noise=noise)
    tag = "%s/o_%s_%s_%d" % (TMP, mesh, noise, seed)
    files = []
    for lab, args in variants:
        o = "%s_%s.ply" % (tag, lab)
        p = subprocess.run([CLI, noisy, o, "--operator", "curvature", "--threads", "1", "--json", "-q"]
                           + args, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        if p.returncode != 0:
            out[lab] = None; out[lab + "_err"] = p.stderr[:200]; continue
        j = json.loads(p.stdout.strip().splitlines()[-1])
        out[lab + "_ts"] = j.get("time_step"); files.append((lab, o))
    if files:
        ev = subprocess.run([DT, "eval", clean, truth, noisy] + [o for _, o in files],
                            capture_output=True, text=True).stdout
        e = {json.loads(l)["file"]: json.loads(l) for l in ev.splitlines() if l.startswith("{")}
        for lab, o in files:
            out[lab] = e[o]["rms"]; os.remove(o)
    print(json.dumps(out), flush=True)
if __name__ == "__main__":
    with ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as ex:
        list(ex.map(one, cases))
