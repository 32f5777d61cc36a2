// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// A cache-friendly numbering of the vertices (not installed).
//
// The solver's products gather the neighbours' rows of 3-column vectors; when the input lists
// vertices in an order unrelated to the surface (scanners, subdivision and many file writers
// do), each gather misses the cache and a CG iteration costs several times more. Numbering the
// vertices breadth-first from a far end of each connected component (Cuthill-McKee's order,
// without its sort by degree) puts every edge's two ends within about two fronts of the search:
// on the 1.2 M-face Loop bunny no edge is more than 2,289 rows apart. A Z-order (Morton) curve of
// the positions, the numbering before, kept the median gap at 5 but left 1 % of the edges more
// than 16,384 rows apart, each a miss past the caches: the automatic strength's Lanczos steps
// took 59 ms against 44 ms breadth-first, the one click's four curvature steps 15.8 s against
// 10.5 s (one thread). The fronts grow with the square root of the size: on the 2.4 M-vertex
// bunny (Loop x3) an edge spans a median 2,363 rows, more of them cross the sweep blocks
// (sweeps.h), and its curvature steps take 297 iterations instead of 239, in 0.90x the time
// (bench/results/issue11/auto-gap.md section 50).
//
// Conventions: order[new] = old; an empty order means "keep the input's". Faces are then listed
// by their smallest new vertex (stable), so that assembly also walks memory forwards.
#pragma once

#include "fairing/fairing.h"

#include <vector>

namespace fairing {
namespace detail {

// Meshes below this many vertices fit in the cache whatever their order.
constexpr int kReorderVertices = 32768;
// The input is kept when the median index distance between the two ends of an edge (sampled)
// is at most this: neighbours are then already close in memory.
constexpr int kReorderMedianGap = 4096;

// Empty when the input's order is good enough, too small to matter, or unusable (indices out of
// range, non-finite coordinates: HalfEdgeMesh::build reports those).
std::vector<int> locality_order(const TriangleMesh& mesh);

// The mesh and constraints renumbered by `order` (faces sorted by their smallest new vertex).
TriangleMesh renumbered(const TriangleMesh& mesh, const std::vector<int>& order);
Constraints renumbered(const Constraints& constraints, const std::vector<int>& order);

}  // namespace detail
}  // namespace fairing
