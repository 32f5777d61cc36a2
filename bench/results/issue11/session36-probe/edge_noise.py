#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""A noise estimate that a flat facet cannot inflate, against the engine's (measured, not kept).
Each interior edge and its two triangles form a quad i, j, k, l; the distance between the lines
ij and kl along their common perpendicular is exactly 0 when the quad is planar, and to first
order it is the normal noise of the four corners weighted by the lines' crossing parameters s, t,
so divided by sqrt((1-s)^2 + s^2 + (1-t)^2 + t^2) it reads sigma. A low quantile of its absolute
values would then skip the edges that cross a crease. Printed over the true sigma: the engine's
estimate (bi-Laplacian MAD, session33-probe/noise_estimates.py), this one at the 10th, 25th and
50th percentiles, and its 25th percentile on the clean mesh.
  edge_noise.py NOISY CLEAN SIGMA_EDGES [NOISY CLEAN SIGMA_EDGES ...]"""
import os
import sys
import numpy as np
from scipy.stats import norm
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                "session33-probe"))
from meshio33 import read_any, mean_edge  # noqa: E402
argv, sys.argv = sys.argv, sys.argv[:1]  # noise_estimates runs its own loop over sys.argv
from noise_estimates import bilaplacian_values, mad  # noqa: E402
sys.argv = argv


def edge_values(v, f):
    # Half-edges (a, b, opposite); an interior edge is a key held by exactly two of them.
    he = np.r_[f[:, [0, 1, 2]], f[:, [1, 2, 0]], f[:, [2, 0, 1]]]
    key = np.minimum(he[:, 0], he[:, 1]) * (len(v) + 1) + np.maximum(he[:, 0], he[:, 1])
    order = np.argsort(key, kind="stable")
    k = key[order]
    _, first, count = np.unique(k, return_index=True, return_counts=True)
    pair = first[count == 2]
    h1, h2 = he[order[pair]], he[order[pair + 1]]
    xi, xj, xk, xl = v[h1[:, 0]], v[h1[:, 1]], v[h1[:, 2]], v[h2[:, 2]]
    d1, d2, w0 = xj - xi, xl - xk, xi - xk
    a, b, c = (d1 * d1).sum(1), (d1 * d2).sum(1), (d2 * d2).sum(1)
    d, e = (d1 * w0).sum(1), (d2 * w0).sum(1)
    den = a * c - b * b
    ok = den > 1e-12 * a * c
    safe = np.where(ok, den, 1)
    s, t = (b * e - c * d) / safe, (a * e - b * d) / safe
    dist = np.linalg.norm(xk + t[:, None] * d2 - xi - s[:, None] * d1, axis=1)
    factor = np.sqrt((1 - s) ** 2 + s ** 2 + (1 - t) ** 2 + t ** 2)
    keep = ok & (s > -0.5) & (s < 1.5) & (t > -0.5) & (t < 1.5)
    return dist[keep] / factor[keep]


def quantile_estimate(x, p):
    return np.quantile(np.abs(x), p) / norm.ppf(0.5 + p / 2)


for noisy, clean, sigma in zip(sys.argv[1::3], sys.argv[2::3], map(float, sys.argv[3::3])):
    vn, fn = read_any(noisy)
    vc, fc = read_any(clean)
    unit = mean_edge(vc, fc) * sigma
    values = edge_values(vn, fn)
    print("%-30s bi-Laplacian %.3f | edges q.10 %.3f q.25 %.3f q.50 %.3f | clean q.25 %.3f"
          % (os.path.basename(noisy), mad(bilaplacian_values(vn, fn)) / unit,
             quantile_estimate(values, .1) / unit, quantile_estimate(values, .25) / unit,
             quantile_estimate(values, .5) / unit,
             quantile_estimate(edge_values(vc, fc), .25) / unit), flush=True)
