// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The L^2 step as one complex solve (fairing/src/complex_factor.h): A^-1 g = Re (M + i s K)^-1 g
// without soft weights. Checked against a dense solve of the real L^2 system, for every
// operator, with fixed rows, in both residual norms; bit-identical on 1 and 2 threads; the
// iteration count grows as lambda_dt^(1/4) where Jacobi CG on the L^2 system grows as
// lambda_dt^(1/2); block symmetric Gauss-Seidel (Eisenstat's form) gives complex Jacobi's result
// to the tolerance in far fewer iterations, across sweep blocks and fixed rows, and is not used
// on rows that are not sorted.
#include "meshes.h"

#include "complex_factor.h"
#include "sweeps.h"
#include "vertex_order.h"
#include "fairing/half_edge.h"
#include "fairing/operators.h"
#include "fairing/solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>

using fairing::LinearSystem;
using fairing::Operator;
using fairing::Preconditioner;
using meshes::Positions;

namespace {

using Case = meshes::Assembled;

Case make(Operator op, int levels) {
    return meshes::assembled(meshes::radial_noise(meshes::icosphere(levels), 0.05, 23), op);
}

// lambda_dt of an L^2 step of dimensionless size t (section "Units" of the README).
double l2_lambda(const Case& c, Operator op, double t) {
    return op == Operator::Umbrella ? t : t * std::pow(c.h, 4);
}

LinearSystem l2_system(const Case& c, double lambda_dt, const std::vector<char>& free) {
    LinearSystem s;
    s.op = &c.op;
    s.diagonal = c.op.mass;
    s.free = free;
    s.lambda_dt = lambda_dt;
    s.order = 2;
    return s;
}

}  // namespace

TEST(ComplexFactor, EqualsDenseL2SolveForEveryOperatorAndNorm) {
    for (Operator op : meshes::kOperators)
        for (auto norm : {fairing::ResidualNorm::L2, fairing::ResidualNorm::LInfinity}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " norm "
                                            << static_cast<int>(norm));
            const Case c = make(op, 3);
            const int n = c.op.size();
            const std::vector<char> free = meshes::every_kth_fixed(n, 17);
            const double lambda_dt = l2_lambda(c, op, op == Operator::Umbrella ? 10 : 22.5);
            Positions x = c.mesh.positions;
            fairing::SolveSettings settings;
            settings.tolerance = 1e-11;
            settings.norm = norm;
            const fairing::SolveStats stats = fairing::solve(l2_system(c, lambda_dt, free), x,
                                                             settings);
            EXPECT_TRUE(stats.complex_factor);
            EXPECT_FALSE(stats.factored);
            ASSERT_TRUE(stats.converged);
            EXPECT_LT(stats.residual, settings.tolerance);
            const Positions ref = meshes::dense_implicit_step(c.op, c.mesh.positions, lambda_dt,
                                                              2, {}, free);
            EXPECT_LT(meshes::max_row_distance(x, ref), 1e-9 * meshes::bbox_diagonal(ref));
            for (int i = 0; i < n; ++i) {
                if (free[i]) continue;
                EXPECT_EQ(x.row(i), c.mesh.positions.row(i)) << "fixed row " << i;
            }
        }
}

TEST(ComplexFactor, NotUsedWithSoftWeightsOrWhenAPreconditionerIsForced) {
    const Case c = make(Operator::CurvatureFlow, 2);
    const int n = c.op.size();
    LinearSystem s = l2_system(c, l2_lambda(c, Operator::CurvatureFlow, 22.5),
                               std::vector<char>(n, 1));
    Positions x = c.mesh.positions;
    fairing::SolveSettings settings;
    settings.preconditioner = Preconditioner::Factored;
    EXPECT_FALSE(fairing::solve(s, x, settings).complex_factor);
    s.diagonal[5] /= 0.5;  // a soft constraint: D != M, the factorization does not hold
    x = c.mesh.positions;
    settings.preconditioner = Preconditioner::Automatic;
    const fairing::SolveStats stats = fairing::solve(s, x, settings);
    EXPECT_FALSE(stats.complex_factor);
    EXPECT_TRUE(stats.converged);
}

TEST(ComplexFactor, BitIdenticalOnOneAndTwoThreads) {
    // 40,962 vertices: ten blocks of the fixed-order sums, so two threads split the work.
    for (int order : {1, 2}) {
        SCOPED_TRACE(testing::Message() << "order " << order);
        Case c = make(Operator::CurvatureFlow, 6);
        const int n = c.op.size();
        LinearSystem s = l2_system(c, l2_lambda(c, Operator::CurvatureFlow, 22.5),
                                   meshes::every_kth_fixed(n, 101));
        s.order = order;
        Positions one = c.mesh.positions, two = c.mesh.positions;
        c.op.threads = 1;
        const fairing::SolveStats a = fairing::solve(s, one, fairing::SolveSettings{});
        c.op.threads = 2;
        const fairing::SolveStats b = fairing::solve(s, two, fairing::SolveSettings{});
        EXPECT_TRUE(a.converged);
        EXPECT_EQ(a.iterations, b.iterations);
        EXPECT_EQ(a.residual, b.residual);
        EXPECT_EQ(0, std::memcmp(one.data(), two.data(), sizeof(double) * 3 * n));
    }
}

TEST(ComplexFactor, IterationsGrowAsTheFourthRootOfTheTimeStep) {
    // Per mode the complex system is 1 + i s mu, s = sqrt(lambda_dt): its condition, and so the
    // Krylov iterations' count squared, grows as sqrt(lambda_dt). A step 16x stronger needs
    // about 2x the iterations; Jacobi CG on the real L^2 system (condition ~ lambda_dt) needs 4x.
    const Case c = make(Operator::CurvatureFlow, 5);
    const int n = c.op.size();
    const auto iterations = [&](double t, Preconditioner p) {
        Positions x = c.mesh.positions;
        fairing::SolveSettings settings;
        settings.preconditioner = p;
        settings.max_iterations = 20000;
        const fairing::SolveStats stats = fairing::solve(
            l2_system(c, l2_lambda(c, Operator::CurvatureFlow, t), std::vector<char>(n, 1)), x,
            settings);
        EXPECT_TRUE(stats.converged);
        return static_cast<double>(stats.iterations);
    };
    const double complex_ratio = iterations(360, Preconditioner::Automatic) /
                                 iterations(22.5, Preconditioner::Automatic);
    const double jacobi_ratio = iterations(360, Preconditioner::Jacobi) /
                                iterations(22.5, Preconditioner::Jacobi);
    EXPECT_LT(complex_ratio, 2.6);
    EXPECT_GT(jacobi_ratio, complex_ratio * 1.3);
}

namespace {

// The correction of one complex solve from x = the positions, to a relative L^2 residual of
// 1e-10, by ComplexFactorSolver with Gauss-Seidel or complex Jacobi; iterations in *count.
Positions complex_solve(const LinearSystem& s, const Positions& start, bool gauss_seidel,
                        int* count) {
    Positions b(start.rows(), 3), x = start;
    for (int i = 0; i < start.rows(); ++i) b.row(i) = s.diagonal[i] * start.row(i);
    fairing::detail::ComplexFactorSolver solver(s, nullptr, gauss_seidel);
    const std::array<double, 3> g = solver.set_residual(b, x, fairing::ResidualNorm::L2);
    std::array<double, 3> goal;
    for (int c = 0; c < 3; ++c) goal[c] = 1e-10 * b.col(c).norm();
    *count = solver.correct(x, goal, fairing::ResidualNorm::L2, 5000, {true, true, true},
                            nullptr);
    const std::array<double, 3> left = solver.set_residual(b, x, fairing::ResidualNorm::L2);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(g[c], goal[c]);
        EXPECT_LE(left[c], goal[c]) << "column " << c;
    }
    return x;
}

}  // namespace

// Automatic sweeps for the weighted operators at every strength, the mildest included (their
// iterations halve there too: solver.cpp), and keeps the umbrella on its complex diagonal.
TEST(ComplexFactor, AutomaticSweepsForWeightedOperatorsAtEveryStrength) {
    for (Operator op : meshes::kOperators) {
        const Case c = make(op, 3);
        for (double t : {0.05, 1.0, 22.5}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " time step " << t);
            const LinearSystem s = l2_system(c, l2_lambda(c, op, t),
                                             std::vector<char>(c.op.size(), 1));
            Positions x = c.mesh.positions;
            const fairing::SolveStats stats = fairing::solve(s, x, fairing::SolveSettings());
            EXPECT_TRUE(stats.converged);
            EXPECT_TRUE(stats.complex_factor);
            EXPECT_EQ(stats.gauss_seidel, op != Operator::Umbrella);
        }
    }
}

TEST(ComplexFactor, GaussSeidelGivesJacobisResultInFewerIterations) {
    // 40,962 vertices, fixed rows: below kParallelRows, so one sweep block.
    for (Operator op : meshes::kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const Case c = make(op, 6);
        const int n = c.op.size();
        const LinearSystem s = l2_system(c, l2_lambda(c, op, op == Operator::Umbrella ? 10 : 22.5),
                                         meshes::every_kth_fixed(n, 101));
        int sweeps = 0, jacobi = 0;
        const Positions a = complex_solve(s, c.mesh.positions, true, &sweeps);
        const Positions b = complex_solve(s, c.mesh.positions, false, &jacobi);
        EXPECT_LT(meshes::max_row_distance(a, b), 1e-8 * meshes::bbox_diagonal(b));
        for (int i = 0; i < n; ++i) {
            if (!s.free[i]) {
                ASSERT_EQ(a.row(i), c.mesh.positions.row(i)) << "fixed row " << i;
            }
        }
        // Measured here: 17 / 30 (umbrella), 38 / 84 (scale-dependent), 34 / 77 (curvature).
        EXPECT_LT(sweeps, 0.65 * jacobi) << sweeps << " against " << jacobi;
    }
}

TEST(ComplexFactor, GaussSeidelInBlocksOnLargeMeshesInLocalOrder) {
    // 163,842 vertices: from kParallelRows on, blocks of kSweepBlock rows, whose couplings to
    // other blocks are left to the Krylov method. Numbered level by level (the icosphere's own
    // order) most couplings cross blocks and the solver keeps complex Jacobi (the same bits);
    // in the engine's numbering (vertex_order.h) it sweeps, on one thread or two alike.
    const meshes::TriangleMesh sphere = meshes::radial_noise(meshes::icosphere(7), 0.05, 23);
    static_assert(fairing::detail::kSweepBlock * 4 < 163842, "several sweep blocks");
    for (bool local : {false, true}) {
        SCOPED_TRACE(local ? "engine numbering" : "level order");
        const meshes::TriangleMesh mesh =
            local ? fairing::detail::renumbered(sphere, fairing::detail::locality_order(sphere))
                  : sphere;
        Case c = meshes::assembled(mesh, Operator::CurvatureFlow);
        const int n = c.op.size();
        const LinearSystem s = l2_system(c, l2_lambda(c, Operator::CurvatureFlow, 22.5),
                                         meshes::every_kth_fixed(n, 101));
        int sweeps = 0, jacobi = 0, two = 0;
        const Positions a = complex_solve(s, c.mesh.positions, true, &sweeps);
        const Positions b = complex_solve(s, c.mesh.positions, false, &jacobi);
        c.op.threads = 2;
        const Positions a2 = complex_solve(s, c.mesh.positions, true, &two);
        EXPECT_EQ(sweeps, two);
        EXPECT_EQ(0, std::memcmp(a.data(), a2.data(), sizeof(double) * 3 * n));
        if (!local) {
            EXPECT_EQ(sweeps, jacobi);
            EXPECT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(double) * 3 * n));
            continue;
        }
        EXPECT_LT(meshes::max_row_distance(a, b), 1e-8 * meshes::bbox_diagonal(b));
        // Measured here: 97 against 151 (blocks of 8,192 rows).
        EXPECT_LT(sweeps, 0.75 * jacobi) << sweeps << " against " << jacobi;
    }
}

TEST(ComplexFactor, GaussSeidelNeedsRowsSortedByColumn) {
    // The sweeps split a row at its diagonal by column order; on a row out of order the solver
    // falls back to complex Jacobi, with Jacobi's bits.
    Case c = make(Operator::CurvatureFlow, 3);
    const int n = c.op.size();
    for (int i = 0; i < n; ++i)
        for (int e = c.op.row_start[i] + 1; e < c.op.row_start[i + 1]; ++e)
            ASSERT_LT(c.op.column[e - 1], c.op.column[e]) << "assemble sorts row " << i;
    const int row = n / 2, e = c.op.row_start[row];
    std::swap(c.op.column[e], c.op.column[e + 1]);
    std::swap(c.op.weight[e], c.op.weight[e + 1]);
    const LinearSystem s = l2_system(c, l2_lambda(c, Operator::CurvatureFlow, 22.5),
                                     std::vector<char>(n, 1));
    int asked = 0, jacobi = 0;
    const Positions a = complex_solve(s, c.mesh.positions, true, &asked);
    const Positions b = complex_solve(s, c.mesh.positions, false, &jacobi);
    EXPECT_EQ(asked, jacobi);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(double) * 3 * n));
}
