// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Section 5.3: the three boundary modes.
#include "meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using fairing::BoundaryMode;
using fairing::Operator;
using fairing::Options;
using fairing::Triangle;
using fairing::TriangleMesh;
using meshes::Positions;

namespace {

using meshes::kOperators;

// [-1,1]^2 grid whose boundary vertices carry in-plane noise (35% of a cell) and every vertex a
// z-noise (30% of a cell).
TriangleMesh noisy_sheet() { return meshes::noisy_open_grid(12, 0.35, 0.3, 19); }

// The same sheet with the central 4x4 cells removed: two boundary loops.
TriangleMesh noisy_annulus() {
    const int n = 12;
    TriangleMesh m = noisy_sheet();
    std::vector<Triangle> kept;
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const int cell = static_cast<int>(f) / 2, i = cell % n, j = cell / n;
        if (i >= 4 && i < 8 && j >= 4 && j < 8) continue;
        kept.push_back(m.triangles[f]);
    }
    m.triangles = kept;
    return m;
}

Options options(Operator op, int order, BoundaryMode mode, int steps = 2) {
    Options o;
    o.op = op;
    o.order = order;
    o.boundary = mode;
    o.steps = steps;
    o.time_step = 2.0;
    o.preserve_volume = false;
    o.tolerance = 1e-12;
    o.max_iterations = 20000;
    return o;
}

}  // namespace

TEST(Boundary, FixedKeepsLoopsBitIdentical) {
    for (const TriangleMesh& m : {noisy_sheet(), noisy_annulus()}) {
        const auto loops = meshes::boundary_loops(m.triangles);
        int on_loops = 0;
        for (const auto& l : loops) on_loops += static_cast<int>(l.size());
        // The annulus leaves the vertices inside its hole unreferenced (isolated, not moved).
        std::vector<char> used(m.positions.rows(), 0);
        for (const Triangle& t : m.triangles)
            for (int v : t) used[v] = 1;
        const int referenced = static_cast<int>(std::count(used.begin(), used.end(), 1));
        for (Operator op : kOperators)
            for (int order : {1, 2, 3, 4}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
                const fairing::Result r = fairing::fair(m, {}, options(op, order, BoundaryMode::Fixed));
                EXPECT_EQ(r.boundary_loops, static_cast<int>(loops.size()));
                for (const auto& loop : loops)
                    for (int v : loop) ASSERT_TRUE(r.positions.row(v) == m.positions.row(v)) << v;
                EXPECT_EQ(r.vertices_fixed, on_loops);
                EXPECT_EQ(r.vertices_moved, referenced - on_loops);
            }
    }
}

// The annulus's inner loop is small (16 short edges): curve diffusion shrinks a closed loop, and
// with a fixed absolute lambda_dt the shrinking accelerates as its edges get shorter (order 2
// collapses it to a point within two steps at time_step 2), so it gets a gentler time step.
TEST(Boundary, SmoothCurveShortensNoisyLoops) {
    const struct {
        TriangleMesh mesh;
        double time_step;
    } cases[] = {{noisy_sheet(), 2.0}, {noisy_annulus(), 0.2}};
    for (const auto& c : cases) {
        const TriangleMesh& m = c.mesh;
        const auto loops = meshes::boundary_loops(m.triangles);
        for (Operator op : kOperators)
            for (int order : {1, 2, 3, 4}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                << " loops " << loops.size());
                Options o = options(op, order, BoundaryMode::SmoothCurve, 3);
                o.time_step = c.time_step;
                const fairing::Result r = fairing::fair(m, {}, o);
                ASSERT_TRUE(r.positions.allFinite());
                EXPECT_EQ(r.boundary_loops, static_cast<int>(loops.size()));
                for (const auto& loop : loops) {
                    const double before = meshes::loop_length(m.positions, loop);
                    const double after = meshes::loop_length(r.positions, loop);
                    EXPECT_LT(after, 0.98 * before);
                }
                EXPECT_EQ(r.vertices_fixed, 0);
                // One boundary-curve solve before each surface solve.
                int curve = 0, surface = 0;
                for (const auto& s : r.solves) {
                    curve += s.system == "boundary curve" ? 1 : 0;
                    surface += s.system == "surface" ? 1 : 0;
                }
                EXPECT_EQ(curve, 3);
                EXPECT_EQ(surface, 3);
            }
    }
}

// The boundary block of eq. 11 restricted to the two loop neighbours does not depend on the
// interior: the new loop is the solution of (M_b - ldt K_b) X_b' = M_b X_b with
// (K_b x)_i = sum over the two neighbours (x_j - x_i)/|e_ij|, M_b,i = (|e_prev| + |e_next|)/2.
TEST(Boundary, SmoothCurveSolvesEquation11OnTheLoop) {
    const TriangleMesh m = noisy_sheet();
    const std::vector<int> loop = meshes::boundary_loops(m.triangles).at(0);
    const int L = static_cast<int>(loop.size());
    for (Operator op : {Operator::ScaleDependent, Operator::CurvatureFlow}) {
        SCOPED_TRACE(fairing::to_string(op));
        const fairing::Result r = fairing::fair(m, {}, options(op, 1, BoundaryMode::SmoothCurve, 1));
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(L, L), b(L, 3);
        for (int k = 0; k < L; ++k) {
            const int i = loop[k];
            double mass = 0;
            for (int d : {L - 1, 1}) {
                const int kj = (k + d) % L;
                const double len =
                    (meshes::row(m.positions, i) - meshes::row(m.positions, loop[kj])).norm();
                mass += len / 2;
                A(k, kj) -= r.lambda_dt / len;
                A(k, k) += r.lambda_dt / len;
            }
            A(k, k) += mass;
            b.row(k) = mass * m.positions.row(i);
        }
        const Eigen::MatrixXd x = A.ldlt().solve(b);
        double worst = 0;
        for (int k = 0; k < L; ++k)
            worst = std::max(worst, (x.row(k) - Eigen::RowVector3d(r.positions.row(loop[k]))).norm());
        EXPECT_LT(worst, 1e-8);
    }
}

TEST(Boundary, VirtualVertexIsNeverWrittenBack) {
    for (const TriangleMesh& m : {noisy_sheet(), noisy_annulus()}) {
        const auto loops = meshes::boundary_loops(m.triangles);
        for (Operator op : kOperators)
            for (int order : {1, 2, 3, 4}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
                const fairing::Result r =
                    fairing::fair(m, {}, options(op, order, BoundaryMode::VirtualVertex));
                ASSERT_EQ(r.positions.rows(), m.positions.rows());
                EXPECT_TRUE(r.positions.allFinite());
                EXPECT_EQ(r.boundary_loops, static_cast<int>(loops.size()));
                EXPECT_EQ(r.vertices_fixed, 0);
                EXPECT_LE(r.vertices_moved, static_cast<int>(m.positions.rows()));
                for (int i = 0; i < m.positions.rows(); ++i) {
                    bool used = false;
                    for (const Triangle& t : m.triangles) used = used || t[0] == i || t[1] == i || t[2] == i;
                    if (!used) {
                        EXPECT_TRUE(r.positions.row(i) == m.positions.row(i)) << "isolated " << i;
                    }
                }
                // The boundary is free: its vertices move.
                for (const auto& loop : loops) {
                    int moved = 0;
                    for (int v : loop) moved += r.positions.row(v) == m.positions.row(v) ? 0 : 1;
                    EXPECT_EQ(moved, static_cast<int>(loop.size()));
                }
                ASSERT_EQ(r.components.size(), 1u);
                EXPECT_EQ(r.components[0].faces, static_cast<int>(m.triangles.size()));
                EXPECT_FALSE(r.components[0].closed);
            }
    }
}

TEST(Boundary, ClosedMeshHasNoLoops) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(2), 0.05, 3);
    for (BoundaryMode mode :
         {BoundaryMode::Fixed, BoundaryMode::SmoothCurve, BoundaryMode::VirtualVertex}) {
        const fairing::Result r = fairing::fair(m, {}, options(Operator::CurvatureFlow, 2, mode));
        EXPECT_EQ(r.boundary_loops, 0);
        EXPECT_EQ(r.vertices_fixed, 0);
        EXPECT_EQ(r.positions.rows(), m.positions.rows());
    }
}

// The automatic strength chooses the boundary curve's time step on its own (Result::
// boundary_time_step): a loop of eq. 11 is a 1-D filter whose best strength is far from the
// surface's. A flat open square with Gaussian noise of a quarter cell along z on every vertex:
// the surface's choice (a flat patch asks for very strong steps) given to the curve as well
// rounds the square away (RMS distance of the loop to the square's outline 7.9 cells with the
// umbrella, 3.0 with the curvature flow, 1.08 with the scale-dependent operator, whose surface
// step is the weakest), while the curve's own choice rounds it by 1.14 cells and takes 84 % of the
// loop's z-noise out. (The risk is measured along the normals, so it does not see the in-plane
// rounding of the corners: auto-gap.md, section 29.)
TEST(Boundary, AutomaticStrengthChoosesTheCurvesOwnTimeStep) {
    const int n = 24;
    const double h = 2.0 / n;
    TriangleMesh m = meshes::grid(n, n, 2.0, 2.0, nullptr, -1.0, -1.0);
    const TriangleMesh clean = m;
    meshes::Rng rng(23);
    for (int v = 0; v < m.positions.rows(); ++v) m.positions(v, 2) += 0.25 * h * rng.normal();
    const auto loops = meshes::boundary_loops(m.triangles);
    ASSERT_EQ(loops.size(), 1u);
    const std::vector<int>& loop = loops[0];
    // The loop's RMS distance to the clean square's outline (in-plane), and its RMS z, in cells.
    const auto outline_error = [&](const Positions& p) {
        double s = 0;
        for (int v : loop) {
            const double d = 1.0 - std::max(std::abs(p(v, 0)), std::abs(p(v, 1)));
            s += d * d;
        }
        return std::sqrt(s / loop.size()) / h;
    };
    const auto loop_z = [&](const Positions& p) {
        double s = 0;
        for (int v : loop) s += p(v, 2) * p(v, 2);
        return std::sqrt(s / loop.size()) / h;
    };
    ASSERT_EQ(outline_error(clean.positions), 0);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        Options o;
        o.op = op;
        o.boundary = BoundaryMode::SmoothCurve;
        const fairing::Result automatic = fairing::fair(m, {}, o);
        ASSERT_TRUE(automatic.automatic_time_step);
        EXPECT_GT(automatic.boundary_time_step, 0);
        EXPECT_NE(automatic.boundary_time_step, automatic.time_step);
        EXPECT_LT(loop_z(automatic.positions), 0.25 * loop_z(m.positions));
        EXPECT_LT(outline_error(automatic.positions), 1.5);
        // The surface's time step given explicitly serves both systems, as before.
        Options given = o;
        given.time_step = automatic.time_step;
        const fairing::Result both = fairing::fair(m, {}, given);
        EXPECT_EQ(both.boundary_time_step, automatic.time_step);
        if (op != Operator::ScaleDependent)
            EXPECT_GT(outline_error(both.positions), 2 * outline_error(automatic.positions));
    }
}
