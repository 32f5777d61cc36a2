#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43 (not kept): the statistic with one median over all vertices against each
# value taken about the median of its two-ring, each calibrated on a draw of unit noise along the
# normals of the same mesh; clean in mean edges, at 0.1 edge over the noise. numpy and scipy.
# Usage: [MESHES=DIR] python3 localmed.py MESH...
import os, sys
import numpy as np, scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plyio import normals  # noqa: E402
from readings import clean_mesh, noisy_copies  # noqa: E402


def mad(v):
    return 1.4826 * np.median(np.abs(v - np.median(v)))


def local(v, rings):
    return mad(np.array([v[i] - np.median(v[r]) for i, r in enumerate(rings)]))


for mesh in sys.argv[1:]:
    C, F, L, A, E, deg, h = clean_mesh(mesh)
    n = len(C)
    R2 = ((A + sp.eye(n)) @ (A + sp.eye(n))).tocsr()
    rings = [R2.indices[R2.indptr[i]:R2.indptr[i + 1]] for i in range(n)]
    L2 = L @ L
    norm = np.sqrt(np.asarray(L2.multiply(L2).sum(1)).ravel())
    field = lambda Y, N: np.einsum("ij,ij->i", N, L2 @ Y) / norm
    N = normals(C, F)
    unit = N * np.random.default_rng(0).standard_normal(n)[:, None]
    noise = field(unit, N)
    cal_global, cal_local = mad(noise), local(noise, rings)
    v = field(C, N)
    out = ["clean %.3f/%.3f" % (mad(v) / cal_global / h, local(v, rings) / cal_local / h)]
    for s, sigma, Y in noisy_copies(mesh, n, "n0.1"):
        v = field(Y, normals(Y, F))
        out.append("%s %.2f/%.2f" % (s, mad(v) / cal_global / h / sigma,
                                      local(v, rings) / cal_local / h / sigma))
    print(mesh, "(one median / two-ring medians)", " ".join(out), flush=True)
