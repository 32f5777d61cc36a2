#!/usr/bin/env python3
"""runs.jsonl (bench/run_bench.py) -> bench/results/results.md, plus a gnuplot PNG when available."""
import json, os, shutil, subprocess, sys

src, dst = sys.argv[1], sys.argv[2]
lines = [json.loads(l) for l in open(src)]
meta = lines[0]["meta"]
R = lines[1:]
meshes = []
for r in R:
    if r["mesh"] not in meshes:
        meshes.append(r["mesh"])


def get(mesh, prefix, group=None):
    for r in R:
        if r["mesh"] == mesh and r["method"].startswith(prefix) and (group is None or r["group"] == group):
            return r
    return None


def f(x, p=3):
    return "—" if x is None else ("%.*f" % (p, x))


def g(x):
    return "—" if x is None else ("%.2g" % x)


out = []
w = out.append
w("# End-to-end results\n")
w("`%s` on %s (%s, %d cores, %d GB), commit %s%s, %s. Run time %.1f min. Load average (1/5/15 min) "
  "%s before, %s after: **other jobs shared the 2 cores**, so wall times carry noise; compare rows of the "
  "same mesh (same run).\n" % (meta["command"].strip(), meta["machine"], meta["cpu"], meta["cores"], meta["mem_gb"],
  meta["git"], " + uncommitted engine changes" if meta["dirty"] else "", meta["date"], meta["minutes"],
  "/".join("%.1f" % x for x in meta["load_before"]), "/".join("%.1f" % x for x in meta["load_after"])))
w("Inputs: clean mesh + Gaussian noise of 0.25 mean edge along the normals (seed 1). Errors are RMS "
  "vertex-to-clean-surface distance in mean edge lengths (input noise ≈ 0.25); drift is the RMS tangential "
  "component of (result − clean) w.r.t. the clean normals, in mean edges; volume change vs the noisy input. "
  "Equal diffusion time t = %.3f h² (MeshLab's 10 cotangent Laplacian steps; mappings in bench/README.md). "
  "Seconds: engine time for ours (CLI `seconds_engine`), the algorithm call for CGAL/OpenMesh, and for MeshLab "
  "filters the meshlabserver wall time minus the same mesh's load+save-only run. Ratio = that time / ours "
  "(curvature flow L, 1 thread).\n" % meta["t_diff"])

for m in meshes:
    base = get(m, "MeshLab load+save only")
    ours = get(m, "ours CLI curvature L ts", "equal-time")
    info = next(r for r in R if r["mesh"] == m)
    w("## %s (%d vertices, %d faces)\n" % (m, info["vertices"], info["faces"]))
    w("| method (equal diffusion time) | seconds | ratio vs ours | CG its | error | volume Δ % | drift | peak RSS MB |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in R:
        if r["mesh"] != m or r["group"] != "equal-time":
            continue
        s = r["seconds"]
        if r["method"].startswith("MeshLab") or r["method"].startswith("ours plugin"):
            s = r["wall"] - base["wall"]
        r["_s"] = s
        noise = s <= 0.05
        w("| %s | %s | %s | %s | %s | %s | %s | %d |" % (
            r["method"], "≤ noise" if noise else f(s), "—" if noise else (f(s / ours["seconds"], 2) if ours and ours["seconds"] > 0 else "—"),
            r.get("cg_iterations") if r.get("cg_iterations") is not None else "",
            f(r.get("rms_result")), g(r.get("volume_change_percent")), f(r.get("tangential_drift")),
            r["peak_rss_kb"] // 1024))
    w("")
    w("| denoising (filters' defaults and a small sweep) | seconds | CG its | error | volume Δ % | drift |")
    w("|---|---:|---:|---:|---:|---:|")
    for r in R:
        if r["mesh"] != m or r["group"] != "denoise":
            continue
        s = r["seconds"] if r["method"].startswith("ours CLI") else r["wall"] - base["wall"]
        w("| %s | %s | %s | %s | %s | %s |" % (r["method"], "≤ noise" if s <= 0.05 else f(s), r.get("cg_iterations") or "",
                                               f(r.get("rms_result")), g(r.get("volume_change_percent")),
                                               f(r.get("tangential_drift"))))
    w("\nNoisy input error: %s mean edges.\n" % f(info.get("rms_input") or get(m, "ours CLI", "equal-time").get("rms_input")))

# ------------------------------------------------------------------ targets
w("## Issue 5 targets, from this run\n")
w("| mesh | CGAL / ours (≥ 6) | MeshLab Laplacian / ours (≥ 1.5) | 1 thread / 2 threads (≥ 1.6 above 500k vertices, ≥ 1 below) | ×16 step / unit step, L (≤ 2.5) | ×16 / default, L² (≤ 2.5) | plugin overhead in filter (≤ 30 %) | plugin wall − load/save − engine, % of engine | engine extra memory B/vertex (≤ 150) | best ours L² error / best Taubin error (≤ 1) | ours volume Δ % (≤ 1e-4) |")
w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for m in meshes:
    base = get(m, "MeshLab load+save only")
    ours = get(m, "ours CLI curvature L ts", "equal-time")
    two = get(m, "ours CLI curvature L ts=", "equal-time")
    two = next((r for r in R if r["mesh"] == m and "2 threads" in r["method"]), None)
    cg = get(m, "CGAL")
    lap = get(m, "MeshLab Laplacian")
    s16 = get(m, "ours CLI curvature L ts", "strength")
    d2 = get(m, "ours CLI curvature L² ts=22.5", "strength")
    d2x = get(m, "ours CLI curvature L² ts=360", "strength")
    plug = get(m, "ours plugin curvature")
    mem = get(m, "engine direct")
    oursd = [r for r in R if r["mesh"] == m and r["group"] == "denoise" and r["method"].startswith("ours") and r.get("rms_result") is not None]
    taub = [r for r in R if r["mesh"] == m and r["group"] == "denoise" and "Taubin" in r["method"]]
    bo = min(oursd, key=lambda r: r["rms_result"]) if oursd else None
    bt = min(taub, key=lambda r: r["rms_result"]) if taub else None
    lap_s = lap["wall"] - base["wall"] if lap else None
    over_in = (plug["plugin_total"] - plug["plugin_engine"]) / plug["plugin_engine"] * 100 if plug and plug.get("plugin_engine") else None
    over_wall = (plug["wall"] - base["wall"] - ours["seconds"]) / ours["seconds"] * 100 if plug else None
    vols = [abs(r["volume_change_percent"]) for r in R if r["mesh"] == m and r["method"].startswith("ours") and r.get("volume_change_percent") is not None]
    w("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s (%s vs %s) | %s |" % (
        m, f(cg["seconds"] / ours["seconds"], 2) if cg else "—", f(lap_s / ours["seconds"], 2) if lap and lap_s > 0.05 else "noise",
        f(ours["seconds"] / two["seconds"], 2) if two else "—",
        f(s16["seconds"] / ours["seconds"], 2) if s16 else "—", f(d2x["seconds"] / d2["seconds"], 2) if d2 and d2x else "—",
        f(over_in, 0), f(over_wall, 0) if plug and plug["wall"] - base["wall"] > 0.05 else "noise", f(mem["extra_bytes_per_vertex"], 0) if mem else "—",
        f(bo["rms_result"] / bt["rms_result"], 2) if bo and bt else "—", bo["method"].replace("ours CLI ", "").replace("ours plugin ", "plugin ") if bo else "",
        bt["method"].replace("MeshLab Taubin Smooth ", "Taubin ") if bt else "", g(max(vols)) if vols else "—"))
w("")
open(dst, "w").write("\n".join(out) + "\n")

# ------------------------------------------------------------------ plot (seconds vs faces)
if shutil.which("gnuplot"):
    series = [("ours CLI curvature L ts", "ours curvature L"), ("CGAL", "CGAL smooth_shape"),
              ("MeshLab Laplacian", "MeshLab Laplacian x10"), ("OpenMesh", "OpenMesh Jacobi")]
    d = os.path.dirname(dst)
    files = []
    for i, (pre, label) in enumerate(series):
        pts = []
        for m in meshes:
            r = get(m, pre, "equal-time")
            if r and r.get("_s", r["seconds"]) > 0:
                pts.append((r["faces"], r.get("_s", r["seconds"])))
        pts.sort()
        fn = os.path.join(d, ".plot%d.dat" % i)
        open(fn, "w").write("".join("%d %g\n" % p for p in pts))
        files.append((fn, label))
    png = os.path.join(d, "time_vs_faces.png")
    cmd = ("set terminal pngcairo size 640,420 font ',9'; set output '%s'; set logscale xy; set key left top;"
           "set xlabel 'faces'; set ylabel 'seconds (equal diffusion time)'; set grid;"
           "plot %s" % (png, ", ".join("'%s' using 1:2 with linespoints title '%s'" % fl for fl in files)))
    subprocess.run(["gnuplot", "-e", cmd], check=False)
    for fn, _ in files:
        os.remove(fn)
