#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43 (not kept): the statistic with one median over all vertices against each
# value taken about the median of its two-ring, each calibrated on a draw of unit noise along the
# normals of the same mesh; clean in mean edges, at 0.1 edge over the noise. numpy and scipy.
# Usage: [MESHES=DIR] python3 localmed.py MESH...
import glob, os, sys
import numpy as np, scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
from plyio import read_ply, normals, MESHES  # noqa: E402
MESHES = os.environ.get("MESHES", MESHES)


def mad(v):
    return 1.4826 * np.median(np.abs(v - np.median(v)))


def local(v, rings):
    return mad(np.array([v[i] - np.median(v[r]) for i, r in enumerate(rings)]))


for mesh in sys.argv[1:]:
    C, F = read_ply("%s/dn_%s_clean.ply" % (MESHES, mesh))
    n = len(C)
    E = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), 1), axis=0)
    A = sp.coo_matrix((np.ones(2 * len(E)), (np.r_[E[:, 0], E[:, 1]], np.r_[E[:, 1], E[:, 0]])),
                      shape=(n, n)).tocsr()
    L = (sp.diags(1 / np.asarray(A.sum(1)).ravel()) @ A - sp.eye(n)).tocsr()
    h = np.linalg.norm(C[E[:, 0]] - C[E[:, 1]], axis=1).mean()
    R2 = ((A + sp.eye(n)) @ (A + sp.eye(n))).tocsr()
    rings = [R2.indices[R2.indptr[i]:R2.indptr[i + 1]] for i in range(n)]
    L2 = L @ L
    norm = np.sqrt(np.asarray(L2.multiply(L2).sum(1)).ravel())
    field = lambda Y, N: np.einsum("ij,ij->i", N, L2 @ Y) / norm
    N = normals(C, F)
    unit = N * np.random.default_rng(0).standard_normal(n)[:, None]
    cal_global, cal_local = mad(field(unit, N)), local(field(unit, N), rings)
    v = field(C, N)
    out = ["clean %.3f/%.3f" % (mad(v) / cal_global / h, local(v, rings) / cal_local / h)]
    for f in sorted(glob.glob("%s/dn_%s_n0.1*.ply" % (MESHES, mesh))):
        s = os.path.basename(f)[len("dn_%s_" % mesh):-4]
        Y, _ = read_ply(f)
        v = field(Y, normals(Y, F))
        out.append("%s %.2f/%.2f" % (s, mad(v) / cal_global / h / 0.1, local(v, rings) / cal_local / h / 0.1))
    print(mesh, "(one median / two-ring medians)", " ".join(out), flush=True)
