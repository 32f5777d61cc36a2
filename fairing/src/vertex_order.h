// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// A cache-friendly numbering of the vertices (not installed).
//
// The solver's products gather the neighbours' rows of 3-column vectors; when the input lists
// vertices in an order unrelated to the surface (scanners, subdivision and many file writers
// do), each gather misses the cache and a CG iteration costs several times more. Numbering the
// vertices along a Z-order (Morton) curve of their positions puts neighbours close together.
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
