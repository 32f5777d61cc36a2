#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43 (not kept): the noise estimate's statistic along the normals of a lightly
# smoothed copy (four lazy umbrella passes), with the uniform bi-Laplacian and with the cotangent
# one whose weights come from that copy (so linear in the data), each value about its valence's
# median. Clean: in mean edges; noisy: over the noise put in. numpy and scipy.
# Usage: [MESHES=DIR] python3 cotsig.py MESH...
import os, sys
import numpy as np, scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plyio import normals  # noqa: E402
from readings import clean_mesh, noisy_copies  # noqa: E402


def cotangent(X, F, n):
    I, J, W = [], [], []
    for k in range(3):
        i, j, o = F[:, k], F[:, (k + 1) % 3], F[:, (k + 2) % 3]
        u, v = X[i] - X[o], X[j] - X[o]
        c = np.einsum("ij,ij->i", u, v) / np.maximum(np.linalg.norm(np.cross(u, v), axis=1), 1e-300)
        I += [i, j]; J += [j, i]; W += [0.5 * c, 0.5 * c]
    A = sp.coo_matrix((np.concatenate(W), (np.concatenate(I), np.concatenate(J))), shape=(n, n)).tocsr()
    area = np.zeros(n)
    fa = 0.5 * np.linalg.norm(np.cross(X[F[:, 1]] - X[F[:, 0]], X[F[:, 2]] - X[F[:, 0]]), axis=1)
    for k in range(3): np.add.at(area, F[:, k], fa / 3)
    return (sp.diags(1 / area) @ (A - sp.diags(np.asarray(A.sum(1)).ravel()))).tocsr()


def reading(Y, F, Lu, deg, h):
    S = Y
    for _ in range(4): S = S + 0.5 * (Lu @ S)
    N = normals(S, F)
    out = []
    for L in (Lu, cotangent(S, F, len(Y))):
        L2 = L @ L
        v = np.einsum("ij,ij->i", N, L2 @ Y) / np.sqrt(np.asarray(L2.multiply(L2).sum(1)).ravel()) / h
        for k in np.unique(deg): v[deg == k] -= np.median(v[deg == k])
        out.append(1.482602218505602 * np.median(np.abs(v)))
    return out


for mesh in sys.argv[1:]:
    C, F, Lu, _, _, deg, h = clean_mesh(mesh)
    out = ["clean %.3f/%.3f" % tuple(reading(C, F, Lu, deg, h))]
    for s, sigma, Y in noisy_copies(mesh, len(C)):
        a, b = reading(Y, F, Lu, deg, h)
        out.append("%s %.2f/%.2f" % (s, a / sigma, b / sigma))
    print(mesh, "(umbrella/cotangent)", " ".join(out), flush=True)
