#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""What fair() holds at its heap peak, by data structure, in bytes per vertex.

    heaptrack -o run fairing-bench-tool fair MESH out.ply OP 2 TS 1 threads=1
    heaptrack_print -f run.zst -p 0 -a 0 -T 0 --flamegraph-cost-type peak -F run.peak
    bench/tools/heap_account.py run.peak VERTICES

Allocations outside fair() (the bench tool's own mesh) are left out. The groups follow the
allocating function, so a build with symbols (RelWithDebInfo) gives the clearest account.
"""
import sys

RULES = [  # first match wins: (text in the stack, group)
    ("renumbered", "renumbered copy of the mesh (vertex_order.cpp renumbered)"),
    ("locality_order", "vertex order (vertex_order.cpp)"),
    ("keep_faces", "half-edge view: faces, input-face map (half_edge.cpp keep_faces)"),
    ("pair_half_edges", "half-edge view: twins (half_edge.cpp pair_half_edges)"),
    ("VertexPass::list_components", "half-edge view: component vertex and face lists"),
    ("vertices_and_components", "half-edge view: outgoing, component of vertex"),
    ("Build::boundary_loops", "half-edge view: boundary flags"),
    ("Multigrid::", "multigrid hierarchy (multigrid.cpp)"),
    ("ComplexFactorSolver", "complex solve: r, p, q, and u or the Jacobi inverse (complex_factor.cpp)"),
    ("Sketch", "strength: sketch and restoration fields (auto_strength.cpp)"),
    ("restoration", "strength: sketch and restoration fields (auto_strength.cpp)"),
    ("robust_normals", "strength: normals (auto_strength.cpp robust_normals)"),
    ("estimate_strength", "strength: Lanczos vectors and contexts (auto_strength.cpp)"),
    ("assemble", "operator K, M in CSR (operators.cpp assemble)"),
    ("centre", "working positions (fairing.cpp Run::centre)"),
    ("system_for", "linear system: D, free mask (fairing.cpp Run::system_for)"),
    ("solve(", "right-hand side b (solver.cpp solve)"),
    ("fairing::fair(", "run: weights, masks, targets (fairing.cpp)"),
]


def group(stack):
    if "perturb" in stack:  # the strength estimate's Monte-Carlo problem
        if "assemble" in stack:
            return "strength: perturbed operator (auto_strength.cpp perturb)"
        return "strength: perturbed process: vectors, context, probe (auto_strength.cpp perturb)"
    return next((label for text, label in RULES if text in stack), "other")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    vertices = int(sys.argv[2])
    total = {}
    for line in open(sys.argv[1]):
        stack, _, value = line.rstrip().rpartition(" ")
        if "fairing::fair(" not in stack:
            continue
        label = group(stack)
        total[label] = total.get(label, 0) + int(value)
    print("| held at the heap peak | bytes / vertex |\n|---|---:|")
    for label, value in sorted(total.items(), key=lambda kv: -kv[1]):
        if value / vertices >= 0.5:
            print("| %s | %.0f |" % (label, value / vertices))
    print("| **total** | **%.0f** |" % (sum(total.values()) / vertices))


if __name__ == "__main__":
    main()
