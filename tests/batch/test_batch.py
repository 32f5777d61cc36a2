#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Tests of scripts/batch.py (label batch): Debian's python3 with python3-distributed.

  test_batch.py CASE --batch scripts/batch.py --tool BIN --mltest tests/meshlab2020/mltest.py
                --work DIR

CASE local: a LocalCluster over 30 generated meshes, 7 of them bad (non-manifold, NaN, empty
file, empty mesh, truncated, PLY bytes named .obj, a face index out of range) and a .txt to
ignore: per-file outcomes, the errors the CLI gives on its own, exit status, the table and JSON
report, no partial or temporary file (also after runs killed by --timeout and workers killed
mid-task), options passed through (bytes equal to a direct CLI run), --resume, top level only
without --recursive, the CLI leaving an existing OUT untouched on failure.
CASE cluster: `dask scheduler` and two `dask worker --no-nanny` started as separate processes
on loopback; batch.py --scheduler tcp://127.0.0.1:PORT must run every file in those two
worker processes; a --cli missing on the workers fails every file with a message naming it.
Exit 0: pass, 1: fail.
"""
import argparse
import importlib.util
import json
import os
import random
import shutil
import signal
import socket
import struct
import subprocess
import sys
import time

ARGS = None
ML = None
CLI_TEST = None   # tests/cli/test_cli.py, for its readers of PLY, OBJ, OFF and STL
OPTIONS = ["--operator", "umbrella", "--time-step", "5", "--steps", "2"]


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def write_ply(path, V, F, truncate=0):
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
            "property float y\nproperty float z\nelement face %d\n"
            "property list uchar int vertex_indices\nend_header\n" % (len(V), len(F)))
    data = head.encode() + b"".join(struct.pack("<3f", *v) for v in V) + \
        b"".join(struct.pack("<B3i", 3, *f) for f in F)
    with open(path, "wb") as f:
        f.write(data[:len(data) - truncate])


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines("v %.7g %.7g %.7g\n" % tuple(v) for v in V)
        f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F)


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        f.writelines("%.7g %.7g %.7g\n" % tuple(v) for v in V)
        f.writelines("3 %d %d %d\n" % tuple(t) for t in F)


def write_stl(path, V, F):
    with open(path, "wb") as f:
        f.write(b"binary stl".ljust(80, b" ") + struct.pack("<I", len(F)))
        for t in F:
            f.write(struct.pack("<3f", 0, 0, 0))
            for i in t:
                f.write(struct.pack("<3f", *V[i]))
            f.write(b"\0\0")


GOOD, BAD = {}, {}   # relative path -> (vertices, faces) / what is wrong with it


def make_inputs(folder, n_good=23):
    """Good meshes in four formats, some in sub/; the bad ones of the docstring."""
    rng = random.Random(5)
    writers = [(".ply", write_ply), (".obj", write_obj), (".off", write_off), (".stl", write_stl)]
    os.makedirs(os.path.join(folder, "sub", "deeper"), exist_ok=True)
    for i in range(n_good):
        V, F = (ML.noisy_sphere(rng, 2, 1.0 + 0.1 * i) if i % 3 else ML.noisy_grid(rng, 12))
        ext, writer = writers[i % 4]
        rel = os.path.join(["", "sub", os.path.join("sub", "deeper")][i % 3], "m%02d%s" % (i, ext))
        writer(os.path.join(folder, rel), V, F)
        GOOD[rel] = (len(V), len(F))
    V, F = ML.noisy_sphere(rng, 1)
    nmV, nmF = ML.noisy_grid(rng, 8)
    nmV.append([0.1, 0.1, 0.5])
    nmF.append((27, 28, len(nmV) - 1))            # a third face on an interior edge
    write_ply(os.path.join(folder, "bad_nonmanifold.ply"), nmV, nmF)
    BAD["bad_nonmanifold.ply"] = "an edge shared by three faces"
    write_ply(os.path.join(folder, "bad_nan.ply"), [[float("nan"), 0, 0]] + V[1:], F)
    BAD["bad_nan.ply"] = "a NaN coordinate"
    open(os.path.join(folder, "bad_empty_file.ply"), "wb").close()
    BAD["bad_empty_file.ply"] = "an empty file"
    write_ply(os.path.join(folder, "sub", "bad_empty_mesh.ply"), [], [])
    BAD[os.path.join("sub", "bad_empty_mesh.ply")] = "a mesh with nothing in it"
    write_ply(os.path.join(folder, "sub", "bad_truncated.ply"), V, F, truncate=7)
    BAD[os.path.join("sub", "bad_truncated.ply")] = "7 bytes missing"
    write_ply(os.path.join(folder, "bad_ply_named.obj"), V, F)
    BAD["bad_ply_named.obj"] = "PLY bytes named .obj"
    write_off(os.path.join(folder, "bad_index.off"), V, F[:-1] + [(0, 1, len(V) + 5)])
    BAD["bad_index.off"] = "a face index out of range"
    with open(os.path.join(folder, "notes.txt"), "w") as f:
        f.write("not a mesh\n")


def batch(args, expect):
    cmd = [sys.executable, ARGS.batch] + args
    print("$ " + " ".join(cmd))
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=600)
    print("  -> %d in %.1f s\n%s" % (p.returncode, time.monotonic() - t0, p.stdout))
    if p.returncode != expect:
        print(p.stderr[-3000:])
        fail("batch.py exited %d, expected %d" % (p.returncode, expect))
    return p.stdout, p.stderr


def all_files(folder):
    out = []
    for root, _, files in os.walk(folder):
        out += [os.path.relpath(os.path.join(root, f), folder) for f in files]
    return sorted(out)


def mesh_counts(path):
    """(vertices, faces) of an output, read by tests/cli's independent readers."""
    V, nf = CLI_TEST.READERS[os.path.splitext(path)[1][1:].lower()](path)
    return len(V), nf


def direct_errors(src):
    """The error lines of the CLI run directly on src (those not naming its output)."""
    out = os.path.join(ARGS.work, "direct-error", "out" + os.path.splitext(src)[1])
    os.makedirs(os.path.dirname(out), exist_ok=True)
    p = subprocess.run([ARGS.tool, src, out] + OPTIONS, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    check(p.returncode == 1, "the CLI alone on %s exited %d, expected 1" % (src, p.returncode))
    return [l for l in p.stderr.splitlines() if "error" in l and out not in l]


def check_report(report_path, expect_status):
    with open(report_path) as f:
        report = json.load(f)
    files = {r["rel"]: r for r in report["files"]}
    check(sorted(files) == sorted(expect_status),
          "report lists %r, expected %r" % (sorted(files), sorted(expect_status)))
    for rel, status in expect_status.items():
        r = files[rel]
        check(r["status"] == status, "%s: status %s, expected %s (%s)" %
              (rel, r["status"], status, r.get("error")))
        if status == "failed":
            want = direct_errors(r["input"])
            check(want and all(line in r["error"] for line in want),
                  "%s (%s): error %r is not the CLI's own %r" % (rel, BAD[rel], r["error"], want))
            check(r["returncode"] == 1, "%s: CLI exit %r, expected 1" % (rel, r["returncode"]))
            check(".batch-" not in r["error"] and "was not written" not in r["error"],
                  "%s: the error names a temporary file or repeats the CLI's epilogue" % rel)
        if status == "ok":
            check(r["figures"]["operator"] == "umbrella" and r["figures"]["steps"] == 2,
                  "%s: options not passed through: %r" % (rel, r["figures"]))
    counts = report["counts"]
    want = {s: sum(v == s for v in expect_status.values()) for s in ("ok", "failed", "skipped")}
    check(counts == want, "report counts %r, expected %r" % (counts, want))
    return report


def case_local():
    src, out = os.path.join(ARGS.work, "in"), os.path.join(ARGS.work, "out")
    make_inputs(src)
    check(len(GOOD) + len(BAD) == 30, "expected 30 meshes, made %d" % (len(GOOD) + len(BAD)))

    stdout, _ = batch([src, out, "--recursive", "--workers", "2", "--cli", ARGS.tool, "--"]
                      + OPTIONS, expect=1)
    status = {rel: "ok" for rel in GOOD}
    status.update({rel: "failed" for rel in BAD})
    report = check_report(os.path.join(out, "batch-report.json"), status)
    check(report["ignored"] == ["notes.txt"], "ignored files %r" % report["ignored"])
    check("23 ok, 7 failed" in stdout, "summary line missing: %r" % stdout[:300])
    for rel in BAD:
        check(any(line.startswith(rel + " ") for line in stdout.splitlines()),
              "failure table has no row for %s" % rel)
    # Exactly one complete output per good file; nothing else (no partial, no temporary).
    expected = sorted(list(GOOD) + ["batch-report.json"])
    check(all_files(out) == expected, "output folder holds %r" % (
        sorted(set(all_files(out)) ^ set(expected))))
    for rel, (nv, nf) in GOOD.items():
        got = mesh_counts(os.path.join(out, rel))
        # STL stores corners per triangle; the reader merges equal ones, so counts match too.
        check(got == (nv, nf), "%s: output has %r vertices/faces, input %r" % (rel, got, (nv, nf)))
    # Options passed through: bytes equal to a direct run of the CLI with the same options.
    for rel in ["m00.ply", os.path.join("sub", "m01.obj")]:
        os.makedirs(os.path.join(ARGS.work, "direct"), exist_ok=True)
        # same file name: the OBJ writer stores it in the file
        direct = os.path.join(ARGS.work, "direct", os.path.basename(rel))
        subprocess.run([ARGS.tool, os.path.join(src, rel), direct, "--threads", "1", "-q"]
                       + OPTIONS, check=True)
        with open(direct, "rb") as a, open(os.path.join(out, rel), "rb") as b:
            check(a.read() == b.read(), "%s differs from a direct CLI run" % rel)
    print("ok: per-file outcomes, report, table, no partial output, options passed through")

    # --resume: finished files are skipped (and not rewritten), failures are tried again.
    mtimes = {rel: os.stat(os.path.join(out, rel)).st_mtime_ns for rel in GOOD}
    batch([src, out, "-r", "--resume", "--workers", "2", "--cli", ARGS.tool, "--"] + OPTIONS,
          expect=1)
    status = {rel: "skipped" for rel in GOOD}
    status.update({rel: "failed" for rel in BAD})
    check_report(os.path.join(out, "batch-report.json"), status)
    check(all(os.stat(os.path.join(out, rel)).st_mtime_ns == t for rel, t in mtimes.items()),
          "--resume rewrote a finished output")
    print("ok: --resume")

    # A run killed mid-way (--timeout) leaves nothing behind either.
    slow = os.path.join(ARGS.work, "slow")
    os.makedirs(slow)
    shutil.copy(os.path.join(src, "m00.ply"), slow)
    shutil.copy(os.path.join(src, "m03.stl"), slow)
    batch([slow, os.path.join(ARGS.work, "slow-out"), "--timeout", "0.001", "--cli", ARGS.tool,
           "--workers", "1", "--", "--steps", "50"], expect=1)
    with open(os.path.join(ARGS.work, "slow-out", "batch-report.json")) as f:
        r = json.load(f)
    check(all(x["status"] == "failed" and "timed out" in x["error"] for x in r["files"]),
          "--timeout: %r" % [(x["status"], x["error"]) for x in r["files"]])
    left = os.listdir(os.path.join(ARGS.work, "slow-out"))   # hidden folders included
    check(left == ["batch-report.json"], "a killed run left %r" % left)
    print("ok: runs killed by --timeout leave no file")

    # A worker killed while smoothing (as the out-of-memory killer would): that file fails
    # with the reason, the files that ran beside it get a second chance and succeed, and
    # nothing partial is left.
    crash = os.path.join(ARGS.work, "crash")
    os.makedirs(crash)
    for f in ("m00.ply", "m03.stl"):
        shutil.copy(os.path.join(src, f), crash)
    shutil.copy(os.path.join(src, "m00.ply"), os.path.join(crash, "crash_me.ply"))
    killer = os.path.join(ARGS.work, "killer.sh")
    with open(killer, "w") as f:
        f.write('#!/bin/sh\ncase "$(basename "$1")" in crash*) kill -9 $PPID; exit 1;; esac\n'
                'exec "%s" "$@"\n' % ARGS.tool)
    os.chmod(killer, 0o755)
    crash_out = os.path.join(ARGS.work, "crash-out")
    batch([crash, crash_out, "--workers", "2", "--cli", killer], expect=1)
    with open(os.path.join(crash_out, "batch-report.json")) as f:
        r = {x["rel"]: x for x in json.load(f)["files"]}
    check(r["crash_me.ply"]["status"] == "failed" and
          "KilledWorker" in r["crash_me.ply"]["error"], "killed worker: %r" % r["crash_me.ply"])
    check(r["m00.ply"]["status"] == "ok" and r["m03.stl"]["status"] == "ok",
          "the files beside a killed worker: %r" % [(x["rel"], x["error"]) for x in r.values()])
    left = sorted(os.listdir(crash_out))
    check(left == ["batch-report.json", "m00.ply", "m03.stl"], "after killed workers: %r" % left)
    print("ok: a killed worker fails its file only, and leaves nothing partial")

    # Top level only, good files only: exit 0; a separate report file.
    top = os.path.join(ARGS.work, "top")
    os.makedirs(top)
    for rel in GOOD:
        if os.sep not in rel:
            shutil.copy(os.path.join(src, rel), top)
    os.makedirs(os.path.join(top, "sub"))
    shutil.copy(os.path.join(src, "bad_nan.ply"), os.path.join(top, "sub"))
    rep = os.path.join(ARGS.work, "top-report.json")
    batch([top, os.path.join(ARGS.work, "top-out"), "--workers", "1", "--cli", ARGS.tool,
           "--report", rep, "--format", "ply", "--"] + OPTIONS, expect=0)
    with open(rep) as f:
        r = json.load(f)
    n_top = sum(os.sep not in rel for rel in GOOD)
    check(r["counts"] == {"ok": n_top, "failed": 0, "skipped": 0},
          "top level: %r, expected %d ok" % (r["counts"], n_top))
    check(all(f["output"].endswith(".ply") for f in r["files"]), "--format ply not applied")
    print("ok: top level only, exit 0, --format, --report")

    # The CLI's own promise, which batch.py relies on: a failing run leaves OUT untouched.
    target = os.path.join(ARGS.work, "existing.ply")
    shutil.copy(os.path.join(src, "m00.ply"), target)
    before = open(target, "rb").read()
    p = subprocess.run([ARGS.tool, os.path.join(src, "bad_nan.ply"), target, "-q"])
    check(p.returncode == 1, "CLI on NaN input exited %d" % p.returncode)
    check(open(target, "rb").read() == before, "the CLI changed an existing OUT on failure")
    check(not [f for f in os.listdir(ARGS.work) if ".tmp-" in f], "CLI left a temporary file")
    print("ok: the CLI leaves an existing OUT untouched on failure")

    # Usage errors: exit 2.
    batch([os.path.join(ARGS.work, "nowhere"), out], expect=2)
    batch([src, src], expect=2)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def case_cluster():
    src, out = os.path.join(ARGS.work, "in"), os.path.join(ARGS.work, "out")
    make_inputs(src, n_good=8)
    for rel in list(BAD):   # two bad files are enough here
        if rel not in ("bad_nan.ply", "bad_empty_file.ply"):
            os.remove(os.path.join(src, rel))
            del BAD[rel]
    port = free_port()
    address = "tcp://127.0.0.1:%d" % port
    logs = open(os.path.join(ARGS.work, "dask.log"), "w")
    procs = []
    env = dict(os.environ, PATH="/usr/bin:/bin")    # the CLI is not on the workers' PATH
    try:
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
             "--port", str(port), "--no-dashboard"], stdout=logs, stderr=logs, env=env,
            cwd=ARGS.work, start_new_session=True))
        for i in range(2):
            procs.append(subprocess.Popen(
                [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads",
                 "1", "--no-nanny", "--no-dashboard", "--name", "w%d" % i],
                stdout=logs, stderr=logs, env=env, cwd=ARGS.work, start_new_session=True))
        from distributed import Client
        with Client(address, timeout="60s") as c:
            c.wait_for_workers(2, timeout=60)
        worker_pids = {p.pid for p in procs[1:]}

        batch([src, out, "-r", "--scheduler", address, "--cli", ARGS.tool, "--"] + OPTIONS,
              expect=1)
        status = {rel: "ok" for rel in GOOD}
        status.update({rel: "failed" for rel in BAD})
        report = check_report(os.path.join(out, "batch-report.json"), status)
        used = {r["pid"] for r in report["files"]}
        check(used <= worker_pids, "tasks ran in processes %r, not in the workers %r" %
              (used, worker_pids))
        check(report["scheduler"] == address, "report names scheduler %r" % report["scheduler"])
        check(all_files(out) == sorted(list(GOOD) + ["batch-report.json"]),
              "output folder holds %r" % all_files(out))
        print("ok: %d files on the scheduler at %s, in worker processes %r (of %r)" %
              (len(report["files"]), address, sorted(used), sorted(worker_pids)))

        # The CLI missing on the workers: every file fails with a message saying so.
        stdout, _ = batch([src, os.path.join(ARGS.work, "out2"), "-r", "--scheduler", address,
                           "--cli", "implicit-fairing"], expect=1)
        with open(os.path.join(ARGS.work, "out2", "batch-report.json")) as f:
            r = json.load(f)
        check(r["counts"]["failed"] == len(GOOD) + len(BAD), "counts %r" % r["counts"])
        check(all("not found on worker" in f["error"] and "--cli" in f["error"]
                  for f in r["files"]), "missing CLI not reported: %r" % r["files"][0]["error"])
        print("ok: a CLI missing on the workers is reported per file")
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
        logs.close()
    # Unreachable scheduler: exit 2 with a message.
    _, err = batch([src, os.path.join(ARGS.work, "out3"), "--scheduler", address,
                    "--connect-timeout", "3", "--cli", ARGS.tool], expect=2)
    check("cannot reach the scheduler" in err, "no message for an unreachable scheduler")


def main():
    global ARGS, ML, CLI_TEST
    p = argparse.ArgumentParser()
    p.add_argument("case", choices=["local", "cluster"])
    p.add_argument("--batch", required=True)
    p.add_argument("--tool", required=True)
    p.add_argument("--mltest", required=True)
    p.add_argument("--work", required=True)
    ARGS = p.parse_args()
    try:
        import distributed  # noqa: F401
    except ImportError:
        print("FAIL: python3-distributed is not installed for %s (scripts/setup.sh installs it)"
              % sys.executable)
        return 1
    spec = importlib.util.spec_from_file_location("mltest", ARGS.mltest)
    ML = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ML)
    spec = importlib.util.spec_from_file_location(
        "test_cli", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli",
                                 "test_cli.py"))
    CLI_TEST = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(CLI_TEST)
    CLI_TEST.ML = ML
    shutil.rmtree(ARGS.work, ignore_errors=True)
    os.makedirs(ARGS.work)
    {"local": case_local, "cluster": case_cluster}[ARGS.case]()
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
