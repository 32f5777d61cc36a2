#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
import os, sys, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply, area_normals, Umbrella
clean, *outs = sys.argv[1:]
xc, f = read_ply(clean); nc, _ = area_normals(xc, f)
e = np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1)
u, c = np.unique(e, axis=0, return_counts=True)
bd = np.zeros(len(xc), bool); bd[u[c == 1].ravel()] = True
# ring distance from boundary
L = Umbrella(f, len(xc)); ring = np.where(bd, 0, 99)
for k in range(1, 6):
    nb = np.zeros(len(xc)); i, j = L.e[:, 0], L.e[:, 1]
    m = (ring <= k - 1).astype(float)
    nb = np.bincount(i, m[j], len(xc)) + np.bincount(j, m[i], len(xc))
    ring = np.where((ring == 99) & (nb > 0), k, ring)
h = np.mean(np.linalg.norm(xc[L.e[:, 0]] - xc[L.e[:, 1]], axis=1))
for o in outs:
    y, _ = read_ply(o); d = np.einsum("ij,ij->i", nc, y - xc) / h
    tot = (d ** 2).sum()
    parts = []
    for k in (0, 1, 2, 3, 99):
        s = ring == k if k < 99 else ring >= 4
        parts.append("r%s n=%d rms=%.4f share=%.2f" % (k if k < 99 else "4+", s.sum(), np.sqrt((d[s] ** 2).mean()), (d[s] ** 2).sum() / tot))
    print(o, "rms %.4f" % np.sqrt((d ** 2).mean()), "|", "; ".join(parts))
