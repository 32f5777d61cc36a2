// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The filters' one-click settings (filter_parameters.h: L^2, 4 / 2 / 4 steps, the automatic time
// step and the Automatic boundary) on open input, good and bad: the boundary loops are smoothed
// as curves with their own automatic time step (loop_strength.h), and every case gives a finite
// result or a refusal that leaves the mesh as it was.
#include "robust.h"

#include <fairing_parameters/filter_parameters.h>

using namespace robust;

namespace {

Options one_click(Operator op) {
    return filter_parameters::toOptions(op, filter_parameters::defaults(op));
}

TriangleMesh noisy_grid(int n, double noise, std::uint64_t seed) {
    TriangleMesh m = meshes::grid(n, n, n, n);
    meshes::Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i) m.positions(i, 2) = noise * rng.normal();
    return m;
}

}  // namespace

TEST(OneClick, AutomaticBoundarySmoothsTheLoopsOnlyWithTheAutomaticTimeStep) {
    for (Operator op : meshes::kOperators) {
        filter_parameters::Values v = filter_parameters::defaults(op);
        EXPECT_EQ(v.boundaryMode, filter_parameters::kAutomaticBoundary);
        EXPECT_EQ(filter_parameters::toOptions(op, v).boundary,
                  fairing::BoundaryMode::SmoothCurve);
        // A time step given: the boundary stays where it was, as before the automatic strength.
        v.timeStep = filter_parameters::referenceTimeStep(op);
        EXPECT_EQ(filter_parameters::toOptions(op, v).boundary, fairing::BoundaryMode::Fixed);
    }
    EXPECT_EQ(filter_parameters::boundaryModeLabels()[filter_parameters::kAutomaticBoundary],
              "Automatic");
}

TEST(OneClick, NoisyOpenGridMovesItsBoundaryAndReportsTheLoopStep) {
    const TriangleMesh m = noisy_grid(16, 0.25, 5);
    const auto loops = meshes::boundary_loops(m.triangles);
    for (Operator op : meshes::kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const Result r = expect_result(m, {}, one_click(op));
        EXPECT_TRUE(r.automatic_time_step);
        EXPECT_GT(r.boundary_time_step, 0);
        int boundary_moved = 0;
        for (int v : loops[0])
            boundary_moved += r.positions.row(v) != m.positions.row(v) ? 1 : 0;
        EXPECT_GT(boundary_moved, 0);
    }
}

// Bad open input through the one-click path: tiny loops, a bow-tie vertex on the boundary,
// coincident boundary vertices, a loop of needle triangles, loops pinned by a selection.
TEST(OneClick, BadOpenInputGivesAFiniteResult) {
    std::vector<std::pair<const char*, TriangleMesh>> cases;
    {
        TriangleMesh t;
        t.positions.resize(3, 3);
        t.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0.1;
        t.triangles = {{0, 1, 2}};
        cases.emplace_back("single triangle", t);
    }
    {
        const TriangleMesh a = noisy_grid(4, 0.3, 1);
        TriangleMesh b = meshes::translated(noisy_grid(4, 0.3, 2), Vec3(4, 4, 0));
        b.positions(0, 2) = a.positions(meshes::grid_index(4, 4, 4), 2);
        TriangleMesh m = meshes::merge(a, b);
        const int na = static_cast<int>(a.positions.rows());
        for (Triangle& t : m.triangles)
            for (int& v : t)
                if (v == na) v = meshes::grid_index(4, 4, 4);
        cases.emplace_back("open bow-tie vertex", m);
    }
    {
        TriangleMesh m = noisy_grid(8, 0.3, 3);
        m.positions.row(1) = m.positions.row(0);  // two boundary vertices at one position
        cases.emplace_back("coincident boundary vertices", m);
    }
    {
        TriangleMesh m = noisy_grid(8, 0.3, 4);
        for (int i = 0; i <= 8; ++i) m.positions(i, 1) = 1e-9 * i;  // a row of needles
        cases.emplace_back("needle triangles along a loop", m);
    }
    for (const auto& c : cases)
        for (Operator op : meshes::kOperators) {
            SCOPED_TRACE(testing::Message() << c.first << ", " << fairing::to_string(op));
            expect_result(c.second, {}, one_click(op));
        }
    const TriangleMesh m = noisy_grid(8, 0.3, 6);
    fairing::Constraints pinned;
    pinned.fixed.assign(m.positions.rows(), 0);
    for (int i = 0; i < 9; i += 2) pinned.fixed[i] = 1;  // every other vertex of one side
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, pinned, one_click(op));
        for (int i = 0; i < 9; i += 2) EXPECT_TRUE(r.positions.row(i) == m.positions.row(i));
    }
}
