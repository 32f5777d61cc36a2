// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The row-parallel solver (Options::threads) computes the same step as one thread: only the
// order of the floating-point sums in the dot products differs. Meshes of 50,000 vertices or
// more take the parallel path; smaller ones always run on one thread.
#include "meshes.h"

#include <fairing/fairing.h>
#include <gtest/gtest.h>

using fairing::Operator;

TEST(Threads, TwoThreadsAgreeWithOneAboveTheThreshold) {
    // Level 7: 163,842 vertices, above the 50,000-vertex threshold.
    const fairing::TriangleMesh m = meshes::radial_noise(meshes::icosphere(7), 0.002);
    ASSERT_GE(m.positions.rows(), 50000);
    for (Operator op : {Operator::Umbrella, Operator::CurvatureFlow})
        for (int order : {1, 2, 3}) {  // 3: the partial-fraction solve's complex passes
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            fairing::Options o;
            o.op = op;
            o.order = order;
            o.time_step = 1.0;
            o.tolerance = 1e-12;
            o.threads = 1;
            const fairing::Result one = fairing::fair(m, {}, o);
            o.threads = 2;
            const fairing::Result two = fairing::fair(m, {}, o);
            EXPECT_LT(meshes::max_row_distance(one.positions, two.positions), 1e-9);
            EXPECT_NEAR(two.volume_after, two.volume_before, 1e-12 * two.volume_before);
            EXPECT_GT(two.vertices_moved, 0);
        }
}

TEST(Threads, NegativeThreadCountIsRefused) {
    const fairing::TriangleMesh m = meshes::icosphere(1);
    fairing::Options o;
    o.threads = -1;
    try {
        fairing::fair(m, {}, o);
        FAIL() << "expected fairing::Error";
    } catch (const fairing::Error& e) {
        EXPECT_NE(std::string(e.what()).find("thread"), std::string::npos) << e.what();
    }
}
