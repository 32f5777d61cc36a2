#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 44: a thin closed plate of N x N cells and thickness T cells (top and
# bottom interior vertices jittered by up to a quarter cell, seed SEED), as ASCII PLY; numpy.
# Usage: python3 plate.py N T OUT.ply [SEED]
import sys, numpy as np
N = int(sys.argv[1]); T = float(sys.argv[2]); out = sys.argv[3]; seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
rng = np.random.default_rng(seed)
V = []; F = []
def vid(layer, i, j): return layer * (N + 1) ** 2 + i * (N + 1) + j
for layer, z in ((0, T / 2), (1, -T / 2)):
    for i in range(N + 1):
        for j in range(N + 1):
            jit = rng.uniform(-0.25, 0.25, 2) if 0 < i < N and 0 < j < N else np.zeros(2)
            V.append([i + jit[0], j + jit[1], z])
def quad(a, b, c, d, flip):
    if flip: F.extend([[a, b, d], [b, c, d]])
    else: F.extend([[a, b, c], [a, c, d]])
for i in range(N):
    for j in range(N):
        f = (i + j) % 2 == 0
        quad(vid(0, i, j), vid(0, i + 1, j), vid(0, i + 1, j + 1), vid(0, i, j + 1), f)   # top, normal +z
        quad(vid(1, i, j), vid(1, i, j + 1), vid(1, i + 1, j + 1), vid(1, i + 1, j), f)   # bottom, -z
# sides: walk the boundary ring counterclockwise seen from +z
ring = [(i, 0) for i in range(N)] + [(N, j) for j in range(N)] + [(i, N) for i in range(N, 0, -1)] + [(0, j) for j in range(N, 0, -1)]
for k in range(len(ring)):
    a, b = ring[k], ring[(k + 1) % len(ring)]
    quad(vid(0, *b), vid(0, *a), vid(1, *a), vid(1, *b), False)
V = np.array(V); F = np.array(F)
with open(out, "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(V), len(F)))
    for v in V: f.write("%r %r %r\n" % tuple(v))
    for t in F: f.write("3 %d %d %d\n" % tuple(t))
