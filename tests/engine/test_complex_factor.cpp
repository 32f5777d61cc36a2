// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The L^2 step as one complex solve (fairing/src/complex_factor.h): A^-1 g = Re (M + i s K)^-1 g
// without soft weights. Checked against a dense solve of the real L^2 system, for every
// operator, with fixed rows, in both residual norms; bit-identical on 1 and 2 threads; the
// iteration count grows as lambda_dt^(1/4) where Jacobi CG on the L^2 system grows as
// lambda_dt^(1/2).
#include "meshes.h"

#include "fairing/half_edge.h"
#include "fairing/operators.h"
#include "fairing/solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

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
