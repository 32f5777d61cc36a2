#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 44: a closed mesh's volume (eq. 10) against the model's volume,
# sum a_i n_i . (x_i - c) / 3, with a_i the vertex areas and n_i the normals of a copy smoothed by
# four umbrella half passes, averaged over the one-ring (as the estimate's robust normals), and
# the total area. numpy and scipy (python3-scipy); a measurement aid only.
# Usage: python3 vol.py MESH.ply ...  (e.g. the sponge's dn_cheese_18k_clean.ply and noisy copies)
import os, sys
import numpy as np, scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
from plyio import read_ply  # noqa: E402


def area_normals(X, F):
    fn = np.cross(X[F[:, 1]] - X[F[:, 0]], X[F[:, 2]] - X[F[:, 0]]) / 2
    N = np.zeros_like(X)
    for k in range(3):
        np.add.at(N, F[:, k], fn)
    return N


for path in sys.argv[1:]:
    X, F = read_ply(path)[:2]
    n = len(X)
    E = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), 1), axis=0)
    A = sp.coo_matrix((np.ones(2 * len(E)), (np.r_[E[:, 0], E[:, 1]], np.r_[E[:, 1], E[:, 0]])),
                      shape=(n, n)).tocsr()
    deg = np.asarray(A.sum(1)).ravel()
    S = X.copy()
    for _ in range(4):
        S = 0.5 * S + 0.5 * (A @ S) / deg[:, None]
    N = area_normals(S, F)
    N /= np.linalg.norm(N, axis=1)[:, None]
    N = N + A @ N
    N /= np.linalg.norm(N, axis=1)[:, None]
    t = np.einsum('ij,ij->i', X[F[:, 0]], np.cross(X[F[:, 1]], X[F[:, 2]])) / 6
    V = t.sum()
    c = ((X[F[:, 0]] + X[F[:, 1]] + X[F[:, 2]]) / 4 * t[:, None]).sum(0) / V  # solid centroid
    area = np.linalg.norm(np.cross(X[F[:, 1]] - X[F[:, 0]], X[F[:, 2]] - X[F[:, 0]]), axis=1) / 2
    a = np.zeros(n)
    for k in range(3):
        np.add.at(a, F[:, k], area / 3)
    model = (a * np.einsum('ij,ij->i', N, X - c)).sum() / 3
    print("%s V %.6g  model %.6g ratio %.3f  area %.5g" % (os.path.basename(path), V, model,
                                                          model / V, area.sum()))
