#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: three numberings of a binary PLY compared by the index gaps of its edges
# and the share of edges inside one sweep block of 8,192 rows (sweeps.h): the former Z-order
# curve, breadth-first (the engine's now), and patches of 4,096 or 8,192 vertices grown
# breadth-first in that order. Needs numpy (/usr/bin/python3).
# Usage: /usr/bin/python3 patch_order.py MESH.ply
import os, sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from order_gaps import adjacency, breadth_first, edge_gaps, morton, read  # noqa: E402


def patches(order, start, column, size):
    """Patches of at most `size` vertices grown breadth-first over the vertices not yet taken,
    seeded in `order`."""
    taken, out = bytearray(len(order)), []
    for s in order:
        if taken[s]:
            continue
        first = len(out)
        out.append(s)
        taken[s] = 1
        head = first
        while head < len(out):
            u = out[head]
            head += 1
            for k in range(start[u], start[u + 1]):
                w = column[k]
                if not taken[w] and len(out) - first < size:
                    taken[w] = 1
                    out.append(w)
    return out


def stats(name, order, f):
    a, g = edge_gaps(order, f)
    b = a // 8192
    inside = np.concatenate([b[:, 0] == b[:, 1], b[:, 1] == b[:, 2], b[:, 2] == b[:, 0]]).mean()
    print(name, "gap pct50/90/99/99.9", np.percentile(g, [50, 90, 99, 99.9]).astype(int),
          ">4096 %.4f >65536 %.4f" % ((g > 4096).mean(), (g > 65536).mean()),
          "in-block %.3f" % inside)


v, f = read(sys.argv[1])
n = len(v)
start, column = adjacency(n, f)
bfs = breadth_first(n, start, column)
stats("morton", morton(v), f)
stats("bfs", bfs, f)
for size in (4096, 8192):
    stats("patch%d" % size, patches(bfs, start, column, size), f)
