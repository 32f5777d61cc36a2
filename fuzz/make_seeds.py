#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Writes the seed corpus of fuzz_mesh_bytes (format: fuzz_mesh_bytes.cpp) into DIR:
an octahedron, a 4x4 grid, a tetrahedron in raw floats with a NaN and an Inf, a bow-tie, a
duplicated face, a selection of one vertex. Tiny files, generated rather than committed."""
import os
import struct
import sys


def mesh(b0, b1, b2, b3, verts, faces, raw=False, vflags=None, fflags=None):
    out = bytearray([b0, b1 | (0x80 if raw else 0), b2, b3])
    out += struct.pack("<HH", len(verts), len(faces))
    for i, v in enumerate(verts):
        if raw:
            out += struct.pack("<3f", *v)
        else:
            out += struct.pack("<3b", *[max(-128, min(127, int(round(c * 8)))) for c in v])
        out.append(vflags[i] if vflags else 0x40)   # quality 0.5
    for i, f in enumerate(faces):
        out += struct.pack("<3H", *f)
        out.append(fflags[i] if fflags else 0)
    return bytes(out)


def main(d):
    os.makedirs(d, exist_ok=True)
    octa_v = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    octa_f = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    n = 4
    grid_v = [(i, j, ((i * 7 + j * 3) % 5) / 8.0) for j in range(n + 1) for i in range(n + 1)]
    grid_f = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            grid_f += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    tet_v = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, float("nan"))]
    tet_f = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]
    seeds = {
        "octahedron_curvature_l2": mesh(0x06, 0x00, 0x05, 40, octa_v, octa_f),
        "octahedron_curvature_l3": mesh(0x02, 0x00, 0x85, 40, octa_v, octa_f),
        "grid_umbrella_l4_selected": mesh(0x04, 0x10, 0x83, 30, grid_v, grid_f),
        "octahedron_umbrella_explicit": mesh(0x18, 0x00, 0x02, 10, octa_v, octa_f),
        "grid_smooth_boundary_area": mesh(0x01, 0x05, 0x03, 30, grid_v, grid_f),
        "grid_virtual_vertex": mesh(0x02, 0x02, 0x04, 30, grid_v, grid_f),
        "tetra_raw_nan": mesh(0x00, 0x00, 0x03, 20, tet_v, tet_f, raw=True),
        "tetra_raw_inf": mesh(0x02, 0x00, 0x07, 20,
                              [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, float("inf"))], tet_f,
                              raw=True),
        "bowtie": mesh(0x01, 0x02, 0x03, 20, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (-1, 0, 0),
                                              (0, -1, 0)], [(0, 1, 2), (0, 3, 4)]),
        "octahedron_dup_face": mesh(0x00, 0x00, 0x03, 20, octa_v, octa_f + [octa_f[0]]),
        "octahedron_one_selected_quality": mesh(
            0x02, 0x30, 0x03, 20, octa_v, octa_f, vflags=[0x41, 0x40, 0x20, 0x7E, 0xFE, 0x00]),
        "octahedron_deleted": mesh(0x00, 0x00, 0x03, 20, octa_v, octa_f,
                                   vflags=[0x40, 0x40, 0x40, 0x40, 0x40, 0xFF],
                                   fflags=[0, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF]),
    }
    for name, data in seeds.items():
        with open(os.path.join(d, name), "wb") as f:
            f.write(data)
    print("%d seeds in %s" % (len(seeds), d))


if __name__ == "__main__":
    main(sys.argv[1])
