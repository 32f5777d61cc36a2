#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 23's restoration field (auto-gap.md section 23), a measurement aid, not part of the
# product: one weight per vertex for the curvature flow's volume offset, written one per line for
# engine-hack.diff's FAIR_W_FILE. Needs numpy (apt python3-numpy: /usr/bin/python3) and the bench
# tools (cmake --build BUILD --target fairing-bench-tool fairing-denoise-tool).
#   restoration_field.py NOISY.ply OUT.txt NOISE_EDGES TOOLS_DIR
# The field: the noisy mesh after one implicit curvature step L at time step 8, its cotangent mean
# curvature (cotangents clamped to +-19.1 as the operator clamps them) smoothed by 64 umbrella
# half-passes, pulled towards its mean by the share of its variance that noise does not explain.
# The noise's part is measured: the same recipe on the mesh with a second draw of noise at
# NOISE_EDGES along the normals (seed 99), the variance of the two fields' difference.
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../../scripts"))
from recipes_mesh import read_ply, vertex_normals  # noqa: E402  the project's PLY reader, normals


def mean_curvature(v, f):
    """n . (-L x) with the clamped cotangent operator and barycentric areas: 2H, outward > 0."""
    kx, area = np.zeros_like(v), np.zeros(len(v))
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        i, j, k = f[:, a], f[:, b], f[:, c]
        u, w = v[i] - v[k], v[j] - v[k]
        cot = np.einsum('ij,ij->i', u, w) / np.maximum(np.linalg.norm(np.cross(u, w), axis=1), 1e-300)
        half = 0.5 * np.clip(cot, -19.1, 19.1)
        np.add.at(kx, i, half[:, None] * (v[j] - v[i]))
        np.add.at(kx, j, half[:, None] * (v[i] - v[j]))
    face_area = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    for a in range(3):
        np.add.at(area, f[:, a], face_area / 3)
    return -np.einsum('ij,ij->i', vertex_normals(v, f), kx) / np.maximum(area, 1e-300)


def smoothed(w, f, passes):
    edges = np.unique(np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1), axis=0)
    degree = np.maximum(np.bincount(edges.ravel(), minlength=len(w)), 1)
    for _ in range(passes):
        s = np.zeros(len(w))
        np.add.at(s, edges[:, 0], w[edges[:, 1]])
        np.add.at(s, edges[:, 1], w[edges[:, 0]])
        w = 0.5 * w + 0.5 * s / degree
    return w


def field(noisy, tools, scratch):
    out = os.path.join(scratch, 'stepped.ply')
    subprocess.run([os.path.join(tools, 'fairing-bench-tool'), 'fair', noisy, out, 'curvature', '1',
                    '8', '1', 'threads=1'], check=True, capture_output=True)
    v, f = read_ply(out)
    return smoothed(mean_curvature(v, f), f, 64)


def main():
    noisy, out, level, tools = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
    with tempfile.TemporaryDirectory() as scratch:
        first = field(noisy, tools, scratch)
        redrawn = os.path.join(scratch, 'redrawn.ply')
        subprocess.run([os.path.join(tools, 'fairing-denoise-tool'), 'noise', noisy, redrawn, level,
                        '99', 'normal'], check=True, capture_output=True)
        second = field(redrawn, tools, scratch)
    share = max(0.0, 1 - np.var(second - first) / np.var(first))
    np.savetxt(out, first.mean() + share * (first - first.mean()))
    print('share %.3f' % share)


if __name__ == '__main__':
    main()
