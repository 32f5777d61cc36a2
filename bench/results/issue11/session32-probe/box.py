#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""A closed 2 x 1 x 0.05 box, 40 x 20 x 1 cells (auto-gap.md sections 29 and 32): box.py OUT.ply"""
import os, sys, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import write_ply
nx, ny, nz = 40, 20, 1; sx, sy, sz = 2.0, 1.0, 0.05
idx = {}; V = []; F = []
def vid(i, j, k):
    key = (i, j, k)
    if key not in idx: idx[key] = len(V); V.append((sx * i / nx, sy * j / ny, sz * k / nz))
    return idx[key]
def face(fixed_axis, value, flip):
    dims = [nx, ny, nz]; a, b = [d for d in range(3) if d != fixed_axis]
    for u in range(dims[a]):
        for w in range(dims[b]):
            def p(uu, ww):
                c = [0, 0, 0]; c[fixed_axis] = value; c[a] = uu; c[b] = ww; return vid(*c)
            q = [p(u, w), p(u + 1, w), p(u + 1, w + 1), p(u, w + 1)]
            t1, t2 = [q[0], q[1], q[2]], [q[0], q[2], q[3]]
            if flip: t1, t2 = t1[::-1], t2[::-1]
            F.extend([t1, t2])
face(2, 0, True); face(2, nz, False); face(1, 0, False); face(1, ny, True); face(0, 0, True); face(0, nx, False)
V = np.array(V); F = np.array(F)
write_ply(sys.argv[1], V, F)
