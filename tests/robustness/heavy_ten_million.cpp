// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Issue 6, item 6: a 10 M-face mesh, generated here (a noisy torus grid, 2500 x 2000 vertices,
// 10,000,000 faces), smoothed once with the plugin's defaults. Not part of the default CTest
// run (it takes minutes and GBs): build the target robustness_heavy and run
//   /usr/bin/time -v <build>/bin/robustness_heavy --gtest_filter='Heavy.*Umbrella'
// or configure with -DFAIRING_BUILD_HEAVY_TESTS=ON and run `ctest -L heavy`.
#include "robust.h"

#include <chrono>
#include <cstdio>

using namespace robust;

namespace {

void run_heavy(Operator op) {
    const auto t0 = std::chrono::steady_clock::now();
    TriangleMesh m = meshes::torus_grid(2500, 2000, 3.0, 1.0);
    ASSERT_EQ(m.triangles.size(), 10000000u);
    meshes::Rng rng(99);
    const double h = 2 * meshes::kPi / 2000.0;  // about the minor edge length
    for (int i = 0; i < m.positions.rows(); ++i)
        for (int k = 0; k < 3; ++k) m.positions(i, k) += 0.25 * h * rng.symmetric();
    const double v0 = volume_of(m.positions, m.triangles);
    const auto t1 = std::chrono::steady_clock::now();
    Options o = defaults(op);
    const Result r = fairing::fair(m, {}, o);
    const auto t2 = std::chrono::steady_clock::now();
    ASSERT_TRUE(r.positions.allFinite());
    const double v1 = volume_of(r.positions, m.triangles);
    EXPECT_NEAR(v1, v0, 1e-9 * v0);
    EXPECT_GT(r.vertices_moved, static_cast<int>(m.positions.rows()) / 2);
    std::printf("[heavy] %s: %lld vertices, %zu faces; generation %.1f s, fair() %.1f s "
                "(engine %.1f s), %d CG iterations, residual %.3g, volume %.12g -> %.12g, "
                "RSS at the end %lld MB\n",
                fairing::to_string(op), static_cast<long long>(m.positions.rows()),
                m.triangles.size(), std::chrono::duration<double>(t1 - t0).count(),
                std::chrono::duration<double>(t2 - t1).count(), r.seconds, r.total_iterations,
                r.max_residual, v0, v1, resident_bytes() / (1024 * 1024));
}

}  // namespace

TEST(Heavy, TenMillionFacesUmbrella) { run_heavy(Operator::Umbrella); }
TEST(Heavy, TenMillionFacesCurvatureFlow) { run_heavy(Operator::CurvatureFlow); }
