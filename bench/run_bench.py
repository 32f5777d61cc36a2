#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""End-to-end runs for bench/run.sh: meshes, our CLI and plugin, the peers, metrics, tables.

Equal diffusion time (bench/README.md derives each mapping): T = t h^2, h = mean edge length,
t = T_DIFF (dimensionless) below. On a regular mesh of edge h:
  ours, curvature flow (eq. 14, L = Laplace-Beltrami/6)   time_step = 6 t   (order 1)
  ours, umbrella (eq. 7, L = h^2/4 Laplace-Beltrami)        time_step = 4 t   (order 1)
  ours, scale-dependent (eq. 11, L = Laplace-Beltrami/2)    time_step = 2 t   (order 1)
  CGAL smooth_shape (M = ring area/6, K = cot a + cot b)    time = t h^2 / 4
  MeshLab Laplacian Smooth (cotangent, default)             steps = t / (sqrt3/(1+4 sqrt3))
  MeshLab ScaleDependent Laplacian (Fujiwara)               delta = 4 t h^2 / steps
  OpenMesh JacobiLaplaceSmootherT C0 (uniform, 0.5 damping) iterations = t / (1/8)

MeshLab's filters (and our plugin) are timed in-process by meshlab_filter_timer (applyFilter
only, bench/tools/meshlab_filter_timer.cpp); on the smallest mesh of the run its outputs are
compared byte for byte with meshlabserver's for the same filters and parameters.

Options: --quick (no >= 1M-face meshes), --only NAME[,NAME] (only these meshes, e.g. torus_10k),
--results DIR (where runs.jsonl and results.md go; default bench/results), --micro-json FILE
(this run's Google Benchmark JSON, for the targets table), --repeat N (timer repetitions).
"""
from cgal_demo import cgal_demo_off
from one_click import ONE_CLICK_STEPS
import argparse, json, math, os, platform, re, subprocess, sys, time

ML_LAP_T = math.sqrt(3) / (1 + 4 * math.sqrt(3))   # diffusion time per MeshLab cot step, in h^2
ML_STEPS = 10
T_DIFF = ML_STEPS * ML_LAP_T                       # ~2.18 h^2: MeshLab's 10 cotangent steps
OM_ITERS = round(T_DIFF / 0.125)

p = argparse.ArgumentParser()
p.add_argument("--root", required=True)
p.add_argument("--build", required=True)
p.add_argument("--cache", required=True)
p.add_argument("--quick", action="store_true")
p.add_argument("--only", default="", help="comma-separated mesh names (torus_10k, torus_100k, bunny_75k, "
               "bunny_loop1_302k, torus_1m, bunny_loop2_1.2m; dragon_mid3_1.3m only when named)")
p.add_argument("--results", default="", help="output directory (default: <root>/bench/results)")
p.add_argument("--micro-json", default="", help="Google Benchmark JSON of this run (targets b)")
p.add_argument("--repeat", type=int, default=3, help="meshlab_filter_timer --repeat (median)")
p.add_argument("--cli-repeat", type=int, default=3,
               help="runs of the CLI rows that targets a, c, d compare (the fastest is kept)")
p.add_argument("--issue12-only", action="store_true",
               help="run only issue 12's rows (engine direct through fairing-bench-tool, MeshLab's "
               "Taubin Smooth x10 when the filter timer is built) on the meshes of >= 500 k vertices")
a = p.parse_args()
REPEAT = a.cli_repeat
only = [x for x in a.only.split(",") if x]
root, build, cache = a.root, a.build, a.cache
bin_b = os.path.join(build, "bench", "bin")
tool = os.path.join(bin_b, "fairing-bench-tool")
cli = os.path.join(build, "main", "bin", "implicit-fairing")
mls = os.path.join(root, "scripts", "meshlabserver.sh")
timer = os.path.join(bin_b, "meshlab_filter_timer")
ML_PLUGINS = "/usr/lib/x86_64-linux-gnu/meshlab/plugins"
unsharp = os.path.join(ML_PLUGINS, "libfilter_unsharp.so")   # Laplacian, Taubin, ScaleDependent
ours_so = os.path.join(build, "main", "meshlab2020", "plugins", "libfilter_implicit_fairing.so")
meshes_dir = os.path.join(cache, "bench-meshes")
runs_dir = os.path.join(cache, "bench-runs")
results = os.path.abspath(a.results) if a.results else os.path.join(root, "bench", "results")
os.makedirs(meshes_dir, exist_ok=True)
os.makedirs(runs_dir, exist_ok=True)
os.makedirs(results, exist_ok=True)
env_ml = dict(os.environ, BUILD_DIR=os.path.join(build, "main"))
records = []


def log(*m):
    print("run_bench:", *m, file=sys.stderr, flush=True)


def run(cmd, env=None, timed=True):
    """Runs cmd under /usr/bin/time -v; returns (stdout, wall seconds, peak RSS kB)."""
    full = (["/usr/bin/time", "-v"] if timed else []) + cmd
    t0 = time.perf_counter()
    r = subprocess.run(full, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError("failed: %s\n%s\n%s" % (" ".join(cmd), r.stdout[-2000:], r.stderr[-2000:]))
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr)
    return r.stdout, r.stderr, wall, int(m.group(1)) if m else 0


def jline(out):
    for line in reversed(out.strip().splitlines()):
        if line.startswith("{"):
            return json.loads(line)
    raise RuntimeError("no JSON in output: " + out[-500:])


# ------------------------------------------------------------------ meshes
def bunny_off():
    """bunny00.off (Stanford bunny scan, closed, 75k faces) from Debian's libcgal-demo."""
    return cgal_demo_off(meshes_dir, "bunny00")


def prepare(name, make_clean):
    clean = os.path.join(meshes_dir, name + "_clean.ply")
    noisy = os.path.join(meshes_dir, name + "_noisy.ply")
    if not os.path.exists(clean):
        make_clean(clean)
    if not os.path.exists(noisy):
        run([tool, "noise", clean, noisy, "0.25", "1"], timed=False)
    info = jline(run([tool, "info", clean], timed=False)[0])
    return dict(name=name, clean=clean, noisy=noisy, **info)


MESHES = [  # name, big (>= 1M faces; None: only with --only), how to make the clean mesh
    ("torus_10k", False, lambda o: run([tool, "torus", "10000", o], timed=False)),
    ("torus_100k", False, lambda o: run([tool, "torus", "100000", o], timed=False)),
    ("bunny_75k", False, lambda o: run([tool, "convert", bunny_off(), o], timed=False)),
    ("bunny_loop1_302k", False, lambda o: run([tool, "loop", bunny_off(), o, "1"], timed=False)),
    ("torus_1m", True, lambda o: run([tool, "torus", "1000000", o], timed=False)),
    ("bunny_loop2_1.2m", True, lambda o: run([tool, "loop", bunny_off(), o, "2"], timed=False)),
    # A raw scan's triangulation at bench size: CGAL's dragon split 1-to-4 three times keeps its
    # obtuse and thin triangles (16 % of the edges with negative cotangent weights, against 0.9 %
    # on the Loop-subdivided bunny). Only with --only: not part of the default full run.
    ("dragon_mid3_1.3m", None, lambda o: run([tool, "midpoint", cgal_demo_off(meshes_dir, "ChineseDragon-10kv"),
                                               o, "3"], timed=False)),
]
unknown = set(only) - {n for n, _, _ in MESHES}
if unknown:
    sys.exit("run_bench: unknown mesh(es) in --only: %s" % ", ".join(sorted(unknown)))
meshes = [prepare(n, mk) for n, big, mk in MESHES
          if ((n in only) if only else big is not None and not (big and a.quick))]


# ------------------------------------------------------------------ .mlx scripts
def mlx(filter_name, params):
    s = ['<!DOCTYPE FilterScript>', '<FilterScript>', ' <filter name="%s">' % filter_name]
    for name, typ, val, extra in params:
        s.append('  <Param name="%s" type="%s" value="%s" description="%s"%s/>' % (name, typ, val, name, extra))
    s += [' </filter>', '</FilterScript>', '']
    return "\n".join(s)


# A filter is (plugin .so, filter name, [(name, type, value, extra .mlx attributes)]): the same
# list gives the .mlx for meshlabserver and the name=value arguments of meshlab_filter_timer.
def ours_mlx(op_menu, time_step, order):
    enum = lambda n, k: ' enum_cardinality="%d"%s' % (n, "".join(' enum_val%d="%s"' % (i, v) for i, v in enumerate(k)))
    return (ours_so, op_menu, [
        ("timeStep", "RichFloat", repr(time_step), ""), ("stepSmoothNum", "RichInt", 1, ""),
        ("order", "RichEnum", order - 1, enum(4, ["L (first order)", "L2 (second order)", "L3 (third order)", "L4 (fourth order)"])),
        ("integration", "RichEnum", 0, enum(3, ["Implicit", "Explicit", "Explicit, normalized operator (section 5.5)"])),
        ("preserveVolume", "RichBool", "true", ""), ("openInvariant", "RichEnum", 0, enum(2, ["None", "Area"])),
        ("boundaryMode", "RichEnum", 0, enum(3, ["Fixed", "Smooth boundary curve", "Virtual vertex"])),
        ("qualityWeights", "RichBool", "false", ""), ("invertQuality", "RichBool", "false", ""),
        ("Selected", "RichBool", "false", ""), ("tolerance", "RichFloat", "1e-08", ""),
        ("maxIterations", "RichInt", 2000, ""), ("freezeOperator", "RichBool", "false", ""),
        ("acceptUnconverged", "RichBool", "false", "")])


def laplacian_mlx(steps):
    return (unsharp, "Laplacian Smooth", [("stepSmoothNum", "RichInt", steps, ""), ("Boundary", "RichBool", "true", ""),
                                          ("cotangentWeight", "RichBool", "true", ""), ("Selected", "RichBool", "false", "")])


def taubin_mlx(steps, lam=0.5, mu=-0.53):
    return (unsharp, "Taubin Smooth", [("lambda", "RichFloat", repr(lam), ""), ("mu", "RichFloat", repr(mu), ""),
                                       ("stepSmoothNum", "RichInt", steps, ""), ("Selected", "RichBool", "false", "")])


def sd_mlx(steps, delta):
    return (unsharp, "ScaleDependent Laplacian Smooth", [("stepSmoothNum", "RichInt", steps, ""),
               ("delta", "RichAbsPerc", repr(delta), ' min="0" max="%r"' % (delta * 100)),
               ("Selected", "RichBool", "false", "")])


# ------------------------------------------------------------------ runners
def record(m, method, group, out_path, seconds, wall, rss, extra=None, metrics=True):
    r = dict(mesh=m["name"], vertices=m["vertices"], faces=m["faces"], method=method, group=group,
             seconds=seconds, wall=wall, peak_rss_kb=rss)
    if extra:
        r.update(extra)
    if metrics and out_path:
        r.update(jline(run([tool, "metrics", m["clean"], m["noisy"], out_path], timed=False)[0]))
    records.append(r)
    log("%-18s %-34s %8.3f s  (wall %.2f s, %d MB)" % (m["name"], method, seconds, wall, rss // 1024))
    return r


def ours_cli(m, group, op, order, ts, threads=1, metrics=True, tag=None, preconditioner="auto", repeat=1):
    """repeat > 1: the fastest of that many runs (rows that a target compares: timing noise on
    this shared 2-core machine is +-20 % on runs of 0.1 s)."""
    out = os.path.join(runs_dir, "%s_cli_%s%d_%g_t%d_%s.ply" % (m["name"], op, order, ts, threads, preconditioner))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    best = None
    for _ in range(repeat):
        o, _, wall, rss = run([cli, m["noisy"], out, "--operator", op, "--order", str(order), "--time-step",
                               repr(ts), "--threads", str(threads), "--preconditioner", preconditioner,
                               "--json", "-q"], env=env)
        if best is None or jline(o)["seconds_engine"] < jline(best[0])["seconds_engine"]:
            best = (o, wall, rss)
    o, wall, rss = best
    j = jline(o)
    name = tag or "ours CLI %s L%s ts=%g%s" % (op, "²" if order == 2 else "", ts,
                                            "" if preconditioner == "auto" else ", " + preconditioner)
    return record(m, name, group, out, j["seconds_engine"], wall, rss,
                  dict(cg_iterations=j.get("cg_iterations"), inner_iterations=j.get("inner_iterations"),
                       threads=threads, seconds_total=j.get("seconds_total"), order=order, time_step=ts,
                       op=op, preconditioner=preconditioner), metrics)


def timer_args(flt):
    so, fname, params = flt
    return [so, fname] + ["%s=%s" % (n, v) for n, _, v, _ in params]


def meshlab(m, group, name, flt, metrics=True, out=None):
    """One MeshLab filter (Debian's or our plugin) timed in-process: seconds = applyFilter only."""
    safe = re.sub(r"[^A-Za-z0-9]+", "_", name)
    out = out or os.path.join(runs_dir, "%s_%s.ply" % (m["name"], safe))
    so, fname, _ = flt
    args = timer_args(flt)
    o, e, wall, rss = run([timer] + args[:2] + [m["noisy"], out] + args[2:] + ["--repeat", str(a.repeat)],
                          env=dict(os.environ, OMP_NUM_THREADS="1", QT_QPA_PLATFORM="offscreen"))
    j = jline(o)
    extra = dict(filter=fname, all=j["all"])
    for k in ("engine_seconds", "overhead", "cg_iterations"):
        if k in j:
            extra[k] = j[k]
    return record(m, name, group, out, j["seconds"], wall, rss, extra, metrics)


def meshlabserver_check(m, name, flt):
    """Runs the filter in Debian's meshlabserver (with our plugin in its plugin folder) and compares
    its output PLY byte for byte with meshlab_filter_timer's, same input and parameters."""
    safe = re.sub(r"[^A-Za-z0-9]+", "_", name)
    script = os.path.join(runs_dir, "%s_%s.mlx" % (m["name"], safe))
    so, fname, params = flt
    open(script, "w").write(mlx(fname, params))
    out_ms = os.path.join(runs_dir, "%s_%s_meshlabserver.ply" % (m["name"], safe))
    out_ti = os.path.join(runs_dir, "%s_%s_timer.ply" % (m["name"], safe))
    _, _, wall, rss = run([mls, "-i", m["noisy"], "-o", out_ms, "-s", script],
                          env=dict(env_ml, OMP_NUM_THREADS="1", FAIRING_PLUGIN=ours_so))
    r = meshlab(m, "check", "timer: " + name, flt, metrics=False, out=out_ti)
    r["meshlabserver_wall"] = wall
    r["identical"] = open(out_ms, "rb").read() == open(out_ti, "rb").read()
    log("%-18s %s: meshlabserver and timer outputs %s" % (m["name"], name, "IDENTICAL" if r["identical"] else "DIFFER"))
    return r


def cgal(m, group, t):
    out = os.path.join(runs_dir, "%s_cgal.ply" % m["name"])
    tau = t * m["mean_edge"] ** 2 / 4
    o, _, wall, rss = run([os.path.join(bin_b, "cgal_smooth_shape"), m["noisy"], out, repr(tau), "1"])
    return record(m, "CGAL smooth_shape time=t·h²/4", group, out, jline(o)["seconds"], wall, rss, dict(cgal_time=tau))


def openmesh(m, group, iters):
    out = os.path.join(runs_dir, "%s_openmesh.ply" % m["name"])
    o, _, wall, rss = run([os.path.join(bin_b, "openmesh_jacobi"), m["noisy"], out, str(iters)])
    return record(m, "OpenMesh Jacobi C0 ×%d" % iters, group, out, jline(o)["seconds"], wall, rss)


def engine_memory(m, ts):
    out = os.path.join(runs_dir, "%s_tool.ply" % m["name"])
    o, _, wall, rss = run([tool, "fair", m["noisy"], out, "curvature", "1", repr(ts)], env=dict(os.environ, OMP_NUM_THREADS="1"))
    j = jline(o)
    return record(m, "engine direct (fair()) curvature L ts=%g" % ts, "memory", None, j["seconds_engine"], wall, rss,
                  dict(extra_bytes_per_vertex=j["extra_peak_bytes_per_vertex"], cg_iterations=j["cg_iterations"]), False)


# Issue 12: each filter's default L² step against a first-order step of the same operator at
# equal cutoff (the mode damped by 1/2: time step sqrt(t) for L where L² has t), threads, strength,
# a frozen operator, memory. Engine direct (fair() in fairing-bench-tool, the same code the CLI
# and the plugin call), fastest of REPEAT runs. One-thread rows are compared by the process CPU
# time of fair() (the machine is shared: wall time counts waits for a core too), the thread rows by
# wall time.
ISSUE12_DEFAULTS = (("umbrella", 10.0), ("scale-dependent", 2.5), ("curvature", 22.5))


def engine(m, op, order, ts, steps=1, threads=1, freeze=False, preconditioner="auto"):
    """ts "auto": the automatic time step (the one-click default; its choice, the estimate's
    seconds and the default's extra peak are recorded, with automatic=True)."""
    automatic = ts == "auto"
    out = os.path.join(runs_dir, "%s_tool.ply" % m["name"])
    args = [tool, "fair", m["noisy"], out, op, str(order), "auto" if automatic else repr(ts), str(steps),
            "threads=%d" % threads, "preconditioner=" + preconditioner] + (["freeze=1"] if freeze else [])
    best = None
    for _ in range(REPEAT):
        o, _, wall, rss = run(args, env=dict(os.environ, OMP_NUM_THREADS=str(threads)))
        j = jline(o)
        key = "cpu_seconds" if threads == 1 else "seconds_engine"
        if best is None or j[key] < best[0][key]:
            best = (j, wall, rss)
    j, wall, rss = best
    ts_name = "automatic (ts=%g)" % j["time_step"] if automatic else "ts=%g" % ts
    name = "engine %s L%s %s%s%s%s" % (op, "²" if order == 2 else "", ts_name, ", %d steps" % steps if steps > 1 else "",
                                     ", frozen" if freeze else "", ", %d threads" % threads if threads > 1 else "")
    extra = dict(op=op, order=order, time_step=j["time_step"] if automatic else ts, steps=steps, threads=threads,
                 freeze=freeze, cg_iterations=j["cg_iterations"], inner_iterations=j.get("inner_iterations"),
                 cpu_seconds=j.get("cpu_seconds"), extra_bytes_per_vertex=j["extra_peak_bytes_per_vertex"])
    if automatic:
        extra.update(automatic=True, strength_seconds=j.get("strength_seconds"))
    return record(m, name, "issue12", None, j["seconds_engine"], wall, rss, extra, False)


def issue12(m):
    # The defaults are automatic: the step they choose on this mesh, against L at equal cutoff.
    for op, _ in ISSUE12_DEFAULTS:
        chosen = engine(m, op, 2, "auto")["time_step"]
        engine(m, op, 2, "auto", threads=2)
        if chosen > 0:
            engine(m, op, 2, chosen)
            engine(m, op, 1, math.sqrt(chosen))
        # The whole one-click run, its step count included: its peak memory is the default's.
        engine(m, op, 2, "auto", steps=ONE_CLICK_STEPS[op])
    for op, ts in ISSUE12_DEFAULTS:
        engine(m, op, 2, ts)
        engine(m, op, 1, math.sqrt(ts))
        engine(m, op, 2, ts, threads=2)
    engine(m, "curvature", 1, 16 * math.sqrt(22.5))
    engine(m, "curvature", 2, 16 * 22.5)
    engine(m, "curvature", 2, 22.5, steps=10, freeze=True)
    if os.path.exists(timer):
        meshlab(m, "issue12", "MeshLab Taubin Smooth ×10", taubin_mlx(10), metrics=False)


def micro_records():
    """This run's Google Benchmark JSON (run.sh --micro), kept in runs.jsonl for the targets table."""
    if not a.micro_json or not os.path.exists(a.micro_json):
        return []
    d = json.load(open(a.micro_json))
    out = []
    for b_ in d["benchmarks"]:
        if b_.get("run_type") == "aggregate":
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b_.get("time_unit", "ns")]
        out.append(dict(micro=b_["name"], real_ms=b_["real_time"] * scale, cpu_ms=b_["cpu_time"] * scale,
                        vertices=b_.get("vertices", 0), cg_iterations=b_.get("cg_iterations")))
    return out


def write_results():
  meta = dict(machine=platform.node(), cpu=next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?"),
            cores=os.cpu_count(), mem_gb=round(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30),
            load_before=load0, load_after=os.getloadavg(), minutes=(time.time() - started) / 60,
            date=time.strftime("%Y-%m-%d %H:%M"), t_diff=T_DIFF, om_iters=OM_ITERS, ml_steps=ML_STEPS,
            git=GIT_AT_START,
            dirty=ENGINE_DIRTY_AT_START,
            command="bench/run.sh" + (" --quick" if a.quick else "") + (" --only " + a.only if only else "")
                    + (" --issue12-only" if a.issue12_only else "")
                    + ("" if a.micro_json else " --no-micro") + (" --repeat %d" % a.repeat if a.repeat != 1 else ""),
            repeat=a.repeat, cli_repeat=REPEAT, complete=done)
  with open(os.path.join(results, "runs.jsonl"), "w") as f:
    f.write(json.dumps(dict(meta=meta)) + "\n")
    for r in records:
        f.write(json.dumps(r) + "\n")
    for r in micro:
        f.write(json.dumps(r) + "\n")
  subprocess.run([sys.executable, os.path.join(root, "bench", "report.py"), os.path.join(results, "runs.jsonl"),
                  os.path.join(results, "results.md")], check=True)
  log("%.1f min so far; tables in %s" % (meta["minutes"], os.path.join(results, "results.md")))


# ------------------------------------------------------------------ the runs
started = time.time()
# The commit and the engine's state as the run starts, when run.sh has just built it: the run
# writes its results into the tree (bench/results/...) as it goes, which `git describe --dirty`
# at the end would count as a change, as it would any edit made while the run goes on.
GIT_AT_START = subprocess.run(["git", "-C", root, "describe", "--always", "--dirty", "--abbrev=7"],
                              capture_output=True, text=True).stdout.strip()
ENGINE_DIRTY_AT_START = bool(subprocess.run(["git", "-C", root, "status", "--porcelain", "fairing"],
                                            capture_output=True, text=True).stdout.strip())
load0 = os.getloadavg()
micro = micro_records()
done = False
t = T_DIFF
for mi, m in enumerate(meshes if not a.issue12_only else []):
    log("mesh %s: %d vertices, %d faces, mean edge %.4g" % (m["name"], m["vertices"], m["faces"], m["mean_edge"]))
    h2 = m["mean_edge"] ** 2
    big = m["faces"] > 500000
    if mi == 0:  # the timer against meshlabserver, byte for byte, on the smallest mesh
        meshlabserver_check(m, "MeshLab Laplacian Smooth (cot) ×%d" % ML_STEPS, laplacian_mlx(ML_STEPS))
        meshlabserver_check(m, "MeshLab Taubin Smooth ×10", taubin_mlx(10))
        meshlabserver_check(m, "MeshLab ScaleDependent Laplacian ×%d" % ML_STEPS, sd_mlx(ML_STEPS, 4 * t * h2 / ML_STEPS))
        meshlabserver_check(m, "ours plugin curvature L ts=%g" % (6 * t), ours_mlx("Implicit Fairing: Curvature Flow", 6 * t, 1))
    # equal diffusion time (targets a, c, e)
    ours_cli(m, "equal-time", "curvature", 1, 6 * t, repeat=REPEAT)
    ours_cli(m, "equal-time", "curvature", 1, 6 * t, threads=2, metrics=False, repeat=REPEAT,
             tag="ours CLI curvature L ts=%g, 2 threads" % (6 * t))
    ours_cli(m, "equal-time", "umbrella", 1, 4 * t)
    ours_cli(m, "equal-time", "scale-dependent", 1, 2 * t)
    meshlab(m, "equal-time", "ours plugin curvature L ts=%g" % (6 * t), ours_mlx("Implicit Fairing: Curvature Flow", 6 * t, 1))
    cgal(m, "equal-time", t)
    meshlab(m, "equal-time", "MeshLab Laplacian Smooth (cot) ×%d" % ML_STEPS, laplacian_mlx(ML_STEPS))
    meshlab(m, "equal-time", "MeshLab ScaleDependent Laplacian ×%d" % ML_STEPS, sd_mlx(ML_STEPS, 4 * t * h2 / ML_STEPS))
    openmesh(m, "equal-time", OM_ITERS)
    # strength (target d): a step 16x stronger; the unit L step is the equal-time row above
    ours_cli(m, "strength", "curvature", 1, 96 * t, metrics=False, repeat=REPEAT)
    ours_cli(m, "strength", "curvature", 2, 22.5, metrics=False, repeat=REPEAT)
    ours_cli(m, "strength", "curvature", 2, 360, metrics=False, repeat=REPEAT)
    if not big:  # reference: plain Jacobi PCG (on >= 1M faces L² at 360 exceeds the 2000-iteration cap)
        ours_cli(m, "strength", "curvature", 2, 22.5, metrics=False, preconditioner="jacobi")
        ours_cli(m, "strength", "curvature", 2, 360, metrics=False, preconditioner="jacobi")
    # denoising (target f) at the filters' defaults and a small sweep (best of each kept)
    for ts in ((10, 40) if big else (2.5, 10, 40)):
        ours_cli(m, "denoise", "umbrella", 2, ts)
    for ts in ((22.5,) if big else (5.625, 22.5, 90)):
        ours_cli(m, "denoise", "curvature", 2, ts)
    meshlab(m, "denoise", "ours plugin umbrella L² ts=10", ours_mlx("Implicit Fairing: Umbrella Diffusion", 10.0, 2))
    for steps in ((10, 30) if big else (10, 30, 100)):
        meshlab(m, "denoise", "MeshLab Taubin Smooth ×%d" % steps, taubin_mlx(steps))
    engine_memory(m, 6 * t)  # target e, memory
    if m["vertices"] >= 500000:
        issue12(m)
    done = mi + 1 == len(meshes)
    write_results()
if a.issue12_only:
    for mi, m in enumerate(meshes):
        if m["vertices"] >= 500000:
            issue12(m)
        done = mi + 1 == len(meshes)
        write_results()
