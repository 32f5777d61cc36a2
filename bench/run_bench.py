#!/usr/bin/env python3
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
"""
import argparse, json, math, os, platform, re, shutil, subprocess, sys, tarfile, time

ML_LAP_T = math.sqrt(3) / (1 + 4 * math.sqrt(3))   # diffusion time per MeshLab cot step, in h^2
ML_STEPS = 10
T_DIFF = ML_STEPS * ML_LAP_T                       # ~2.18 h^2: MeshLab's 10 cotangent steps
OM_ITERS = round(T_DIFF / 0.125)

p = argparse.ArgumentParser()
p.add_argument("--root", required=True)
p.add_argument("--build", required=True)
p.add_argument("--cache", required=True)
p.add_argument("--quick", action="store_true")
a = p.parse_args()
root, build, cache = a.root, a.build, a.cache
bin_b = os.path.join(build, "bench", "bin")
tool = os.path.join(bin_b, "fairing-bench-tool")
cli = os.path.join(build, "main", "bin", "implicit-fairing")
mls = os.path.join(root, "scripts", "meshlabserver.sh")
meshes_dir = os.path.join(cache, "bench-meshes")
runs_dir = os.path.join(cache, "bench-runs")
results = os.path.join(root, "bench", "results")
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
    dst = os.path.join(meshes_dir, "bunny00.off")
    if os.path.exists(dst):
        return dst
    d = os.path.join(meshes_dir, "deb")
    os.makedirs(d, exist_ok=True)
    subprocess.run(["apt-get", "download", "libcgal-demo"], cwd=d, check=True, capture_output=True)
    deb = [f for f in os.listdir(d) if f.startswith("libcgal-demo") and f.endswith(".deb")][0]
    x = os.path.join(d, "x")
    subprocess.run(["dpkg", "-x", os.path.join(d, deb), x], check=True)
    with tarfile.open(os.path.join(x, "usr/share/doc/libcgal-dev/data.tar.gz")) as t:
        f = t.extractfile("data/meshes/bunny00.off")
        open(dst, "wb").write(f.read())
    shutil.rmtree(d)
    return dst


def prepare(name, make_clean):
    clean = os.path.join(meshes_dir, name + "_clean.ply")
    noisy = os.path.join(meshes_dir, name + "_noisy.ply")
    if not os.path.exists(clean):
        make_clean(clean)
    if not os.path.exists(noisy):
        run([tool, "noise", clean, noisy, "0.25", "1"], timed=False)
    info = jline(run([tool, "info", clean], timed=False)[0])
    return dict(name=name, clean=clean, noisy=noisy, **info)


meshes = []
meshes.append(prepare("torus_10k", lambda o: run([tool, "torus", "10000", o], timed=False)))
meshes.append(prepare("torus_100k", lambda o: run([tool, "torus", "100000", o], timed=False)))
b = bunny_off()
meshes.append(prepare("bunny_75k", lambda o: run([tool, "convert", b, o], timed=False)))
meshes.append(prepare("bunny_loop1_302k", lambda o: run([tool, "loop", b, o, "1"], timed=False)))
if not a.quick:
    meshes.append(prepare("torus_1m", lambda o: run([tool, "torus", "1000000", o], timed=False)))
    meshes.append(prepare("bunny_loop2_1.2m", lambda o: run([tool, "loop", b, o, "2"], timed=False)))


# ------------------------------------------------------------------ .mlx scripts
def mlx(filter_name, params):
    s = ['<!DOCTYPE FilterScript>', '<FilterScript>', ' <filter name="%s">' % filter_name]
    for name, typ, val, extra in params:
        s.append('  <Param name="%s" type="%s" value="%s" description="%s"%s/>' % (name, typ, val, name, extra))
    s += [' </filter>', '</FilterScript>', '']
    return "\n".join(s)


def ours_mlx(op_menu, time_step, order):
    enum = lambda n, k: ' enum_cardinality="%d"%s' % (n, "".join(' enum_val%d="%s"' % (i, v) for i, v in enumerate(k)))
    return mlx(op_menu, [
        ("timeStep", "RichFloat", repr(time_step), ""), ("stepSmoothNum", "RichInt", 1, ""),
        ("order", "RichEnum", order - 1, enum(2, ["L (first order)", "L² (second order, recommended)"])),
        ("integration", "RichEnum", 0, enum(3, ["Implicit", "Explicit", "Explicit, normalized operator (section 5.5)"])),
        ("preserveVolume", "RichBool", "true", ""), ("openInvariant", "RichEnum", 0, enum(2, ["None", "Area"])),
        ("boundaryMode", "RichEnum", 0, enum(3, ["Fixed", "Smooth boundary curve", "Virtual vertex"])),
        ("qualityWeights", "RichBool", "false", ""), ("invertQuality", "RichBool", "false", ""),
        ("Selected", "RichBool", "false", ""), ("tolerance", "RichFloat", "1e-08", ""),
        ("maxIterations", "RichInt", 2000, ""), ("freezeOperator", "RichBool", "false", ""),
        ("acceptUnconverged", "RichBool", "false", "")])


def laplacian_mlx(steps):
    return mlx("Laplacian Smooth", [("stepSmoothNum", "RichInt", steps, ""), ("Boundary", "RichBool", "true", ""),
                                    ("cotangentWeight", "RichBool", "true", ""), ("Selected", "RichBool", "false", "")])


def taubin_mlx(steps, lam=0.5, mu=-0.53):
    return mlx("Taubin Smooth", [("lambda", "RichFloat", lam, ""), ("mu", "RichFloat", mu, ""),
                                 ("stepSmoothNum", "RichInt", steps, ""), ("Selected", "RichBool", "false", "")])


def sd_mlx(steps, delta):
    return mlx("ScaleDependent Laplacian Smooth", [("stepSmoothNum", "RichInt", steps, ""),
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


def ours_cli(m, group, op, order, ts, threads=1, metrics=True, tag=None):
    out = os.path.join(runs_dir, "%s_cli_%s%d_%g_t%d.ply" % (m["name"], op, order, ts, threads))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    o, _, wall, rss = run([cli, m["noisy"], out, "--operator", op, "--order", str(order), "--time-step",
                           repr(ts), "--threads", str(threads), "--json", "-q"], env=env)
    j = jline(o)
    name = tag or "ours CLI %s L%s ts=%g" % (op, "²" if order == 2 else "", ts)
    return record(m, name, group, out, j["seconds_engine"], wall, rss,
                  dict(cg_iterations=j.get("cg_iterations"), threads=threads, seconds_total=j.get("seconds_total")),
                  metrics)


def meshlab(m, group, name, script_text, metrics=True):
    safe = re.sub(r"[^A-Za-z0-9]+", "_", name)
    script = os.path.join(runs_dir, "%s_%s.mlx" % (m["name"], safe))
    open(script, "w").write(script_text)
    out = os.path.join(runs_dir, "%s_%s.ply" % (m["name"], safe))
    o, e, wall, rss = run([mls, "-i", m["noisy"], "-o", out, "-s", script], env=env_ml)
    extra = {}
    t = re.search(r"Time: ([0-9.eE+-]+) s in the engine, ([0-9.eE+-]+) s in total", o + e)
    if t:
        extra = dict(plugin_engine=float(t.group(1)), plugin_total=float(t.group(2)))
    it = re.search(r"CG iterations in total: (\d+)", o + e)
    if it:
        extra["cg_iterations"] = int(it.group(1))
    return record(m, name, group, out, wall, wall, rss, extra, metrics)


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


def write_results():
  meta = dict(machine=platform.node(), cpu=next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?"),
            cores=os.cpu_count(), mem_gb=round(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30),
            load_before=load0, load_after=os.getloadavg(), minutes=(time.time() - started) / 60,
            date=time.strftime("%Y-%m-%d %H:%M"), t_diff=T_DIFF, om_iters=OM_ITERS, ml_steps=ML_STEPS,
            git=subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip(),
            dirty=bool(subprocess.run(["git", "-C", root, "status", "--porcelain", "fairing"], capture_output=True, text=True).stdout.strip()),
            command="bench/run.sh " + (" --quick" if a.quick else ""))
  with open(os.path.join(results, "runs.jsonl"), "w") as f:
    f.write(json.dumps(dict(meta=meta)) + "\n")
    for r in records:
        f.write(json.dumps(r) + "\n")
  subprocess.run([sys.executable, os.path.join(root, "bench", "report.py"), os.path.join(results, "runs.jsonl"),
                  os.path.join(results, "results.md")], check=True)
  log("%.1f min so far; tables in bench/results/results.md" % meta["minutes"])


# ------------------------------------------------------------------ the runs
started = time.time()
load0 = os.getloadavg()
t = T_DIFF
for m in meshes:
    log("mesh %s: %d vertices, %d faces, mean edge %.4g" % (m["name"], m["vertices"], m["faces"], m["mean_edge"]))
    h2 = m["mean_edge"] ** 2
    big = m["faces"] > 500000
    # baseline: MeshLab loading + saving the mesh (a 0-step Laplacian), to subtract from MeshLab runs
    meshlab(m, "baseline", "MeshLab load+save only", laplacian_mlx(0), metrics=False)
    # equal diffusion time
    ours_cli(m, "equal-time", "curvature", 1, 6 * t)
    ours_cli(m, "equal-time", "curvature", 1, 6 * t, threads=2, metrics=False, tag="ours CLI curvature L ts=%g, 2 threads" % (6 * t))
    ours_cli(m, "equal-time", "umbrella", 1, 4 * t)
    ours_cli(m, "equal-time", "scale-dependent", 1, 2 * t)
    meshlab(m, "equal-time", "ours plugin curvature L ts=%g" % (6 * t), ours_mlx("Implicit Fairing: Curvature Flow", 6 * t, 1))
    cgal(m, "equal-time", t)
    meshlab(m, "equal-time", "MeshLab Laplacian Smooth (cot) ×%d" % ML_STEPS, laplacian_mlx(ML_STEPS))
    meshlab(m, "equal-time", "MeshLab ScaleDependent Laplacian ×%d" % ML_STEPS, sd_mlx(ML_STEPS, 4 * t * h2 / ML_STEPS))
    openmesh(m, "equal-time", OM_ITERS)
    # strength: a step 16x stronger
    ours_cli(m, "strength", "curvature", 1, 96 * t, metrics=False)
    if not big:  # curvature L² on >= 1M faces needs ~1000 plain Jacobi-PCG iterations (micro.md)
        ours_cli(m, "strength", "curvature", 2, 22.5, metrics=False)
        ours_cli(m, "strength", "curvature", 2, 360, metrics=False)
    # denoising at the filters' defaults and a small sweep (best of each kept in the table)
    for ts in (2.5, 10, 40):
        if big and ts != 10:
            continue
        ours_cli(m, "denoise", "umbrella", 2, ts)
    for ts in (5.625, 22.5, 90):
        if big:
            continue
        ours_cli(m, "denoise", "curvature", 2, ts)
    meshlab(m, "denoise", "ours plugin umbrella L² ts=10", ours_mlx("Implicit Fairing: Umbrella Diffusion", 10.0, 2))
    for steps in (10, 30, 100):
        if big and steps != 10:
            continue
        meshlab(m, "denoise", "MeshLab Taubin Smooth ×%d" % steps, taubin_mlx(steps))
    engine_memory(m, 6 * t)
    write_results()

