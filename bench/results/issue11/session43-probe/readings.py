#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43: the noise estimate's reading (1.4826 x MAD of the normal uniform
# bi-Laplacian over its stencil norm, area-weighted normals of the mesh itself) on a bench mesh's
# clean and noisy copies, three ways: one median over all vertices (the engine before 5482131),
# about each valence's median, and about each vertex type's (valence and the neighbours'
# valences, types of fewer than MIN vertices pooled by valence). Clean: in mean edges; noisy: over
# the noise put in. numpy and scipy (python3-scipy), measurement aid only.
# Usage: [MESHES=DIR] python3 readings.py MESH...   (e.g. knot2_12k cheese_18k; from any folder)
import glob, os, sys
import numpy as np, scipy.sparse as sp
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
import plyio  # noqa: E402
from plyio import read_ply, normals  # noqa: E402
MESHES = os.environ.get("MESHES", plyio.MESHES)  # a folder of dn_NAME_clean.ply and dn_NAME_*.ply
MIN = int(os.environ.get("MIN", "64"))


def umbrella(F, n):
    E = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), 1), axis=0)
    A = sp.coo_matrix((np.ones(2 * len(E)), (np.r_[E[:, 0], E[:, 1]], np.r_[E[:, 1], E[:, 0]])),
                      shape=(n, n)).tocsr()
    deg = np.asarray(A.sum(1)).ravel()
    return (sp.diags(1 / deg) @ A - sp.eye(n)).tocsr(), A, E, deg


def types(A, deg):
    key = []
    for i in range(len(deg)):
        nb = A.indices[A.indptr[i]:A.indptr[i + 1]]
        key.append((int(deg[i]),) + tuple(sorted(min(max(int(deg[j]), 3), 10) for j in nb)))
    count = {}
    for k in key: count[k] = count.get(k, 0) + 1
    key = [k if count[k] >= MIN else (k[0],) for k in key]
    ids = {k: i for i, k in enumerate(sorted(set(key)))}
    return np.array([ids[k] for k in key])


def reading(X, F, L2, norm, strata, h):
    v = np.einsum("ij,ij->i", normals(X, F), L2 @ X) / norm / h
    out = [1.482602218505602 * np.median(np.abs(v - np.median(v)))]
    for g in strata:
        d = v.copy()
        for k in np.unique(g):
            d[g == k] -= np.median(v[g == k])
        out.append(1.482602218505602 * np.median(np.abs(d)))
    return out


def clean_mesh(mesh):
    """The clean mesh's positions, faces, uniform Laplacian, adjacency, edges, valences and mean
    edge."""
    C, F = read_ply("%s/dn_%s_clean.ply" % (MESHES, mesh))
    L, A, E, deg = umbrella(F, len(C))
    return C, F, L, A, E, deg, np.linalg.norm(C[E[:, 0]] - C[E[:, 1]], axis=1).mean()


def noisy_copies(mesh, n, prefix=""):
    """(suffix, sigma in edges, positions) of each noisy copy of `mesh` with n vertices whose
    suffix starts with `prefix`."""
    for f in sorted(glob.glob("%s/dn_%s_%s*.ply" % (MESHES, mesh, prefix))):
        s = os.path.basename(f)[len("dn_%s_" % mesh):-4]
        if s == "clean": continue
        tag = s.split("_")[0]
        Y, _ = read_ply(f)
        if len(Y) == n: yield s, float(tag[3:]) if tag.startswith("iso") else float(tag[1:]), Y


if __name__ == "__main__":
    for mesh in sys.argv[1:]:
        C, F, L, A, E, deg, h = clean_mesh(mesh)
        L2 = L @ L
        norm = np.sqrt(np.asarray(L2.multiply(L2).sum(1)).ravel())
        strata = [deg, types(A, deg)]
        out = ["clean " + "/".join("%.3f" % x for x in reading(C, F, L2, norm, strata, h))]
        for s, sigma, Y in noisy_copies(mesh, len(C)):
            out.append(s + " " + "/".join("%.2f" % (x / sigma)
                                          for x in reading(Y, F, L2, norm, strata, h)))
        print(mesh, "(pooled/valence/type)", " ".join(out), flush=True)
