#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
import os, sys, numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply
xc, f = read_ply(sys.argv[1])
e = np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1); u, c = np.unique(e, axis=0, return_counts=True)
bd = np.zeros(len(xc), bool); bd[u[c == 1].ravel()] = True
h = np.linalg.norm(xc[u[:, 0]] - xc[u[:, 1]], axis=1).mean()
def area(y): return 0.5 * np.linalg.norm(np.cross(y[f[:, 1]] - y[f[:, 0]], y[f[:, 2]] - y[f[:, 0]]), axis=1).sum()
for p in sys.argv[2:]:
    y, _ = read_ply(p)
    print(p, "boundary displacement from clean (edges) mean %.3f max %.3f; area ratio %.4f" % (np.linalg.norm(y[bd] - xc[bd], axis=1).mean() / h, np.linalg.norm(y[bd] - xc[bd], axis=1).max() / h, area(y) / area(xc)))
