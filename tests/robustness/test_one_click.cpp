// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The filters' one-click settings (filter_parameters.h: L^2, 8 / 2 / 4 steps, the automatic time
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

// A flat tetrahedron beside a noisy sphere: the shape of a four-vertex part of libcgal-demo's
// b9_mesh, whose steps flatten it so that scaling its volume back blew it up (the curvature flow's
// one-click run moved it by 400 mean edges). No one-click run enlarges it more than twofold; the
// curvature flow's leaves it exactly as given and says so; every run smooths the sphere with its
// volume kept. Alone, the tetrahedron is refused.
TEST(OneClick, FlattenedComponentIsLeftAsGiven) {
    TriangleMesh sphere = meshes::gaussian_radial_noise(meshes::icosphere(3), 0.02, 11);
    const double edge = meshes::mean_edge_length(sphere.positions, sphere.triangles);
    TriangleMesh tetrahedron;
    tetrahedron.positions.resize(4, 3);
    tetrahedron.positions << -0.5893, 0.8211, -0.4774, -0.1219, -0.0880, 0.1722, 0.0962,
        -0.6682, 0.2416, 0.6150, -0.0650, 0.0636;  // about its centroid, mean edge 1.13
    tetrahedron.positions *= edge / 1.13;
    tetrahedron.triangles = {{2, 1, 3}, {1, 0, 3}, {2, 0, 1}, {2, 3, 0}};
    tetrahedron = meshes::translated(tetrahedron, Vec3(3, 0, 0));
    const TriangleMesh m = meshes::merge(sphere, tetrahedron);
    const int ns = static_cast<int>(sphere.positions.rows());
    const double sphere_volume = volume_of(sphere.positions, sphere.triangles);
    for (Operator op : meshes::kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const Result r = expect_result(m, {}, one_click(op));
        EXPECT_LT(meshes::bbox_diagonal(r.positions.bottomRows(4)),
                  2 * meshes::bbox_diagonal(tetrahedron.positions));
        EXPECT_GT((r.positions.topRows(ns) - sphere.positions).cwiseAbs().maxCoeff(), 0.1 * edge);
        EXPECT_NEAR(volume_of(r.positions.topRows(ns), sphere.triangles), sphere_volume,
                    1e-9 * sphere_volume);
        ASSERT_EQ(r.components.size(), 2u);
        if (op != Operator::CurvatureFlow) continue;
        for (int i = 0; i < 4; ++i)
            EXPECT_TRUE(r.positions.row(ns + i) == m.positions.row(ns + i)) << "vertex " << i;
        EXPECT_EQ(r.components[1].restoration, fairing::Restoration::Collapsed);
        EXPECT_TRUE(has_warning(r, "1 component (4 vertices) was left as given")) << warnings(r);
    }
    Options o = one_click(Operator::CurvatureFlow);
    o.time_step = 22.5;
    expect_refused(tetrahedron, {}, o,
                   {"the steps flattened every component that could move",
                    "the mesh was left unchanged", "use a smaller time step"});
    // Alone, the one-click run flattens it too; the refusal names the automatic step.
    expect_refused(tetrahedron, {}, one_click(Operator::CurvatureFlow),
                   {"the steps flattened every component that could move",
                    "use a smaller time step than the automatic one ("});
}
