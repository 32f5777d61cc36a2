#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Shared helpers of session 33's measurement scripts: OFF/PLY reading, mean edge, normals."""
import os, sys
import numpy as np
import scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply, area_normals  # noqa: E402


def read_any(path):
    """Vertices and triangles of a PLY (the study's) or an OFF (libcgal-demo's; polygons fanned)."""
    if path.endswith(".ply"):
        return read_ply(path)
    toks = " ".join(l.split("#")[0] for l in open(path)).split()
    nv, nf, i = int(toks[1]), int(toks[2]), 4
    v = np.array(toks[i:i + 3 * nv], float).reshape(-1, 3)
    i += 3 * nv
    f = []
    for _ in range(nf):
        k = int(toks[i])
        idx = list(map(int, toks[i + 1:i + 1 + k]))
        i += 1 + k
        f += [[idx[0], idx[t], idx[t + 1]] for t in range(1, k - 1)]
    return v, np.array(f)


def edges(f):
    return np.unique(np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1), axis=0)


def mean_edge(v, f):
    e = edges(f)
    return np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).mean()


def adjacency(v, f):
    e = edges(f)
    n = len(v)
    return sp.coo_matrix((np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])),
                         shape=(n, n)).tocsr()


def boundary(v, f):
    ee = np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1)
    u, c = np.unique(ee, axis=0, return_counts=True)
    b = np.zeros(len(v), bool)
    b[u[c == 1].ravel()] = True
    return b


def robust_normals(v, f, A):
    """Area-weighted vertex normals averaged over the one-ring (the engine's robust_normals)."""
    n, _ = area_normals(v, f)
    n = np.nan_to_num(n)
    s = A @ n + n
    return s / np.maximum(np.linalg.norm(s, axis=1)[:, None], 1e-300)
