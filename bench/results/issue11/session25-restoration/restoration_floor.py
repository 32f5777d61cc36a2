#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 25's table: how close a volume-exact normal offset t w_i n_i can bring the
umbrella L^2 filter's unrestored result to the clean mesh, for several fields w (measurement aid,
not part of any build).

    restoration_floor.py NOISY CLEAN TIME_STEP STEPS BIN

BIN holds fairing-bench-tool and fairing-denoise-tool (bench/ built with CMake). Prints a JSON
object: the unrestored result's error, the engine's (uniform offset), and the error after each field
(edges of CLEAN, `fairing-denoise-tool eval`), and how the clean mesh's L^2 field correlates with the
same field of the result and of the noisy input. Needs numpy only."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

DTYPE_FACE = np.dtype([("n", "u1"), ("i", "<i4", 3)])


def read_ply(path):
    with open(path, "rb") as f:
        header = []
        while header[-1:] != ["end_header"]:
            header.append(f.readline().decode().strip())
        count = {h.split()[1]: int(h.split()[2]) for h in header if h.startswith("element")}
        t = "<f8" if any("double x" in h for h in header) else "<f4"
        v = np.frombuffer(f.read(count["vertex"] * 3 * np.dtype(t).itemsize), t).reshape(-1, 3)
        faces = np.frombuffer(f.read(count["face"] * DTYPE_FACE.itemsize), DTYPE_FACE)
        return v.astype(float), faces["i"].copy()


def write_ply(path, v, f):
    with open(path, "wb") as o:
        o.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\n"
                 "property double y\nproperty double z\nelement face %d\n"
                 "property list uchar int vertex_indices\nend_header\n" % (len(v), len(f))).encode())
        o.write(np.ascontiguousarray(v, "<f8").tobytes())
        faces = np.zeros(len(f), DTYPE_FACE)
        faces["n"], faces["i"] = 3, f
        o.write(faces.tobytes())


def area_normals(v, f):
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    length = np.linalg.norm(n, axis=1)
    return n / length[:, None], length / 6  # unit normals, a third of the ring's area


def volume(v, f):
    return np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum() / 6


class Umbrella:
    """L x = mean of the neighbours - x (the paper's eq. 7)."""

    def __init__(self, f, count):
        e = np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1)
        self.e, self.count = np.unique(e, axis=0), count
        self.valence = np.bincount(self.e.ravel(), minlength=count).astype(float)

    def __call__(self, x):
        i, j = self.e[:, 0], self.e[:, 1]
        x2 = x.reshape(len(x), -1)
        out = np.stack([np.bincount(i, x2[j, k], self.count) + np.bincount(j, x2[i, k], self.count)
                        for k in range(x2.shape[1])], axis=1)
        return (out / self.valence[:, None] - x2).reshape(x.shape)


def smooth(L, x, passes):  # umbrella half-passes
    for _ in range(passes):
        x = x + 0.5 * L(x)
    return x


def restore(y, f, w, target):
    """y + t w n (n: y's unit area normals), t by Newton on the volume's cubic."""
    n, _ = area_normals(y, f)
    t = 0.0
    for _ in range(30):
        z = y + t * w[:, None] * n
        nz, az = area_normals(z, f)
        step = (target - volume(z, f)) / (3 * az * w * np.einsum("ij,ij->i", nz, n)).sum()
        t += step
        if abs(step) < 1e-15 * (1 + abs(t)):
            break
    return y + t * w[:, None] * n


def main():
    noisy, clean, ts, steps, bin_dir = sys.argv[1:6]
    bt, dt = os.path.join(bin_dir, "fairing-bench-tool"), os.path.join(bin_dir, "fairing-denoise-tool")
    run = lambda c: subprocess.run(c, check=True, capture_output=True, text=True).stdout
    xc, f = read_ply(clean)
    x, _ = read_ply(noisy)
    L = Umbrella(f, len(x))
    tmp = tempfile.mkdtemp()
    out = lambda name: os.path.join(tmp, name + ".ply")
    run([bt, "fair", noisy, out("unrestored"), "umbrella", "2", ts, steps, "volume=0"])
    run([bt, "fair", noisy, out("engine"), "umbrella", "2", ts, steps])
    run([bt, "fair", noisy, out("twice"), "umbrella", "2", repr(2 * float(ts)), steps, "volume=0"])
    y, _ = read_ply(out("unrestored"))
    y2, _ = read_ply(out("twice"))
    ny, nc, n2, nx = (area_normals(p, f)[0] for p in (y, xc, y2, x))
    l2 = lambda p, n: np.einsum("ij,ij->i", n, L(L(p)))
    fields = {"uniform": np.ones(len(x))}
    truth = np.einsum("ij,ij->i", ny, xc - y)
    for k in (64, 256):
        fields["true error, %d passes" % k] = smooth(L, truth, k)
    for name, base in (("clean", l2(xc, nc)), ("result", l2(y, ny)), ("result at twice the step", l2(y2, n2)),
                       ("noisy input", l2(x, nx))):
        for k in (0, 1, 2, 4, 8):
            fields["L2 field of the %s, positive part, %d passes" % (name, k)] = np.maximum(0, smooth(L, base, k))
    names = []
    for i, (name, w) in enumerate(fields.items()):
        write_ply(out("field%d" % i), restore(y, f, w / w.mean(), volume(x, f)), f)
        names.append(name)
    files = [out("unrestored"), out("engine")] + [out("field%d" % i) for i in range(len(names))]
    errors = [json.loads(l)["rms"] for l in run([dt, "eval", clean, "mesh", noisy] + files).splitlines() if l]
    correlation = {"correlation of the clean L2 field with the " + name: round(np.corrcoef(l2(xc, nc), base)[0, 1], 3)
                   for name, base in (("result's", l2(y, ny)), ("noisy input's", l2(x, nx)))}
    print(json.dumps(dict(unrestored=errors[0], engine=errors[1], **dict(zip(names, errors[2:])), **correlation),
                     indent=1))


if __name__ == "__main__":
    main()
