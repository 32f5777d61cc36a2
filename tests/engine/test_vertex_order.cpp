// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// vertex_order.h: large meshes in a scattered vertex order are solved on a breadth-first numbering
// and mapped back. The user sees the same result as with a well-ordered input (to the solver's
// tolerance), fixed vertices bit-identical, the volume kept; only the memory traffic changes.
#include "meshes.h"
#include "vertex_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

using fairing::Operator;
using fairing::TriangleMesh;
using meshes::Positions;

namespace {

// A torus grid of 36,864 vertices (above kReorderVertices) with radial noise, listed in grid
// order (neighbours close in index) or scattered by a random permutation.
TriangleMesh noisy_torus() {
    TriangleMesh m = meshes::torus_grid(256, 144, 3.0, 1.0);
    meshes::Rng rng(31);
    for (int i = 0; i < m.positions.rows(); ++i) m.positions.row(i) *= 1.0 + 0.002 * rng.symmetric();
    return m;
}

std::vector<int> random_permutation(int n, std::uint64_t seed) {
    std::vector<int> p(n);
    std::iota(p.begin(), p.end(), 0);
    meshes::Rng rng(seed);
    for (int i = n - 1; i > 0; --i) std::swap(p[i], p[rng.next() % static_cast<std::uint64_t>(i + 1)]);
    return p;
}

// scattered.positions.row(i) = m.positions.row(p[i]).
TriangleMesh scatter(const TriangleMesh& m, const std::vector<int>& p) {
    std::vector<int> inverse(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) inverse[p[i]] = static_cast<int>(i);
    TriangleMesh s;
    s.positions.resize(m.positions.rows(), 3);
    for (std::size_t i = 0; i < p.size(); ++i) s.positions.row(i) = m.positions.row(p[i]);
    for (const auto& t : m.triangles) s.triangles.push_back({inverse[t[0]], inverse[t[1]], inverse[t[2]]});
    return s;
}

}  // namespace

TEST(VertexOrder, OnlyScatteredLargeMeshesAreRenumbered) {
    const TriangleMesh grid = noisy_torus();
    ASSERT_GE(grid.positions.rows(), fairing::detail::kReorderVertices);
    EXPECT_TRUE(fairing::detail::locality_order(grid).empty());  // neighbours already close
    const TriangleMesh scattered = scatter(grid, random_permutation(grid.positions.rows(), 4));
    const std::vector<int> order = fairing::detail::locality_order(scattered);
    ASSERT_EQ(order.size(), static_cast<std::size_t>(grid.positions.rows()));
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < static_cast<int>(sorted.size()); ++i) ASSERT_EQ(sorted[i], i);

    // The renumbering brings neighbours close again, and lists the same faces by smallest vertex.
    const TriangleMesh local = fairing::detail::renumbered(scattered, order);
    std::vector<int> gaps;
    int previous_min = -1;
    for (const auto& t : local.triangles) {
        for (int k = 0; k < 3; ++k) gaps.push_back(std::abs(t[k] - t[(k + 1) % 3]));
        const int smallest = std::min({t[0], t[1], t[2]});
        EXPECT_GE(smallest, previous_min);
        previous_min = smallest;
    }
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    EXPECT_LE(gaps[gaps.size() / 2], fairing::detail::kReorderMedianGap);
    EXPECT_EQ(local.triangles.size(), scattered.triangles.size());
    EXPECT_TRUE(fairing::detail::locality_order(local).empty());
    for (int i = 0; i < local.positions.rows(); ++i)
        ASSERT_EQ(local.positions.row(i), scattered.positions.row(order[i]));
}

// Breadth-first from a far end, every edge's two ends fall within about two fronts of the
// search. The Z-order curve numbered before kept most gaps small but left 5 % of this grid's
// edges more than 768 rows apart, the largest 23,755
// (bench/results/issue11/session50-probe/torus_gaps.py).
TEST(VertexOrder, NoEdgeSpansMoreThanTwoFronts) {
    const TriangleMesh grid = noisy_torus();
    const int n = static_cast<int>(grid.positions.rows());
    const TriangleMesh scattered = scatter(grid, random_permutation(n, 4));
    const TriangleMesh local =
        fairing::detail::renumbered(scattered, fairing::detail::locality_order(scattered));
    int largest = 0;
    for (const auto& t : local.triangles)
        for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(t[k] - t[(k + 1) % 3]));
    EXPECT_LE(largest, 768);  // 4 sqrt(n); 433 when measured
}

TEST(VertexOrder, ScatteredInputGivesTheSameResult) {
    const TriangleMesh grid = noisy_torus();
    const int n = static_cast<int>(grid.positions.rows());
    const std::vector<int> p = random_permutation(n, 9);
    const TriangleMesh scattered = scatter(grid, p);
    const double h = meshes::mean_edge_length(grid.positions, grid.triangles);
    fairing::Constraints fixed_grid, fixed_scattered;
    fixed_grid.fixed.assign(n, 0);
    for (int i = 0; i < n; i += 97) fixed_grid.fixed[i] = 1;
    fixed_scattered.fixed.resize(n);
    for (int i = 0; i < n; ++i) fixed_scattered.fixed[i] = fixed_grid.fixed[p[i]];
    for (Operator op : meshes::kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        fairing::Options o;
        o.op = op;
        o.time_step = 1.0;  // explicit: the automatic one's random probes follow the numbering
        o.tolerance = 1e-11;
        const fairing::Result a = fairing::fair(grid, fixed_grid, o);
        const fairing::Result b = fairing::fair(scattered, fixed_scattered, o);
        double worst = 0;
        for (int i = 0; i < n; ++i) {
            worst = std::max(worst, (b.positions.row(i) - a.positions.row(p[i])).norm());
            if (fixed_scattered.fixed[i]) {
                ASSERT_EQ(b.positions.row(i), scattered.positions.row(i));
            }
        }
        EXPECT_LT(worst, 1e-7 * h);
        EXPECT_GT(b.vertices_moved, n / 2);
        EXPECT_NEAR(b.volume_after, b.volume_before, 1e-12 * b.volume_before);
    }
}
