// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The paper's discrete Laplacians in the symmetric form L = M^-1 K.
//
// Conventions:
// - K is stored by its off-diagonal part only, in compressed rows: (K x)_i = sum_j w_ij (x_j - x_i),
//   so K_ij = w_ij (i != j), K_ii = -sum_j w_ij, rows sum to zero and K is symmetric (w_ij = w_ji).
// - mass[i] = M_ii > 0 for every vertex that takes part; 0 for vertices that do not (isolated,
//   or whose whole star is degenerate); their row of K is empty.
// - Units: umbrella K, M dimensionless; scale-dependent K in 1/length, M in length; curvature
//   K dimensionless, M in length^2. So L is dimensionless for the umbrella and 1/length^2 else.
#pragma once

#include "fairing/fairing.h"
#include "fairing/half_edge.h"

#include <vector>

namespace fairing {

struct SparseOperator {
    std::vector<int> row_start;  // size n+1
    std::vector<int> column;
    std::vector<double> weight;  // w_ij
    std::vector<double> mass;    // M_ii
    int threads = 1;             // threads for products with K (see Options::threads)
    // Every w_ij is 1 (the umbrella, eq. 7): products with K need not read `weight` (the same
    // bits, since 1 * d = d). Set by assemble(); whoever changes the weights clears it.
    bool unit_weights = false;

    int size() const { return static_cast<int>(mass.size()); }
    double diagonal(int i) const;  // K_ii = -sum_j w_ij
    // y = K x (three columns at once).
    void apply_k(const Positions& x, Positions& y) const;
    // y = L x = M^-1 K x, 0 on rows with no mass.
    void apply_l(const Positions& x, Positions& y) const;
};

struct AssemblyReport {
    int zero_area_faces = 0;   // skipped by the curvature operator
    int floored_edges = 0;     // scale-dependent: edges shorter than kDuplicateEdge of the mean
                               // (duplicated vertices?), lengthened as every short edge is
    int massless_vertices = 0; // vertices with faces but no mass: their star is degenerate
    int negligible_vertices = 0;  // curvature: area below kNegligibleArea of the mean, kept in
                                  // place as massless ones are (a part shrunk to a point)
    int needle_faces = 0;      // curvature: faces with an angle below ~0.01 rad
                               // (|cot| > kNeedleCotangent), capped as every sliver is
};

// The curvature operator (eq. 14) clamps every cotangent to +-kCotangentCap, an angle of 3
// degrees (pmp-library's bound), keeping each face's form semi-definite: slivers of raw scans and
// of noise in all directions otherwise stall the solves (operators.cpp). Faces with an angle
// below 0.01 rad are counted as needles (AssemblyReport::needle_faces) and warned about.
constexpr double kCotangentCap = 19.1;
constexpr double kNeedleCotangent = 100;

// The scale-dependent operator (eq. 11) takes 1/|e| of every edge at least kShortEdge times the
// mean edge long: edges that strong steps collapse (thin parts shrinking to curves) otherwise
// leave systems no solve can bring to its tolerance (operators.cpp). Edges shorter than
// kDuplicateEdge times the mean are counted (AssemblyReport::floored_edges) and warned about.
constexpr double kShortEdge = 0.01;
constexpr double kDuplicateEdge = 1e-4;

// The curvature operator (not normalized) counts a vertex whose area (its mass, eq. 14) is below
// kNegligibleArea times the mean vertex area as massless. Steps without volume preservation
// shrink a small closed part towards a point while its faces keep their shape, so none of them
// has zero area, but their area falls without bound: on libcgal-demo's b9 (four L^2 steps at
// time step 1, no volume restored) four small parts reached 2e-17 of the mean area after two
// steps (the third then took 1,206 CG iterations; the first two, 74) and 4e-67 after three, where
// the fourth step's L^2 system, K M^-1 K, overflowed. A length ratio of 1e-6 is far below any
// mesh's own grading.
constexpr double kNegligibleArea = 1e-12;

// Assembles op on the mesh at the given positions (curvature: eq. 14, faces of zero area skipped;
// scale-dependent: eq. 11; umbrella: eq. 7). With normalized = true, mass[i] = sum_j w_ij
// (section 5.5; for the umbrella this is the valence, i.e. no change).
// threads as in Options::threads (0 = all cores), one below detail::kParallelRows vertices; the
// result does not depend on it.
SparseOperator assemble(Operator op, const HalfEdgeMesh& mesh, const Positions& positions,
                        bool normalized = false, AssemblyReport* report = nullptr,
                        int threads = 1);

// Eq. 11 restricted to the two boundary neighbours of every boundary vertex (section 5.3):
// rows of interior vertices are empty and massless.
SparseOperator assemble_boundary_curve(const HalfEdgeMesh& mesh, const Positions& positions,
                                       int threads = 1);

// Mean length of the mesh's undirected edges, summed in fixed chunks of edges (so the same on any
// number of threads).
double mean_edge_length(const HalfEdgeMesh& mesh, const Positions& positions, int threads = 1);

}  // namespace fairing
