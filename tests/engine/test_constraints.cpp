// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Section 2.7: hard constraints (fixed vertices, bit-identical) and soft constraints (weights in
// [0, 1] scaling lambda at each vertex; D = M / w in the symmetric system).
#include "meshes.h"

#include "fairing/half_edge.h"
#include "fairing/operators.h"

#include <gtest/gtest.h>

using fairing::Constraints;
using fairing::Operator;
using fairing::Options;
using fairing::Restoration;
using fairing::TriangleMesh;
using meshes::Positions;

namespace {

using meshes::kOperators;

TriangleMesh noisy_sphere() { return meshes::radial_noise(meshes::icosphere(3), 0.05, 77); }

Options options(Operator op, int order, bool preserve_volume, double time_step = 3.0) {
    Options o;
    o.op = op;
    o.order = order;
    o.time_step = time_step;
    o.steps = 2;
    o.preserve_volume = preserve_volume;
    o.tolerance = 1e-13;
    o.max_iterations = 20000;
    return o;
}

std::vector<char> every_kth(int n, int k) {
    std::vector<char> f(n, 0);
    for (int i = 0; i < n; i += k) f[i] = 1;
    return f;
}

int rows_changed(const Positions& a, const Positions& b) {
    int c = 0;
    for (int i = 0; i < a.rows(); ++i) c += a.row(i) == b.row(i) ? 0 : 1;
    return c;
}

}  // namespace

TEST(Constraints, FixedVerticesAreBitIdentical) {
    const TriangleMesh m = noisy_sphere();
    const int n = static_cast<int>(m.positions.rows());
    Constraints c;
    c.fixed = every_kth(n, 7);
    int nfixed = 0;
    for (char f : c.fixed) nfixed += f ? 1 : 0;
    const double v0 = meshes::volume(m.positions, m.triangles);
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4})
            for (bool volume : {false, true}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                << " preserve_volume " << volume);
                const fairing::Result r = fairing::fair(m, c, options(op, order, volume));
                for (int i = 0; i < n; ++i)
                    if (c.fixed[i]) {
                        ASSERT_TRUE(r.positions.row(i) == m.positions.row(i)) << i;
                    }
                EXPECT_EQ(r.vertices_fixed, nfixed);
                EXPECT_EQ(r.vertices_moved, rows_changed(r.positions, m.positions));
                EXPECT_EQ(r.vertices_moved, n - nfixed);
                ASSERT_EQ(r.components.size(), 1u);
                EXPECT_TRUE(r.components[0].has_fixed);
                if (volume) {
                    EXPECT_EQ(r.components[0].restoration, Restoration::NormalOffset);
                    EXPECT_NEAR(meshes::volume(r.positions, m.triangles), v0, 1e-12 * v0);
                    EXPECT_NEAR(r.components[0].measure_after, v0, 1e-12 * v0);
                } else {
                    EXPECT_EQ(r.components[0].restoration, Restoration::None);
                }
            }
}

TEST(Constraints, FixedWithExplicitIntegration) {
    const TriangleMesh m = noisy_sphere();
    const int n = static_cast<int>(m.positions.rows());
    Constraints c;
    c.fixed = every_kth(n, 5);
    for (Operator op : kOperators) {
        Options o = options(op, 1, true, 0.05);
        o.integration = fairing::Integration::Explicit;
        const fairing::Result r = fairing::fair(m, c, o);
        for (int i = 0; i < n; ++i)
            if (c.fixed[i]) {
                ASSERT_TRUE(r.positions.row(i) == m.positions.row(i)) << i;
            }
        EXPECT_GT(meshes::max_row_distance(r.positions, m.positions), 1e-4);
    }
}

TEST(Constraints, WeightZeroIsFixed) {
    const TriangleMesh m = noisy_sphere();
    const int n = static_cast<int>(m.positions.rows());
    Constraints hard, soft;
    hard.fixed = every_kth(n, 6);
    soft.weights.assign(n, 1.0);
    for (int i = 0; i < n; ++i)
        if (hard.fixed[i]) soft.weights[i] = 0.0;
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4})
            for (bool volume : {false, true}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                << " preserve_volume " << volume);
                const fairing::Result a = fairing::fair(m, hard, options(op, order, volume));
                const fairing::Result b = fairing::fair(m, soft, options(op, order, volume));
                for (int i = 0; i < n; ++i)
                    if (hard.fixed[i]) {
                        ASSERT_TRUE(b.positions.row(i) == m.positions.row(i)) << i;
                    }
                EXPECT_LT(meshes::max_row_distance(a.positions, b.positions), 1e-12);
                EXPECT_EQ(a.vertices_fixed, b.vertices_fixed);
                EXPECT_EQ(a.components[0].restoration, b.components[0].restoration);
            }
}

TEST(Constraints, AllOnesWeightsChangeNothing) {
    const TriangleMesh m = noisy_sphere();
    Constraints ones;
    ones.weights.assign(m.positions.rows(), 1.0);
    for (Operator op : kOperators) {
        const fairing::Result a = fairing::fair(m, {}, options(op, 2, true));
        const fairing::Result b = fairing::fair(m, ones, options(op, 2, true));
        EXPECT_LT(meshes::max_row_distance(a.positions, b.positions), 1e-12);
    }
}

// A uniform weight w scales lambda: (M/w - ldt K) X' = (M/w) X is (M - w ldt K) X' = M X (and
// likewise for order 2), so weight 0.25 with time step t equals weight 1 with time step t/4,
// and it moves the vertices less than weight 1 with time step t.
TEST(Constraints, SmallerWeightsMoveLess) {
    const TriangleMesh m = noisy_sphere();
    Constraints quarter;
    quarter.weights.assign(m.positions.rows(), 0.25);
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4})
            for (bool volume : {false, true}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                << " preserve_volume " << volume);
                const double t = 3.0;
                const fairing::Result full = fairing::fair(m, {}, options(op, order, volume, t));
                const fairing::Result soft = fairing::fair(m, quarter, options(op, order, volume, t));
                const fairing::Result shorter =
                    fairing::fair(m, {}, options(op, order, volume, t / 4));
                EXPECT_LT(meshes::max_row_distance(soft.positions, shorter.positions), 1e-9);
                const double d_full = (full.positions - m.positions).norm();
                const double d_soft = (soft.positions - m.positions).norm();
                // Strictly less, not proportionally: at this time step the noise is mostly gone
                // with either weight, so the displacement saturates.
                EXPECT_LT(d_soft, d_full);
                EXPECT_GT(d_soft, 0.0);
            }
}

// Varying weights: one step equals the dense solve of (M/w - ldt K) X' = (M/w) X, or
// (M/w + ldt K M^-1 K) X' = (M/w) X, with K and M assembled at the input.
TEST(Constraints, VaryingWeightsSolveTheWeightedSystem) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(2), 0.05, 78);
    const int n = static_cast<int>(m.positions.rows());
    meshes::Rng rng(3);
    Constraints c;
    for (int i = 0; i < n; ++i) c.weights.push_back(0.05 + 0.95 * rng.uniform());
    const fairing::HalfEdgeMesh he = fairing::HalfEdgeMesh::build(m.positions, m.triangles);
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = options(op, order, false);
            o.steps = 1;
            const fairing::Result r = fairing::fair(m, c, o);
            const fairing::SparseOperator k = fairing::assemble(op, he, m.positions);
            const Positions ref =
                meshes::dense_implicit_step(k, m.positions, r.lambda_dt, order, c.weights);
            EXPECT_LT(meshes::max_row_distance(r.positions, ref), 1e-9);
        }
}

// Order 1 with hard constraints: the dense reduced solve (fixed values moved to the right).
TEST(Constraints, FixedRowsSolveTheReducedSystem) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(2), 0.05, 79);
    const int n = static_cast<int>(m.positions.rows());
    Constraints c;
    c.fixed = every_kth(n, 4);
    std::vector<char> free(n);
    for (int i = 0; i < n; ++i) free[i] = c.fixed[i] ? 0 : 1;
    const fairing::HalfEdgeMesh he = fairing::HalfEdgeMesh::build(m.positions, m.triangles);
    for (Operator op : kOperators) {
        Options o = options(op, 1, false);
        o.steps = 1;
        const fairing::Result r = fairing::fair(m, c, o);
        const fairing::SparseOperator k = fairing::assemble(op, he, m.positions);
        const Positions ref = meshes::dense_implicit_step(k, m.positions, r.lambda_dt, 1, {}, free);
        EXPECT_LT(meshes::max_row_distance(r.positions, ref), 1e-9) << fairing::to_string(op);
    }
}

TEST(Constraints, EverythingFixedIsUnchanged) {
    const TriangleMesh m = noisy_sphere();
    Constraints c;
    c.fixed.assign(m.positions.rows(), 1);
    const fairing::Result r = fairing::fair(m, c, options(Operator::CurvatureFlow, 2, true));
    EXPECT_TRUE(r.positions == m.positions);
    EXPECT_EQ(r.vertices_moved, 0);
    ASSERT_EQ(r.components.size(), 1u);
    EXPECT_EQ(r.components[0].restoration, Restoration::Unchanged);
}
