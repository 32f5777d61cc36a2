// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Section 2.5.1: the transfer function of implicit (and explicit) umbrella diffusion, checked
// exactly on a regular closed torus grid, where the umbrella operator depends only on the
// connectivity and diagonalizes in the discrete Fourier basis.
//
// Grid N x N, vertex (u, v), neighbours at the offsets (+-1,0), (0,+-1), (1,1), (-1,-1), mass 6.
// For f_i = exp(2 pi i (a u + b v) / N):  L f = -mu f  with
//     mu(a, b) = 1 - (1/6) sum_offsets cos(2 pi (a du + b dv) / N)
// (the offsets come in +- pairs, so cos and sin modes share mu). Then
//     implicit order 1: (I - ldt L) X' = X          -> X' = X / (1 + ldt mu)
//     implicit order 2: (I + ldt L^2) X' = X        -> X' = X / (1 + ldt mu^2)
//     explicit order 1: X' = (I + ldt L) X          -> X' = (1 - ldt mu) X
//     explicit order 2: X' = (I - ldt L^2) X        -> X' = (1 - ldt mu^2) X
// and for the higher powers of section 2.6 (Figure 3a), p = 3, 4:
//     implicit: (I + ldt (-L)^p) X' = X             -> X' = X / (1 + ldt mu^p)
//     explicit: X' = (I - ldt (-L)^p) X             -> X' = (1 - ldt mu^p) X
// The positions are the torus embedding (itself a sum of the modes (1,0), (1,+-1), (0,1)) plus a
// test mode (a, b) of amplitude s, so the expected result is a sum of scaled modes.
#include "meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using fairing::Integration;
using fairing::Operator;
using fairing::Options;
using fairing::TriangleMesh;
using meshes::kPi;
using meshes::Positions;
using meshes::Vec3;

namespace {

const int N = 16;
const double R = 3.0, r = 1.0, s = 0.2;

double mu(int a, int b) {
    double sum = 0;
    for (const auto& d : meshes::torus_neighbour_offsets())
        sum += std::cos(2 * kPi * (a * d[0] + b * d[1]) / N);
    return 1.0 - sum / 6.0;
}

// Positions of the torus plus the test mode (a, b); with a gain g(mode) per mode.
Positions modes(int a, int b, const std::function<double(int, int)>& g) {
    Positions p(N * N, 3);
    for (int v = 0; v < N; ++v) {
        for (int u = 0; u < N; ++u) {
            const double tu = 2 * kPi * u / N, tv = 2 * kPi * v / N;
            const double phi = 2 * kPi * (a * u + b * v) / N;
            // (R + r cos tv) cos tu = R cos tu + r/2 (cos(tu + tv) + cos(tu - tv)), same for sin.
            const double x = R * g(1, 0) * std::cos(tu) +
                             0.5 * r * (g(1, 1) * std::cos(tu + tv) + g(1, -1) * std::cos(tu - tv)) +
                             s * g(a, b) * std::cos(phi);
            const double y = R * g(1, 0) * std::sin(tu) +
                             0.5 * r * (g(1, 1) * std::sin(tu + tv) + g(1, -1) * std::sin(tu - tv)) +
                             s * g(a, b) * std::sin(phi);
            const double z = r * g(0, 1) * std::sin(tv) + s * g(a, b) * std::cos(phi);
            p.row(meshes::torus_index(u, v, N, N)) << x, y, z;
        }
    }
    return p;
}

Options umbrella_options(int order, double time_step, Integration integration, int steps = 1,
                         double tolerance = 1e-14) {
    Options o;
    o.op = Operator::Umbrella;
    o.integration = integration;
    o.order = order;
    o.time_step = time_step;
    o.steps = steps;
    o.preserve_volume = false;
    o.tolerance = tolerance;
    o.max_iterations = 10000;
    return o;
}

const int kModes[][2] = {{1, 0}, {0, 1}, {1, 1}, {2, -1}, {3, 5}, {5, -3}, {8, 8}, {8, 0}, {7, 2}};

void check(int order, Integration integration, double ldt, int steps,
           const std::function<double(double)>& gain_of_mu, double tolerance = 1e-14) {
    TriangleMesh m = meshes::torus_grid(N, N, R, r);
    for (const auto& ab : kModes) {
        SCOPED_TRACE(testing::Message() << "mode (" << ab[0] << ", " << ab[1] << "), ldt = " << ldt
                                        << ", order " << order << ", steps " << steps);
        auto unit = [](int, int) { return 1.0; };
        auto gain = [&](int a, int b) { return std::pow(gain_of_mu(mu(a, b)), steps); };
        m.positions = modes(ab[0], ab[1], unit);
        const fairing::Result res =
            fairing::fair(m, {}, umbrella_options(order, ldt, integration, steps, tolerance));
        EXPECT_DOUBLE_EQ(res.lambda_dt, ldt);  // umbrella: dimensionless time step
        const Positions expected = modes(ab[0], ab[1], gain);
        ASSERT_EQ(res.positions.rows(), expected.rows());
        EXPECT_LT(meshes::max_row_distance(res.positions, expected), 1e-9);
    }
}

}  // namespace

TEST(TransferFunction, EigenvaluesByHand) {
    // Sanity of the hand formula: the constant mode is in the kernel, and since
    // cos A + cos B + cos(A + B) >= -3/2, 0 <= mu <= 3/2 on this grid.
    EXPECT_DOUBLE_EQ(mu(0, 0), 0.0);
    EXPECT_NEAR(mu(N / 2, 0), 1.0 - (2 * -1.0 + 2 * 1.0 + 2 * -1.0) / 6.0, 1e-15);
    for (int a = 0; a < N; ++a)
        for (int b = 0; b < N; ++b) {
            EXPECT_GE(mu(a, b), -1e-15);
            EXPECT_LE(mu(a, b), 1.5 + 1e-15);
        }
}

TEST(TransferFunction, ImplicitOrder1) {
    for (double ldt : {0.1, 1.0, 10.0, 100.0})
        check(1, Integration::Implicit, ldt, 1, [&](double m) { return 1.0 / (1.0 + ldt * m); });
}

TEST(TransferFunction, ImplicitOrder2) {
    for (double ldt : {0.1, 1.0, 10.0, 100.0})
        check(2, Integration::Implicit, ldt, 1,
              [&](double m) { return 1.0 / (1.0 + ldt * m * m); });
}

TEST(TransferFunction, ImplicitSeveralStepsCompose) {
    // The umbrella does not depend on the positions: three steps apply the filter three times.
    const double ldt = 2.0;
    check(1, Integration::Implicit, ldt, 3, [&](double m) { return 1.0 / (1.0 + ldt * m); });
    check(2, Integration::Implicit, ldt, 3, [&](double m) { return 1.0 / (1.0 + ldt * m * m); });
}

TEST(TransferFunction, ExplicitOrder1) {
    // Eq. 8, stable here for ldt < 4/3 (mu <= 3/2).
    for (double ldt : {0.1, 0.45})
        check(1, Integration::Explicit, ldt, 1, [&](double m) { return 1.0 - ldt * m; });
    check(1, Integration::Explicit, 0.3, 2, [&](double m) { return 1.0 - 0.3 * m; });
}

TEST(TransferFunction, ExplicitOrder2) {
    for (double ldt : {0.05, 0.2})
        check(2, Integration::Explicit, ldt, 1, [&](double m) { return 1.0 - ldt * m * m; });
}

// One step goes through the partial-fraction solve (src/power_solve.h: a first-order and a
// complex solve for L^3, two complex ones for L^4); several steps on the umbrella's frozen
// operator through the Lanczos process on the first-order operator (src/frozen_steps.h).
TEST(TransferFunction, ImplicitOrders3And4) {
    // The L^p residual b - A x cannot fall below rounding times |A| |x| ~ 1e-16 ldt mu^p: the
    // stiffest systems are asked for 1e-12 (the result is still checked to 1e-9).
    for (int order : {3, 4})
        for (double ldt : {0.1, 1.0, 10.0, 1000.0})
            check(
                order, Integration::Implicit, ldt, 1,
                [&](double m) { return 1.0 / (1.0 + ldt * std::pow(m, order)); },
                ldt > 10 ? 1e-12 : 1e-14);
}

TEST(TransferFunction, ImplicitOrders3And4SeveralStepsCompose) {
    for (int order : {3, 4})
        check(order, Integration::Implicit, 5.0, 3,
              [&](double m) { return 1.0 / (1.0 + 5.0 * std::pow(m, order)); });
}

TEST(TransferFunction, ExplicitOrders3And4) {
    // Stable while ldt mu^p < 2, mu <= 3/2.
    for (int order : {3, 4})
        for (double ldt : {0.05, 0.3})
            check(order, Integration::Explicit, ldt, 1,
                  [&](double m) { return 1.0 - ldt * std::pow(m, order); });
}
