#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""runs.jsonl (bench/run_bench.py) -> results.md, plus a gnuplot PNG when available.

    report.py RUNS.jsonl RESULTS.md

The "Targets" table at the top is computed here from the runs of RUNS.jsonl only (the end-to-end
records and, when run.sh ran them, the micro-benchmark records of the same run): nothing in it is
typed by hand. Thresholds are the issue's; the per-mesh tables follow."""
import json, os, shutil, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_micro import derived as micro_derived, CG_PER_PRODUCT, ASSEMBLY_IN_CG  # noqa: E402

src, dst = sys.argv[1], sys.argv[2]
lines = [json.loads(l) for l in open(src)]
meta = lines[0]["meta"]
R = [r for r in lines[1:] if "mesh" in r]
MICRO = [r for r in lines[1:] if "micro" in r]
meshes = []
for r in R:
    if r["mesh"] not in meshes:
        meshes.append(r["mesh"])
info = {m: next(r for r in R if r["mesh"] == m) for m in meshes}
T = meta["t_diff"]
BIG_FACES = 1000000        # target a: ">= 1 M faces"
MANY_VERTICES = 500000     # target c: "above 500 k vertices"
CLI_REPEAT = meta.get("cli_repeat", 1)  # runs per compared CLI row (the fastest kept)


def f(x, p=3):
    return "—" if x is None else ("%.*f" % (p, x))


def g(x):
    return "—" if x is None else ("%.2g" % x)


def q(x, y):
    return x / y if x is not None and y else None


def get(mesh, prefix, group=None):
    for r in R:
        if r["mesh"] == mesh and r["method"].startswith(prefix) and (group is None or r["group"] == group):
            return r
    return None


def cli(mesh, op, order, ts, threads=1, pre="auto", group=None):
    for r in R:
        if (r["mesh"] == mesh and r["method"].startswith("ours CLI") and r.get("op") == op and r.get("order") == order
                and abs(r.get("time_step", -1) - ts) < 1e-9 * max(1, ts) and r.get("threads") == threads
                and r.get("preconditioner", "auto") == pre and (group is None or r["group"] == group)):
            return r
    return None


def is_big(m):
    return info[m]["faces"] >= 0.999 * BIG_FACES


def unit_l(m):
    return cli(m, "curvature", 1, 6 * T, group="equal-time")


# ------------------------------------------------------------------ targets
targets = []   # (target, case, measured text, threshold text, ok: True/False/None)


def status(ok):
    return "n/a" if ok is None else ("met" if ok else "**missed**")


def le(x, lim):
    return None if x is None else x <= lim


def ge(x, lim):
    return None if x is None else x >= lim


# a. one curvature-flow step on >= 1M faces vs CGAL and MeshLab's Laplacian, equal diffusion time
a_meshes = [m for m in meshes if is_big(m)]
a_note = ""
if not a_meshes and meshes:
    a_meshes = [max(meshes, key=lambda m: info[m]["faces"])]
    a_note = " (< 1 M faces: info)"
for m in a_meshes:
    ours = unit_l(m)
    plug = get(m, "ours plugin curvature L", "equal-time")
    cg, lap = get(m, "CGAL", "equal-time"), get(m, "MeshLab Laplacian", "equal-time")
    os_ = ours["seconds"] if ours else None
    info_only = bool(a_note)
    x = q(cg["seconds"], os_) if cg else None
    targets.append(("a. CGAL smooth_shape / ours CLI (engine), same time", m + a_note,
                    "%s (%s s / %s s)" % (f(x, 2), f(cg and cg["seconds"]), f(os_)), "≥ 6",
                    None if info_only else ge(x, 6)))
    # CGAL's smooth_shape (a sparse Cholesky factorization) runs on one core; the engine may use
    # both of this machine's: shown beside the one-thread figure, never in its place.
    two = cli(m, "curvature", 1, 6 * T, threads=2)
    x = q(cg["seconds"], two["seconds"]) if cg and two else None
    targets.append(("a. CGAL smooth_shape / ours CLI (engine, 2 threads), same time", m + a_note,
                    "%s (%s s / %s s)" % (f(x, 2), f(cg and cg["seconds"]), f(two and two["seconds"])),
                    "≥ 6", None if info_only else ge(x, 6)))
    x = q(lap["seconds"], os_) if lap else None
    targets.append(("a. MeshLab Laplacian ×%d (applyFilter) / ours CLI (engine)" % meta["ml_steps"], m + a_note,
                    "%s (%s s / %s s)" % (f(x, 2), f(lap and lap["seconds"]), f(os_)), "≥ 1.5",
                    None if info_only else ge(x, 1.5)))
    x = q(lap["seconds"], plug["seconds"]) if lap and plug else None
    targets.append(("a. MeshLab Laplacian ×%d / ours plugin (both applyFilter)" % meta["ml_steps"], m + a_note,
                    "%s (%s s / %s s)" % (f(x, 2), f(lap and lap["seconds"]), f(plug and plug["seconds"])), "≥ 1.5",
                    None if info_only else ge(x, 1.5)))
if not meshes:
    targets.append(("a.", "no mesh in this run", "—", "", None))

# b. micro-benchmarks of the same run
mrows = {r["micro"]: dict(real=r["real_ms"], cpu=r["cpu_ms"], v=r.get("vertices", 0), its=r.get("cg_iterations"))
         for r in MICRO}
D = micro_derived(mrows) if mrows else []
if not D:
    targets.append(("b. CG iteration / product; assembly / CG iteration", "micro-benchmarks not run (--no-micro)",
                    "—", "≤ %.1f; ≤ %g" % (CG_PER_PRODUCT, ASSEMBLY_IN_CG), None))
for d in D:
    case = "micro, torus %s faces" % ("%dM" % (d["faces"] // 1000000) if d["faces"] >= 1000000 else "%dk" % (d["faces"] // 1000))
    targets.append(("b. one CG iteration L / one 3-column product (apply_k)", case,
                    "%s (%s / %s ms)" % (f(d["it1_apply_k"], 2), f(d["cg_it1"]), f(d["apply_k"])),
                    "≤ %.1f" % CG_PER_PRODUCT, le(d["it1_apply_k"], CG_PER_PRODUCT)))
    targets.append(("b. one CG iteration L / system_apply L (product + diagonal)", case,
                    "%s (%s / %s ms)" % (f(d["it1_system"], 2), f(d["cg_it1"]), f(d["system_apply1"])),
                    "≤ %.1f" % CG_PER_PRODUCT, le(d["it1_system"], CG_PER_PRODUCT)))
    targets.append(("b. one CG iteration L² / system_apply L² (2 products)", case,
                    "%s (%s / %s ms)" % (f(d["it2_system"], 2), f(d["cg_it2"]), f(d["system_apply2"])),
                    "≤ %.1f" % CG_PER_PRODUCT, le(d["it2_system"], CG_PER_PRODUCT)))
    targets.append(("b. assembly (curvature) / one CG iteration L", case,
                    "%s (%s / %s ms)" % (f(d["assembly_in_cg"], 1), f(d["assembly"]), f(d["cg_it1"])),
                    "≤ %g" % ASSEMBLY_IN_CG, le(d["assembly_in_cg"], ASSEMBLY_IN_CG)))

# c. two threads vs one (CLI, curvature L at equal time)
for m in meshes:
    one, two = unit_l(m), cli(m, "curvature", 1, 6 * T, threads=2)
    xe = q(one["seconds"], two["seconds"]) if one and two else None
    xt = q(one.get("seconds_total"), two.get("seconds_total")) if one and two else None
    many = info[m]["vertices"] >= MANY_VERTICES
    # Below 50,000 vertices the engine runs one thread whatever is asked (kernels.h), so the two
    # runs execute the same code: their ratio is timing noise, judged within 5 %.
    single = info[m]["vertices"] < 50000
    lim = 1.6 if many else 0.95 if single else 1.0
    note = "" if many else " (same code: one thread below 50 k vertices; 5 % noise)" if single else " (not slower)"
    targets.append(("c. ours CLI 1 thread / 2 threads (engine; total), fastest of %s" % CLI_REPEAT, m,
                    "%s; total %s" % (f(xe, 2), f(xt, 2)), "≥ %.2g%s" % (lim, note),
                    ge(xe, lim)))

# d. a step 16x stronger costs at most 2.5x the unit step
for m in meshes:
    u, s16 = unit_l(m), cli(m, "curvature", 1, 96 * T, group="strength")
    x = q(s16["seconds"], u["seconds"]) if u and s16 else None
    targets.append(("d. curvature L: time(96t) / time(6t)", m,
                    "%s (%s / %s s; CG %s / %s)" % (f(x, 2), f(s16 and s16["seconds"]), f(u and u["seconds"]),
                                                  s16 and s16.get("cg_iterations"), u and u.get("cg_iterations")),
                    "≤ 2.5", le(x, 2.5)))
    l1, l16 = cli(m, "curvature", 2, 22.5, group="strength"), cli(m, "curvature", 2, 360, group="strength")
    j1, j16 = (cli(m, "curvature", 2, 22.5, pre="jacobi", group="strength"),
               cli(m, "curvature", 2, 360, pre="jacobi", group="strength"))
    x = q(l16["seconds"], l1["seconds"]) if l1 and l16 else None
    xj = q(j16["seconds"], j1["seconds"]) if j1 and j16 else None
    its = lambda r: "—" if r is None else "%s%s" % (r.get("cg_iterations"), "+%s inner" % r["inner_iterations"]
                                                    if r.get("inner_iterations") else "")
    targets.append(("d. curvature L², auto preconditioner: time(360) / time(22.5)", m,
                    "%s (%s / %s s; CG %s / %s); jacobi: %s" % (f(x, 2), f(l16 and l16["seconds"]),
                                                                 f(l1 and l1["seconds"]), its(l16), its(l1),
                                                                 f(xj, 2) if xj else "not run"),
                    "≤ 2.5", le(x, 2.5)))

# e. plugin overhead and memory
for m in meshes:
    plug = get(m, "ours plugin curvature L", "equal-time")
    ov = plug.get("overhead") if plug else None
    targets.append(("e. plugin overhead: (applyFilter − engine) / engine", m,
                    "%s %% (%s s − %s s)" % (f(ov * 100 if ov is not None else None, 1), f(plug and plug["seconds"]),
                                            f(plug and plug.get("engine_seconds"))), "≤ 30 %", le(ov, 0.30)))
for m in meshes:
    mem = get(m, "engine direct", "memory")
    x = mem.get("extra_bytes_per_vertex") if mem else None
    targets.append(("e. engine extra peak memory, bytes / vertex", m, f(x, 0), "≤ 150", le(x, 150)))

# f. denoising on the real scans vs MeshLab's Taubin Smooth, volume kept
if not any(m.startswith("bunny") for m in meshes):
    targets.append(("f. best ours error / best Taubin error (real scan); ours volume Δ", "no real scan in this run",
                    "—", "≤ 1; ≤ 1e-4 %", None))
for m in meshes:
    if not m.startswith("bunny"):
        continue
    oursd = [r for r in R if r["mesh"] == m and r["group"] == "denoise" and r["method"].startswith("ours")
             and r.get("rms_result") is not None]
    taub = [r for r in R if r["mesh"] == m and r["group"] == "denoise" and "Taubin" in r["method"]
            and r.get("rms_result") is not None]
    bo = min(oursd, key=lambda r: r["rms_result"]) if oursd else None
    bt = min(taub, key=lambda r: r["rms_result"]) if taub else None
    x = q(bo["rms_result"], bt["rms_result"]) if bo and bt else None
    vol = abs(bo["volume_change_percent"]) if bo and bo.get("volume_change_percent") is not None else None
    ok = None if x is None or vol is None else (x <= 1 and vol <= 1e-4)
    targets.append(("f. best ours error / best Taubin error (real scan); ours volume Δ", m,
                    "%s (%s vs %s); volume Δ %s %%" % (
                        f(x, 2), bo["method"].replace("ours CLI ", "").replace("ours plugin ", "plugin ") if bo else "—",
                        bt["method"].replace("MeshLab Taubin Smooth ", "Taubin ") if bt else "—", g(vol)),
                    "≤ 1; ≤ 1e-4 %", ok))

# g. issue 12: the default L² step as cheap as a first-order step (engine direct, fastest of N)
def eng(mesh, op, order, ts, steps=1, threads=1, freeze=False):
    for r in R:
        if (r["mesh"] == mesh and r["group"] == "issue12" and r.get("op") == op and r.get("order") == order
                and not r.get("automatic")
                and abs(r.get("time_step", -1) - ts) < 1e-9 * max(1, ts) and r.get("steps") == steps
                and r.get("threads") == threads and bool(r.get("freeze")) == freeze):
            return r
    return None


def its(r):
    return "—" if r is None else str(r.get("cg_iterations"))


def cpu(r):
    """One-thread rows: process CPU time of fair() (the shared machine's waits left out)."""
    return None if r is None else r.get("cpu_seconds", r["seconds"])


def wall(r):
    return None if r is None else r["seconds"]


for m in meshes:
    if not any(r["mesh"] == m and r["group"] == "issue12" for r in R):
        continue
    taubin = get(m, "MeshLab Taubin Smooth ×10", "issue12")
    for op, ts in ((("umbrella", 10.0), ("scale-dependent", 2.5), ("curvature", 22.5))):
        l2, l1, two = eng(m, op, 2, ts), eng(m, op, 1, ts ** 0.5), eng(m, op, 2, ts, threads=2)
        x = q(cpu(l2), cpu(l1))
        targets.append(("g. %s L² ts=%g / L ts=%.3g (equal cutoff), 1 thread, CPU s" % (op, ts, ts ** 0.5), m,
                        "%s (%s s / %s s; iterations %s / %s)" % (f(x, 2), f(cpu(l2)), f(cpu(l1)), its(l2), its(l1)),
                        "≤ 1.3", le(x, 1.3)))
        x = q(wall(l2), wall(taubin))
        targets.append(("g. %s L² ts=%g (engine wall) / MeshLab Taubin Smooth ×10 (applyFilter)" % (op, ts), m,
                        "%s (%s s / %s s)" % (f(x, 2), f(wall(l2)), f(wall(taubin))), "< 1",
                        None if x is None else x < 1))
        x = q(wall(l2), wall(two))
        targets.append(("g. %s L² ts=%g: 1 thread / 2 threads, wall" % (op, ts), m,
                        "%s (%s s / %s s)" % (f(x, 2), f(wall(l2)), f(wall(two))), "≥ 1.6", ge(x, 1.6)))
    s1 = eng(m, "curvature", 1, 22.5 ** 0.5)
    strong = eng(m, "curvature", 1, 16 * 22.5 ** 0.5)
    x = q(cpu(strong), cpu(s1))
    targets.append(("g. curvature L: time(16 × %.3g) / time(%.3g), CPU s" % (22.5 ** 0.5, 22.5 ** 0.5), m,
                    "%s (%s s / %s s; iterations %s / %s)" % (f(x, 2), f(cpu(strong)), f(cpu(s1)), its(strong), its(s1)),
                    "≤ 1.5", le(x, 1.5)))
    unit, strong = eng(m, "curvature", 2, 22.5), eng(m, "curvature", 2, 360.0)
    x = q(cpu(strong), cpu(unit))
    targets.append(("g. curvature L²: time(360) / time(22.5), CPU s", m,
                    "%s (%s s / %s s; iterations %s / %s)" % (f(x, 2), f(cpu(strong)), f(cpu(unit)), its(strong), its(unit)),
                    "≤ 1.5", le(x, 1.5)))
    ten = eng(m, "curvature", 2, 22.5, steps=10, freeze=True)
    x = q(cpu(ten), cpu(unit))
    targets.append(("g. curvature L² ts=22.5: 10 steps, frozen operator / 1 step, CPU s", m,
                    "%s (%s s / %s s; iterations %s / %s)" % (f(x, 2), f(cpu(ten)), f(cpu(unit)), its(ten), its(unit)),
                    "≤ 3", le(x, 3)))
    # The one-click defaults: the automatic time step (bench/run_bench.py engine(..., "auto")).
    for op in ("umbrella", "scale-dependent", "curvature"):
        autos = {r.get("threads", 1): r for r in R if r["mesh"] == m and r["group"] == "issue12"
                 and r.get("automatic") and r.get("op") == op and r.get("steps", 1) == 1}
        whole = next((r for r in R if r["mesh"] == m and r["group"] == "issue12" and r.get("automatic")
                      and r.get("op") == op and r.get("steps", 1) > 1), None)
        auto = autos.get(1)
        if auto is None:
            continue
        x = q(wall(auto), wall(autos.get(2)))
        targets.append(("g. one-click %s L² (automatic strength and step): 1 thread / 2 threads, wall" % op, m,
                        "%s (%s s / %s s)" % (f(x, 2), f(wall(auto)), f(wall(autos.get(2)))), "≥ 1.6", ge(x, 1.6)))
        ts = auto["time_step"]
        l2, l1 = eng(m, op, 2, ts), eng(m, op, 1, ts ** 0.5)
        x = q(cpu(l2), cpu(l1))
        targets.append(("g. %s L² at the automatic default's ts=%.4g / L ts=%.4g (equal cutoff), 1 thread, CPU s"
                        % (op, ts, ts ** 0.5), m,
                        "%s (%s s / %s s; iterations %s / %s)" % (f(x, 2), f(cpu(l2)), f(cpu(l1)), its(l2), its(l1)),
                        "≤ 1.3", le(x, 1.3)))
        x = auto.get("extra_bytes_per_vertex")
        targets.append(("g. engine extra peak memory at the one-click default (%s L², automatic ts=%.4g), bytes / vertex"
                        % (op, ts), m, "%s (estimate %s s, step and estimate %s s CPU)" % (
                            f(x, 0), f(auto.get("strength_seconds")), f(cpu(auto))), "≤ 150", le(x, 150)))
        if whole:
            x = whole.get("extra_bytes_per_vertex")
            targets.append(("g. engine extra peak memory of the whole one-click run (%s L² ×%d, automatic ts=%.4g), "
                            "bytes / vertex" % (op, whole["steps"], whole["time_step"]), m,
                            "%s (estimate %s s, all %s s CPU; iterations %s)" % (
                                f(x, 0), f(whole.get("strength_seconds")), f(cpu(whole)), its(whole)),
                            "≤ 150", le(x, 150)))
    for op, ts in ((("umbrella", 10.0), ("scale-dependent", 2.5), ("curvature", 22.5))):
        r = eng(m, op, 2, ts)
        x = r and r.get("extra_bytes_per_vertex")
        targets.append(("g. engine extra peak memory at the default (%s L² ts=%g), bytes / vertex" % (op, ts), m,
                        f(x, 0), "≤ 150", le(x, 150)))

# ------------------------------------------------------------------ results.md
out = []
w = out.append
w("# Benchmark results\n")
w("`%s` on %s (%s, %d cores, %d GB), commit %s%s, %s. Run time %.1f min%s. Load average (1/5/15 min) "
  "%s before, %s after (a loaded machine makes wall times noisy: compare rows of the same run).\n" % (
      meta["command"].strip(), meta["machine"], meta["cpu"], meta["cores"], meta["mem_gb"],
      meta["git"], " + uncommitted engine changes" if meta["dirty"] else "", meta["date"], meta["minutes"],
      "" if meta.get("complete", True) else " (**partial: the run is still going or was stopped**)",
      "/".join("%.1f" % x for x in meta["load_before"]), "/".join("%.1f" % x for x in meta["load_after"])))
w("## Targets\n")
w("Every ratio below is computed by `bench/report.py` from `runs.jsonl` of this run. Seconds: ours CLI = "
  "`seconds_engine` (1 thread unless said); MeshLab filters and our plugin = `applyFilter` alone, timed "
  "in-process by `meshlab_filter_timer` (median of %d); CGAL/OpenMesh = the algorithm call. b comes from the "
  "micro-benchmarks of the same run (cpu time; details in micro.md). Equal diffusion time t = %.3f h² "
  "(bench/README.md).\n" % (meta.get("repeat", 1), T))
w("| target | mesh / size | measured | threshold | status |")
w("|---|---|---|---|---|")
for t_, case, meas, thr, ok in targets:
    w("| %s | %s | %s | %s | %s |" % (t_, case, meas, thr, status(ok)))
w("")

checks = [r for r in R if r["group"] == "check"]
if checks:
    w("## meshlab_filter_timer against meshlabserver (%s)\n" % checks[0]["mesh"])
    w("Same input, filter and parameters; outputs compared byte for byte (binary PLY, coordinates and faces).\n")
    w("| filter run | output identical | applyFilter s (timer) | meshlabserver wall s |")
    w("|---|---|---:|---:|")
    for r in checks:
        w("| %s | %s | %s | %s |" % (r["method"].replace("timer: ", ""), "yes" if r.get("identical") else "**NO**",
                                      f(r["seconds"]), f(r.get("meshlabserver_wall"), 2)))
    w("")

w("## Per mesh\n")
w("Inputs: clean mesh + Gaussian noise of 0.25 mean edge along the normals (seed 1). Errors are RMS "
  "vertex-to-clean-surface distance in mean edge lengths (input noise ≈ 0.25); drift is the RMS tangential "
  "component of (result − clean) w.r.t. the clean normals, in mean edges; volume change vs the noisy input. "
  "Ratio = seconds / ours (CLI curvature flow L, 1 thread, engine).\n")
for m in meshes:
    ours = unit_l(m)
    w("### %s (%d vertices, %d faces)\n" % (m, info[m]["vertices"], info[m]["faces"]))
    w("| method (equal diffusion time) | seconds | ratio vs ours | CG its | error | volume Δ % | drift | peak RSS MB |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in R:
        if r["mesh"] != m or r["group"] != "equal-time":
            continue
        s = r["seconds"]
        r["_s"] = s
        w("| %s | %s | %s | %s | %s | %s | %s | %d |" % (
            r["method"] + (" (total %s s)" % f(r["seconds_total"]) if r.get("seconds_total") else ""),
            f(s), f(q(s, ours and ours["seconds"]), 2),
            r.get("cg_iterations") if r.get("cg_iterations") is not None else "",
            f(r.get("rms_result")), g(r.get("volume_change_percent")), f(r.get("tangential_drift")),
            r["peak_rss_kb"] // 1024))
    w("")
    w("| strength (curvature flow) | seconds engine | seconds total | CG its | inner its (factored) |")
    w("|---|---:|---:|---:|---:|")
    for r in [ours] + [r for r in R if r["mesh"] == m and r["group"] == "strength"]:
        if r:
            w("| %s | %s | %s | %s | %s |" % (r["method"], f(r["seconds"]), f(r.get("seconds_total")),
                                             r.get("cg_iterations", ""), r.get("inner_iterations") or ""))
    w("")
    w("| denoising (filters' defaults and a small sweep) | seconds | CG its | error | volume Δ % | drift |")
    w("|---|---:|---:|---:|---:|---:|")
    for r in R:
        if r["mesh"] != m or r["group"] != "denoise":
            continue
        w("| %s | %s | %s | %s | %s | %s |" % (r["method"], f(r["seconds"]), r.get("cg_iterations") or "",
                                               f(r.get("rms_result")), g(r.get("volume_change_percent")),
                                               f(r.get("tangential_drift"))))
    rin = next((r.get("rms_input") for r in R if r["mesh"] == m and r.get("rms_input") is not None), None)
    w("\nNoisy input error: %s mean edges.\n" % f(rin))
open(dst, "w").write("\n".join(out) + "\n")

# ------------------------------------------------------------------ plot (seconds vs faces)
if shutil.which("gnuplot"):
    series = [("ours CLI curvature L ts", "ours curvature L"), ("CGAL", "CGAL smooth_shape"),
              ("MeshLab Laplacian", "MeshLab Laplacian x10"), ("OpenMesh", "OpenMesh Jacobi")]
    d = os.path.dirname(os.path.abspath(dst))
    files = []
    for i, (pre, label) in enumerate(series):
        pts = []
        for m in meshes:
            r = get(m, pre, "equal-time")
            if r and r["seconds"] > 0:
                pts.append((r["faces"], r["seconds"]))
        pts.sort()
        fn = os.path.join(d, ".plot%d.dat" % i)
        open(fn, "w").write("".join("%d %g\n" % p for p in pts))
        files.append((fn, label))
    png = os.path.join(d, "time_vs_faces.png")
    cmd = ("set terminal pngcairo size 640,420 font ',9'; set output '%s'; set logscale xy; set key left top;"
           "set xlabel 'faces'; set ylabel 'seconds (equal diffusion time)'; set grid;"
           "plot %s" % (png, ", ".join("'%s' using 1:2 with linespoints title '%s'" % fl for fl in files)))
    subprocess.run(["gnuplot", "-e", cmd], check=False, stderr=subprocess.DEVNULL)
    for fn, _ in files:
        os.remove(fn)
