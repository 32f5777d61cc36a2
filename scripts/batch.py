#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Smooths every mesh of a folder with implicit-fairing, on Dask distributed.

  scripts/batch.py IN_DIR OUT_DIR [options] [-- implicit-fairing options]

This machine (default): a LocalCluster of --workers processes. A cluster: --scheduler
tcp://HOST:8786, where `dask scheduler` runs and `dask worker tcp://HOST:8786` runs on every
machine. The command is the same either way. Each file is one task: the worker runs

  implicit-fairing IN TMP --json -q --threads 1 [your options]

with TMP in a hidden folder next to OUT (.batch-RUN-N/), renamed to OUT only after success, so
OUT_DIR never holds a partial mesh. One bad file never stops the batch: its error is collected,
and at the end a table of failures is printed and a JSON report written (--report, default
OUT_DIR/batch-report.json). Exit status: 0 if every file succeeded (or was skipped by
--resume), 1 if any failed, 2 for a usage error.

On a cluster every worker must see IN_DIR and OUT_DIR at the same absolute paths (a shared file
system) and run the CLI: on its PATH, or at the path given with --cli on every worker.
Debian packages: python3-distributed, python3-tqdm (scripts/setup.sh installs them).
"""
import argparse
import json
import logging
import os
import shutil
import sys
import time
import uuid

MESH_EXTENSIONS = (".ply", ".obj", ".off", ".stl")
TOOL = "implicit-fairing"


def parse_args(argv):
    if "--" in argv:
        i = argv.index("--")
        argv, passthrough = argv[:i], argv[i + 1:]
    else:
        passthrough = []
    p = argparse.ArgumentParser(
        prog="batch.py", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__.split("\n\n", 1)[1],
        epilog="Example: scripts/batch.py scans/ smooth/ -r -- --operator curvature "
               "--time-step 22.5")
    p.add_argument("in_dir", metavar="IN_DIR", help="folder of meshes (.ply .obj .off .stl)")
    p.add_argument("out_dir", metavar="OUT_DIR", help="output folder (created; same layout)")
    p.add_argument("-r", "--recursive", action="store_true",
                   help="also the meshes of IN_DIR's subfolders (default: top level only)")
    p.add_argument("--scheduler", metavar="ADDR",
                   help="address of a running Dask scheduler, e.g. tcp://host:8786 "
                        "(default: a LocalCluster on this machine)")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1, metavar="N",
                   help="LocalCluster worker processes (default: the number of cores, %(default)s)")
    p.add_argument("--connect-timeout", type=float, default=30, metavar="S",
                   help="give up reaching --scheduler after S seconds (default: %(default)s)")
    p.add_argument("--cli", metavar="PATH",
                   help="implicit-fairing as the workers find it: a name on their PATH or an "
                        "absolute path valid on every worker (default: implicit-fairing on this "
                        "machine's PATH, else this checkout's build/bin/implicit-fairing)")
    p.add_argument("--format", choices=["ply", "obj", "off", "stl"],
                   help="output format (default: the input's)")
    p.add_argument("--resume", action="store_true",
                   help="skip files whose output already exists (outputs only ever appear "
                        "complete, so an existing one is a finished one)")
    p.add_argument("--timeout", type=float, metavar="S",
                   help="fail a file whose run takes longer than S seconds (default: no limit)")
    p.add_argument("--report", metavar="FILE",
                   help="JSON report (default: OUT_DIR/batch-report.json)")
    p.add_argument("--progress", dest="progress", action="store_true", default=None,
                   help="progress bar on stderr (default: when stderr is a terminal)")
    p.add_argument("--no-progress", dest="progress", action="store_false")
    args = p.parse_args(argv)
    args.passthrough = passthrough
    return args, p


def default_cli():
    found = shutil.which(TOOL)
    if found:
        return found
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    build = os.environ.get("BUILD_DIR", os.path.join(here, "build"))
    local = os.path.abspath(os.path.join(build, "bin", TOOL))
    return local if os.path.exists(local) else TOOL


def find_inputs(in_dir, recursive):
    """(mesh paths relative to in_dir, other files ignored), both sorted."""
    meshes, ignored = [], []
    for root, dirs, files in os.walk(in_dir):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".")) if recursive else []
        for f in sorted(files):
            rel = os.path.relpath(os.path.join(root, f), in_dir)
            if f.startswith("."):
                continue
            (meshes if f.lower().endswith(MESH_EXTENSIONS) else ignored).append(rel)
    return sorted(meshes), sorted(ignored)


def output_path(out_dir, rel, fmt):
    base, ext = os.path.splitext(rel)
    return os.path.join(out_dir, base + ("." + fmt if fmt else ext))


def smooth_one(cli, src, dst, tmp_dir, options, timeout):
    """Runs on a worker: the CLI into tmp_dir/<OUT's name>, renamed to dst on success.

    A hidden folder rather than a hidden name, because the OBJ writer stores the file's name
    inside the file. Self-contained (pickled by value from __main__): workers need only the CLI.
    """
    import json
    import os
    import shutil
    import socket
    import subprocess
    import time
    result = {"input": src, "output": dst, "status": "failed", "host": socket.gethostname(),
              "pid": os.getpid(), "returncode": None, "error": "", "figures": None}
    t0 = time.monotonic()
    tmp = os.path.join(tmp_dir, os.path.basename(dst))
    try:
        shutil.rmtree(tmp_dir, ignore_errors=True)   # left by an attempt whose worker died
        os.makedirs(tmp_dir)
        p = subprocess.run([cli, src, tmp] + list(options), stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=timeout)
        result["returncode"] = p.returncode
        if p.returncode == 0:
            lines = [l for l in p.stdout.splitlines() if l.startswith("{")]
            result["figures"] = json.loads(lines[-1]) if lines else None
            os.replace(tmp, dst)
            result["status"] = "ok"
        else:
            # the user knows the file by its final name, not by our temporary one
            err = [l.replace(tmp, dst) for l in p.stderr.splitlines() if l.strip()]
            err = [l for l in err if "error" in l] or err
            result["error"] = " | ".join(err[-3:]) or "exit status %d, no message" % p.returncode
    except FileNotFoundError as e:
        if e.filename == cli:
            result["error"] = ("%s not found on worker %s: put it on the workers' PATH or pass "
                               "--cli with its absolute path there" % (cli, socket.gethostname()))
        else:
            result["error"] = "FileNotFoundError: %s" % e
    except subprocess.TimeoutExpired:
        result["error"] = "timed out after %g s (--timeout)" % timeout
    except Exception as e:  # a full disk, an unwritable folder: report it, keep going
        result["error"] = "%s: %s" % (type(e).__name__, e)
    finally:
        shutil.rmtree(tmp_dir, ignore_errors=True)   # also the CLI's own temporary if killed
    result["seconds"] = round(time.monotonic() - t0, 3)
    return result


def connect(args):
    from distributed import Client, LocalCluster
    if args.scheduler:
        return Client(args.scheduler, timeout="%gs" % args.connect_timeout), None
    # the worker processes re-import this file; keep scripts/ free of __pycache__
    os.environ["PYTHONDONTWRITEBYTECODE"] = "1"
    cluster = LocalCluster(n_workers=max(1, args.workers), threads_per_worker=1,
                           processes=True, dashboard_address=None,
                           silence_logs=logging.CRITICAL)
    return Client(cluster), cluster


def cli_options(passthrough):
    opts = list(passthrough)
    if "--json" not in opts:
        opts.append("--json")
    if "-q" not in opts and "--quiet" not in opts:
        opts.append("-q")
    # parallelism is across files; one solver thread per task unless asked otherwise
    if not any(o == "--threads" or o.startswith("--threads=") for o in opts):
        opts += ["--threads", "1"]
    return opts


def print_summary(results, ignored, seconds, report_path, out=sys.stdout):
    count = {s: sum(r["status"] == s for r in results) for s in ("ok", "failed", "skipped")}
    out.write("\nbatch: %d files: %d ok, %d failed, %d skipped (--resume); %d other files "
              "ignored; %.1f s\n" % (len(results), count["ok"], count["failed"],
                                      count["skipped"], len(ignored), seconds))
    failed = [r for r in results if r["status"] == "failed"]
    if failed:
        width = max(len(r["rel"]) for r in failed)
        out.write("\n%-*s  %6s  %s\n" % (width, "failed file", "exit", "error"))
        for r in failed:
            code = "-" if r["returncode"] is None else str(r["returncode"])
            out.write("%-*s  %6s  %s\n" % (width, r["rel"], code, r["error"]))
    out.write("\nreport: %s\n" % report_path)


def plan(args, in_dir, out_dir, meshes, run_id):
    """(results of the files --resume skips, tasks (rel, src, dst, tmp_dir) for the others)."""
    skipped, todo = [], []
    for i, rel in enumerate(meshes):
        dst = output_path(out_dir, rel, args.format)
        if args.resume and os.path.isfile(dst) and os.path.getsize(dst) > 0:
            skipped.append({"rel": rel, "input": os.path.join(in_dir, rel), "output": dst,
                            "status": "skipped", "returncode": None, "error": ""})
            continue
        tmp_dir = os.path.join(os.path.dirname(dst), ".batch-%s-%d" % (run_id, i))
        todo.append((rel, os.path.join(in_dir, rel), dst, tmp_dir))
    return skipped, todo


def run(client, todo, cli, options, timeout, run_id, progress):
    """Submits every task and collects one result per task, in completion order."""
    from distributed import as_completed

    def submit(task, suffix=""):
        rel, src, dst, tmp = task
        return client.submit(smooth_one, cli, src, dst, tmp, options, timeout,
                             key="implicit-fairing-%s-%s%s" % (run_id, rel, suffix), pure=False)

    futures = {submit(task): task for task in todo}
    bar = None
    if progress:
        try:
            from tqdm import tqdm
            bar = tqdm(total=len(futures), unit="mesh", file=sys.stderr)
        except ImportError:
            sys.stderr.write("batch.py: no progress bar (python3-tqdm is missing)\n")
    results, orphans = [], []

    def done(task, r):
        r["rel"] = task[0]
        results.append(r)
        if bar:
            bar.set_postfix(failed=sum(x["status"] != "ok" for x in results), refresh=False)
            bar.update(1)
    for f in as_completed(futures):
        try:
            done(futures[f], f.result())
        except Exception:   # its workers died (KilledWorker): maybe not its fault
            orphans.append(futures[f])
    # A worker that dies (out of memory, killed) takes the tasks running beside it down too;
    # each such task gets a second chance alone, one at a time.
    for task in orphans:
        try:
            done(task, submit(task, "-alone").result())
        except Exception as e:
            done(task, {"input": task[1], "output": task[2], "status": "failed",
                        "returncode": None,
                        "error": "task lost twice (its worker died; run alone too): %s: %s"
                                 % (type(e).__name__, e)})
    if bar:
        bar.close()
    return results


def write_report(path, report, run_id):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp-" + run_id
    with open(tmp, "w") as f:
        json.dump(report, f, indent=1)
    os.replace(tmp, path)


def main(argv):
    args, parser = parse_args(argv)
    in_dir, out_dir = os.path.abspath(args.in_dir), os.path.abspath(args.out_dir)
    if not os.path.isdir(in_dir):
        parser.error("IN_DIR %s is not a folder" % args.in_dir)
    if out_dir == in_dir:
        parser.error("OUT_DIR must differ from IN_DIR (the inputs are kept)")
    if os.path.commonpath([in_dir, out_dir]) == in_dir and args.recursive:
        parser.error("OUT_DIR inside IN_DIR with --recursive would read its own outputs")
    cli = args.cli or default_cli()
    if os.sep in cli:
        cli = os.path.abspath(cli)
    report_path = os.path.abspath(args.report or os.path.join(out_dir, "batch-report.json"))
    progress = sys.stderr.isatty() if args.progress is None else args.progress
    options = cli_options(args.passthrough)
    meshes, ignored = find_inputs(in_dir, args.recursive)
    os.makedirs(out_dir, exist_ok=True)
    run_id = uuid.uuid4().hex[:8]
    results, todo = plan(args, in_dir, out_dir, meshes, run_id)

    t0 = time.monotonic()
    if todo:
        try:
            import distributed  # noqa: F401
        except ImportError:
            sys.stderr.write("batch.py: Dask distributed is not installed for %s: install Debian's "
                             "python3-distributed and run with /usr/bin/python3\n" % sys.executable)
            return 2
        try:
            client, cluster = connect(args)
        except (OSError, TimeoutError) as e:
            sys.stderr.write("batch.py: cannot reach the scheduler %s: %s (is `dask scheduler` "
                             "running there, and the port open?)\n" % (args.scheduler, e))
            return 2
        try:
            results += run(client, todo, cli, options, args.timeout, run_id, progress)
        finally:
            client.close()
            if cluster:
                cluster.close()
        for _, _, _, tmp_dir in todo:   # of tasks whose worker died before cleaning up
            shutil.rmtree(tmp_dir, ignore_errors=True)
    seconds = time.monotonic() - t0

    results.sort(key=lambda r: r["rel"])
    for r in results:
        if r["status"] != "ok" and not os.path.exists(r["output"]):
            r["output"] = None
    counts = {s: sum(r["status"] == s for r in results) for s in ("ok", "failed", "skipped")}
    write_report(report_path, {
        "in_dir": in_dir, "out_dir": out_dir, "cli": cli, "options": options,
        "scheduler": args.scheduler or "LocalCluster(%d)" % args.workers,
        "seconds": round(seconds, 3), "counts": counts, "ignored": ignored, "files": results},
        run_id)
    print_summary(results, ignored, seconds, report_path)
    if not meshes:
        sys.stderr.write("batch.py: no meshes (%s) in %s%s\n" % (
            " ".join(MESH_EXTENSIONS), in_dir, "" if args.recursive else " (try --recursive)"))
        return 2
    return 1 if counts["failed"] else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
