#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Per connected component (largest 30): vertices, bounding-box diagonal in mean edges, and the
RMS error along the clean normals (edges) of the noisy input and of each result.
  components.py CLEAN NOISY RESULT..."""
import sys
import numpy as np
from scipy.sparse.csgraph import connected_components
from meshio33 import read_any, mean_edge, adjacency
from restoration_floor import area_normals

vc, f = read_any(sys.argv[1])
h = mean_edge(vc, f)
count, label = connected_components(adjacency(vc, f), directed=False)
normals, _ = area_normals(vc, f)
normals = np.nan_to_num(normals)
results = [read_any(p)[0] for p in sys.argv[2:]]
sizes = np.bincount(label)
print("components", count)
for c in np.argsort(-sizes)[:30]:
    idx = label == c
    row = ["component %2d: %5d vertices, %.1f edges across" % (c, sizes[c], np.linalg.norm(np.ptp(vc[idx], 0)) / h)]
    for x in results:
        d = np.einsum("ij,ij->i", normals[idx], x[idx] - vc[idx]) / h
        row.append("%.3f" % np.sqrt(np.mean(d ** 2)))
    print(" ".join(row))
