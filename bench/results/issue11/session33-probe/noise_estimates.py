#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The noise level read by the engine's estimate (1.4826 x MAD of the uniform bi-Laplacian's
normal component over its stencil norm, interior two-rings), by lower quantiles of the same
values, and by a quadric fit over the two-ring (exact for quadrics), each over the true sigma.
  noise_estimates.py NOISY CLEAN SIGMA_EDGES [NOISY CLEAN SIGMA_EDGES ...]"""
import sys
import numpy as np
import scipy.sparse as sp
from scipy.stats import norm
from meshio33 import read_any, mean_edge, adjacency, boundary, robust_normals


def bilaplacian_values(v, f):
    A, b = adjacency(v, f), boundary(v, f)
    n = len(v)
    m = np.asarray(A.sum(1)).ravel()
    L = sp.diags(1 / m) @ A - sp.identity(n)
    L2 = (L @ L).tocsr()
    vals = np.einsum("ij,ij->i", robust_normals(v, f, A), L2 @ v)
    vals /= np.sqrt(np.asarray(L2.multiply(L2).sum(1)).ravel())
    interior = ~b & ~((A @ b.astype(float)) > 0)
    return vals[interior]


def quadric_values(v, f):
    A, b = adjacency(v, f), boundary(v, f)
    h = mean_edge(v, f)
    nrm = robust_normals(v, f, A)
    A2 = (A @ A + A).tocsr()
    vals = []
    for i in range(len(v)):
        nb = A2.indices[A2.indptr[i]:A2.indptr[i + 1]]
        nb = nb[nb != i]
        if b[i] or len(nb) < 8 or b[nb].any():
            continue
        t1 = np.cross(nrm[i], [1, 0, 0])
        if np.linalg.norm(t1) < 0.5:
            t1 = np.cross(nrm[i], [0, 1, 0])
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(nrm[i], t1)
        d = v[nb] - v[i]
        u, w, z = d @ t1 / h, d @ t2 / h, d @ nrm[i]
        M = np.c_[u * u, u * w, w * w, u, w, np.ones_like(u)]
        weights = np.linalg.pinv(M)[5]  # the fitted height at the vertex
        vals.append(-(weights @ z) / np.sqrt(1 + weights @ weights))
    return np.array(vals)


def mad(x):
    return 1.4826 * np.median(np.abs(x - np.median(x)))


for noisy, clean, sigma in zip(sys.argv[1::3], sys.argv[2::3], map(float, sys.argv[3::3])):
    vn, fn = read_any(noisy)
    vc, fc = read_any(clean)
    unit = mean_edge(vc, fc) * sigma
    x = bilaplacian_values(vn, fn)
    a = np.abs(x - np.median(x))
    q = " ".join("q%.2f %.3f" % (p, np.quantile(a, p) / norm.ppf(0.5 + p / 2) / unit) for p in (0.1, 0.25))
    print("%-32s bi-Laplacian MAD %.3f, %s; quadric fit MAD %.3f (x true)"
          % (noisy.split("/")[-1], mad(x) / unit, q, mad(quadric_values(vn, fn)) / unit))
