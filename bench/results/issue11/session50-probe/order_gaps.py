#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: the index gaps of a binary PLY's edges in its own order, along the
# engine's former Z-order curve and breadth-first (per component from a far end, as
# vertex_order.cpp now numbers); with an output path, writes the mesh renumbered breadth-first.
# Importable: patch_order.py takes its reader, orders and gaps. Needs numpy (/usr/bin/python3).
# Usage: /usr/bin/python3 order_gaps.py MESH.ply [OUT.ply]
import sys
from collections import deque
import numpy as np

FACE = np.dtype([("n", "u1"), ("i", "<i4", 3)])


def read(p):
    """Vertices (n x 3 doubles) and triangles of a binary PLY as the bench tools write it."""
    b = open(p, "rb").read()
    h = b.index(b"end_header\n") + 11
    header = b[:h].decode().split("\n")
    count = {l.split()[1]: int(l.split()[2]) for l in header if l.startswith("element")}
    v = np.frombuffer(b, dtype="<f8", count=count["vertex"] * 3, offset=h).reshape(-1, 3)
    f = np.frombuffer(b, dtype=FACE, count=count["face"], offset=h + v.nbytes)["i"]
    return v.copy(), f.copy()


def write(p, v, f):
    with open(p, "wb") as o:
        o.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\n"
                 "property double y\nproperty double z\nelement face %d\n"
                 "property list uchar int vertex_indices\nend_header\n" % (len(v), len(f))).encode())
        o.write(v.astype("<f8").tobytes())
        a = np.zeros(len(f), dtype=FACE)
        a["n"], a["i"] = 3, f
        o.write(a.tobytes())


def spread(x):
    """The 21 low bits of x spread to every third bit (the former vertex_order.cpp)."""
    x = x.astype(np.uint64) & np.uint64(0x1fffff)
    for s, m in [(32, 0x1f00000000ffff), (16, 0x1f0000ff0000ff), (8, 0x100f00f00f00f00f),
                 (4, 0x10c30c30c30c30c3), (2, 0x1249249249249249)]:
        x = (x | (x << np.uint64(s))) & np.uint64(m)
    return x


def morton(v):
    lo = v.min(0)
    u = ((v - lo) / (v.max(0) - lo) * ((1 << 21) - 1)).astype(np.uint64)
    key = spread(u[:, 0]) | (spread(u[:, 1]) << np.uint64(1)) | (spread(u[:, 2]) << np.uint64(2))
    return np.argsort(key, kind="stable")


def adjacency(n, f):
    """CSR lists of each vertex's face neighbours: (start, column) as Python lists."""
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]],
                        f[:, [1, 0]], f[:, [2, 1]], f[:, [0, 2]]])
    e = e[np.argsort(e[:, 0], kind="stable")]
    return np.searchsorted(e[:, 0], np.arange(n + 1)).tolist(), e[:, 1].tolist()


def breadth_first(n, start, column):
    """Per component, in the order of its first vertex, breadth-first from the vertex a search
    from that first one reaches last (vertex_order.cpp)."""
    seen, order = [0] * n, []

    def search(s0, mark, out):
        q = deque([s0])
        seen[s0] = mark
        last = s0
        while q:
            last = q.popleft()
            out.append(last)
            for k in range(start[last], start[last + 1]):
                w = column[k]
                if seen[w] != mark:
                    seen[w] = mark
                    q.append(w)
        return last

    for i in range(n):
        if not seen[i]:
            search(search(i, 1, []), 2, order)
    return order


def edge_gaps(order, f):
    rank = np.empty(len(order), int)
    rank[np.asarray(order)] = np.arange(len(order))
    a = rank[f]
    return a, np.concatenate([np.abs(a[:, 0] - a[:, 1]), np.abs(a[:, 1] - a[:, 2]),
                              np.abs(a[:, 2] - a[:, 0])])


def print_gaps(name, order, f):
    g = edge_gaps(order, f)[1]
    print(name, "gap pct50/90/99/99.9", np.percentile(g, [50, 90, 99, 99.9]).astype(int),
          "max %d >4096 %.4f >16384 %.4f" % (g.max(), (g > 4096).mean(), (g > 16384).mean()))


if __name__ == "__main__":
    v, f = read(sys.argv[1])
    n = len(v)
    print_gaps("input", np.arange(n), f)
    print_gaps("morton", morton(v), f)
    bfs = np.array(breadth_first(n, *adjacency(n, f)))
    print_gaps("bfs", bfs, f)
    if len(sys.argv) > 2:
        rank = np.empty(n, int)
        rank[bfs] = np.arange(n)
        write(sys.argv[2], v[bfs], rank[f])
