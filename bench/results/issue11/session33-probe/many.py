#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""A unit icosphere of LEVELS subdivisions (none: -1) beside NTINY icosahedra of its edge, a
quarter edge of Gaussian noise in all directions (seed 5): OUT.ply, and the clean OUT_clean.ply.
  many.py LEVELS NTINY OUT.ply"""
import os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import write_ply
def icosa():
    t = (1 + 5 ** 0.5) / 2
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])
    return v / np.linalg.norm(v[0]), f
def sphere(levels):
    v, f = icosa()
    for _ in range(levels):
        edges = {}
        nv = list(v)
        nf = []
        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in edges:
                p = (nv[a] + nv[b]) / 2; nv.append(p / np.linalg.norm(p)); edges[k] = len(nv) - 1
            return edges[k]
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        v, f = np.array(nv), np.array(nf)
    return v, f
big_levels, ntiny, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
rng = np.random.default_rng(5)
V, F = [], []
n = 0
if big_levels >= 0:
    v, f = sphere(big_levels); h = np.linalg.norm(v[f[0, 0]] - v[f[0, 1]])
    V.append(v * 1.0); F.append(f); n += len(v)
else:
    h = 0.01
vt, ft = icosa()
scale = h / np.linalg.norm(vt[0] - vt[11])
for k in range(ntiny):
    c = np.array([3 + (k % 50) * 4 * scale, (k // 50) * 4 * scale, 0])
    V.append(vt * scale + c); F.append(ft + n); n += 12
v = np.vstack(V); f = np.vstack(F)
write_ply(out.replace(".ply", "_clean.ply"), v, f)
v += rng.normal(0, 0.25 * h, v.shape)
write_ply(out, v, f)
print(len(v), "vertices", len(f), "faces")
