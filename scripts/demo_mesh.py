#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The main job's default mesh and its figures (standard library only).

  demo_mesh.py gen OUTDIR
      writes OUTDIR/clean.ply and OUTDIR/noisy.ply: an irregularly sampled torus (R = 1,
      r = 0.4, 14,400 faces) and the same torus with Gaussian noise of 0.25 mean edge lengths
      along the normals (the noise level PEERS.md measured the peers at).
  demo_mesh.py measure MESH.ply
      prints "rms_error volume": the RMS distance of the vertices to the clean torus, in mean
      edge lengths of the clean mesh, and the enclosed volume (eq. 10).
"""
import math
import random
import struct
import sys

R_MAJOR, R_MINOR = 1.0, 0.4
NU, NV = 120, 60
SEED = 1

_TYPES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I",
          "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
          "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}


def torus_point(u, v):
    c = R_MAJOR + R_MINOR * math.cos(v)
    p = (c * math.cos(u), c * math.sin(u), R_MINOR * math.sin(v))
    n = (math.cos(v) * math.cos(u), math.cos(v) * math.sin(u), math.sin(v))
    return p, n


def torus(seed):
    rng = random.Random(seed)
    verts, normals, faces = [], [], []
    for i in range(NU):
        for j in range(NV):
            # Irregular sampling: every vertex jittered by up to 0.3 cells in both directions.
            u = 2 * math.pi * (i + rng.uniform(-0.3, 0.3)) / NU
            v = 2 * math.pi * (j + rng.uniform(-0.3, 0.3)) / NV
            p, n = torus_point(u, v)
            verts.append(p)
            normals.append(n)
    for i in range(NU):
        for j in range(NV):
            a, b = i * NV + j, ((i + 1) % NU) * NV + j
            c, d = ((i + 1) % NU) * NV + (j + 1) % NV, i * NV + (j + 1) % NV
            if rng.random() < 0.5:
                faces += [(a, b, c), (a, c, d)]
            else:
                faces += [(a, b, d), (b, c, d)]
    return verts, normals, faces


def mean_edge(verts, faces):
    edges = set()
    for f in faces:
        for k in range(3):
            a, b = f[k], f[(k + 1) % 3]
            edges.add((min(a, b), max(a, b)))
    return sum(math.dist(verts[a], verts[b]) for a, b in edges) / len(edges)


def write_ply(path, verts, faces):
    with open(path, "wb") as out:
        out.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                   % (len(verts), len(faces))).encode())
        for p in verts:
            out.write(struct.pack("<3f", *p))
        for f in faces:
            out.write(struct.pack("<B3i", 3, *f))


def read_ply(path):
    """Vertices (x, y, z) and triangles of an ASCII or binary little-endian PLY."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    header = data[:end].decode("ascii", "replace").splitlines()
    fmt = next(l.split()[1] for l in header if l.startswith("format"))
    elements = []
    for line in header:
        w = line.split()
        if w and w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w and w[0] == "property":
            elements[-1][2].append(w[1:])
    verts, faces = [], []
    if fmt == "ascii":
        tokens = data[end:].split()
        pos = 0
        for name, count, props in elements:
            for _ in range(count):
                row = {}
                for p in props:
                    if p[0] == "list":
                        k = int(tokens[pos]); pos += 1
                        row[p[3]] = [int(t) for t in tokens[pos:pos + k]]; pos += k
                    else:
                        row[p[1]] = float(tokens[pos]); pos += 1
                (verts if name == "vertex" else faces).append(row)
    else:
        pos = end
        for name, count, props in elements:
            for _ in range(count):
                row = {}
                for p in props:
                    if p[0] == "list":
                        (k,) = struct.unpack_from("<" + _TYPES[p[1]], data, pos)
                        pos += struct.calcsize(_TYPES[p[1]])
                        t = _TYPES[p[2]]
                        row[p[3]] = list(struct.unpack_from("<%d%s" % (k, t), data, pos))
                        pos += k * struct.calcsize(t)
                    else:
                        t = _TYPES[p[0]]
                        (row[p[1]],) = struct.unpack_from("<" + t, data, pos)
                        pos += struct.calcsize(t)
                (verts if name == "vertex" else faces).append(row)
    key = "vertex_indices" if faces and "vertex_indices" in faces[0] else "vertex_index"
    return ([(v["x"], v["y"], v["z"]) for v in verts],
            [tuple(f[key]) for f in faces])


def volume(verts, faces):
    s = 0.0
    for a, b, c in faces:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = verts[a], verts[b], verts[c]
        s += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return s / 6.0


def torus_distance(p):
    x, y, z = p
    return abs(math.hypot(math.hypot(x, y) - R_MAJOR, z) - R_MINOR)


def main(argv):
    if len(argv) >= 2 and argv[0] == "gen":
        verts, normals, faces = torus(SEED)
        rng = random.Random(SEED + 1)
        sigma = 0.25 * mean_edge(verts, faces)
        noisy = []
        for p, n in zip(verts, normals):
            t = rng.gauss(0.0, sigma)
            noisy.append(tuple(p[k] + t * n[k] for k in range(3)))
        write_ply(argv[1] + "/clean.ply", verts, faces)
        write_ply(argv[1] + "/noisy.ply", noisy, faces)
        return 0
    if len(argv) == 2 and argv[0] == "measure":
        verts, faces = read_ply(argv[1])
        rms = float("nan")  # only the generated torus has a known clean surface
        if len(verts) == NU * NV:
            clean_edge = mean_edge(torus(SEED)[0], faces)
            rms = math.sqrt(sum(torus_distance(p) ** 2 for p in verts) / len(verts)) / clean_edge
        print("%.6f %.9g" % (rms, volume(verts, faces)))
        return 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
