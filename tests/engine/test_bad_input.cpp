// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Input validation and refusals (fairing.h, half_edge.h): what is handled (isolated vertices,
// zero-area faces, faces repeating an index, inconsistent orientation) and what is refused with
// a fairing::Error whose message names the problem.
#include "meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using fairing::Constraints;
using fairing::Operator;
using fairing::Options;
using fairing::Triangle;
using fairing::TriangleMesh;
using meshes::Positions;

namespace {

using meshes::kOperators;

TriangleMesh sphere() { return meshes::radial_noise(meshes::icosphere(2), 0.05, 66); }

// Runs fair() and returns the message of the fairing::Error it throws ("" if none).
std::string error_of(const TriangleMesh& m, const Constraints& c, const Options& o) {
    try {
        fairing::fair(m, c, o);
    } catch (const fairing::Error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(BadInput, ZeroAreaFacesAreCountedAndHarmless) {
    // 8x6 integer grid with bumps; vertex (3,2) moved onto the diagonal (2,2)-(3,3) of the
    // triangle (2,2) (3,2) (3,3), which becomes degenerate. Those three vertices stay at z = 0.
    const int nx = 8, ny = 6;
    TriangleMesh m = meshes::grid(nx, ny, nx, ny);
    meshes::Rng rng(4);
    for (int i = 0; i < m.positions.rows(); ++i) m.positions(i, 2) = 0.3 * rng.symmetric();
    const int a = meshes::grid_index(2, 2, nx), moved = meshes::grid_index(3, 2, nx);
    const int c = meshes::grid_index(3, 3, nx);
    m.positions.row(a) << 2.0, 2.0, 0.0;
    m.positions.row(c) << 3.0, 3.0, 0.0;
    m.positions.row(moved) << 2.5, 2.5, 0.0;
    int degenerate = 0;
    for (const Triangle& t : m.triangles) {
        double longest = 0;
        for (int k = 0; k < 3; ++k)
            longest = std::max(longest, (meshes::row(m.positions, t[k]) -
                                         meshes::row(m.positions, t[(k + 1) % 3])).squaredNorm());
        degenerate += meshes::triangle_area(m.positions, t) < 1e-12 * longest ? 1 : 0;
    }
    ASSERT_EQ(degenerate, 1);
    for (Operator op : kOperators)
        for (int order : {1, 2}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o;
            o.op = op;
            o.order = order;
            o.time_step = 1;  // a step that moves the bumps whatever the automatic choice
            const fairing::Result r = fairing::fair(m, {}, o);
            EXPECT_EQ(r.zero_area_faces, 1);
            EXPECT_TRUE(r.positions.allFinite());
            EXPECT_GT(meshes::max_row_distance(r.positions, m.positions), 1e-3);
        }
}

TEST(BadInput, IsolatedVerticesAreLeftOut) {
    TriangleMesh m = sphere();
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 2, 3);
    m.positions.row(n) << 5, 6, 7;
    m.positions.row(n + 1) << -1e3, 0.5, 2;
    const double v0 = meshes::volume(m.positions, m.triangles);
    for (Operator op : kOperators) {
        Options o;
        o.op = op;
        const fairing::Result r = fairing::fair(m, {}, o);
        ASSERT_EQ(r.positions.rows(), n + 2);
        EXPECT_EQ(r.isolated_vertices, 2);
        EXPECT_TRUE(r.positions.row(n) == m.positions.row(n));
        EXPECT_TRUE(r.positions.row(n + 1) == m.positions.row(n + 1));
        EXPECT_TRUE(r.positions.allFinite());
        EXPECT_NEAR(meshes::volume(r.positions, m.triangles), v0, 1e-12 * v0);
        EXPECT_EQ(r.components.size(), 1u);
        EXPECT_LE(r.vertices_moved, n);
    }
}

TEST(BadInput, FacesRepeatingAnIndexAreDropped) {
    TriangleMesh m = sphere();
    m.triangles.push_back({3, 3, 5});
    m.triangles.push_back({7, 8, 7});
    const fairing::Result r = fairing::fair(m, {}, Options{});
    EXPECT_EQ(r.dropped_faces, 2);
    EXPECT_TRUE(r.positions.allFinite());
}

TEST(BadInput, NonFiniteCoordinatesAreRefused) {
    const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity()};
    for (double v : bad) {
        TriangleMesh m = sphere();
        m.positions(10, 1) = v;
        const std::string msg = error_of(m, {}, Options{});
        EXPECT_TRUE(contains(msg, "non-finite")) << "got: '" << msg << "'";
    }
}

TEST(BadInput, NonManifoldEdgeIsRefused) {
    TriangleMesh m = sphere();
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 1, 3);
    m.positions.row(n) << 2, 2, 2;
    m.triangles.push_back({m.triangles[0][1], m.triangles[0][0], n});  // third face on an edge
    try {
        fairing::fair(m, {}, Options{});
        ADD_FAILURE() << "a non-manifold edge was accepted";
    } catch (const fairing::Error& e) {
        // the problem and the repair, which front ends name in their host's words
        EXPECT_EQ(e.repair(), fairing::Repair::NonManifoldEdges);
        EXPECT_EQ(e.problem(), "1 non-manifold edge (shared by three or more faces): the one-ring "
                               "of their vertices is undefined");
        EXPECT_EQ(std::string(e.what()), e.problem() + "; repair the non-manifold edges first");
        EXPECT_EQ(e.alternative(), "");
    }
}

TEST(BadInput, ErrorKeepsProblemRepairAndAlternativeApart) {
    const fairing::Error e("2 things are wrong", fairing::Repair::DuplicateFaces, "give up");
    EXPECT_EQ(std::string(e.what()), "2 things are wrong; remove the duplicated faces first, or "
                                     "give up");
    EXPECT_EQ(e.problem(), "2 things are wrong");
    EXPECT_EQ(e.alternative(), "give up");
    const fairing::Error plain("no repair helps");
    EXPECT_EQ(plain.repair(), fairing::Repair::None);
    EXPECT_EQ(plain.problem(), "no repair helps");
    const fairing::Error copy = e;  // an exception is copied when thrown: offsets, not pointers
    EXPECT_EQ(copy.alternative(), "give up");
}

TEST(BadInput, IndexOutOfRangeIsRefused) {
    for (int bad : {-1, 100000}) {
        TriangleMesh m = sphere();
        m.triangles[4][2] = bad == -1 ? -1 : static_cast<int>(m.positions.rows());
        const std::string msg = error_of(m, {}, Options{});
        EXPECT_TRUE(contains(msg, "out of range")) << "index " << bad << ", got: '" << msg << "'";
    }
}

TEST(BadInput, WeightsOutsideUnitIntervalAreRefused) {
    const TriangleMesh m = sphere();
    for (double w : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
        Constraints c;
        c.weights.assign(m.positions.rows(), 0.5);
        c.weights[12] = w;
        const std::string msg = error_of(m, c, Options{});
        EXPECT_TRUE(contains(msg, "weight")) << "w = " << w << ", got: '" << msg << "'";
    }
}

TEST(BadInput, ConstraintVectorsOfWrongSizeAreRefused) {
    const TriangleMesh m = sphere();
    const int n = static_cast<int>(m.positions.rows());
    {
        Constraints c;
        c.fixed.assign(n - 1, 0);
        const std::string msg = error_of(m, c, Options{});
        EXPECT_TRUE(contains(msg, "size")) << "got: '" << msg << "'";
    }
    {
        Constraints c;
        c.weights.assign(n + 3, 1.0);
        const std::string msg = error_of(m, c, Options{});
        EXPECT_TRUE(contains(msg, "size")) << "got: '" << msg << "'";
    }
}

TEST(BadInput, BadTimeStepIsRefused) {
    const TriangleMesh m = sphere();
    for (double t : {-1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
        Options o;
        o.time_step = t;
        const std::string msg = error_of(m, {}, o);
        EXPECT_TRUE(contains(msg, "time step")) << "t = " << t << ", got: '" << msg << "'";
    }
}

TEST(BadInput, BadOrderIsRefused) {
    const TriangleMesh m = sphere();
    for (int order : {0, 5, -1}) {
        Options o;
        o.order = order;
        const std::string msg = error_of(m, {}, o);
        EXPECT_NE(msg.find("order must be 1 (L), 2 (L squared), 3 or 4"), std::string::npos)
            << "order " << order << ": " << msg;
    }
}

TEST(BadInput, IterationCapTooLow) {
    const TriangleMesh m = sphere();
    Options o;
    o.tolerance = 1e-14;
    o.max_iterations = 1;
    o.direct_fallback = false;  // else solved directly (test_convergence.cpp)
    const std::string msg = error_of(m, {}, o);
    EXPECT_TRUE(contains(msg, "did not converge")) << "got: '" << msg << "'";

    o.accept_unconverged = true;
    fairing::Result r;
    ASSERT_NO_THROW(r = fairing::fair(m, {}, o));
    ASSERT_EQ(r.positions.rows(), m.positions.rows());
    EXPECT_TRUE(r.positions.allFinite());
    EXPECT_FALSE(r.warnings.empty());
    ASSERT_FALSE(r.solves.empty());
    EXPECT_FALSE(r.solves[0].converged);
    EXPECT_GT(r.max_residual, o.tolerance);
}

// Orientation does not matter to the operators; a component whose faces disagree is not
// closed, so it is smoothed but no volume is restored.
TEST(BadInput, InconsistentOrientationIsCountedNotRefused) {
    TriangleMesh m = sphere();
    std::swap(m.triangles[5][0], m.triangles[5][1]);
    Options o;
    o.time_step = 1.0;  // the same strength for both meshes (the flipped face tilts a normal)
    o.preserve_volume = true;
    const fairing::Result r = fairing::fair(m, {}, o);
    EXPECT_EQ(r.inconsistent_edges, 3);
    ASSERT_EQ(r.components.size(), 1u);
    EXPECT_FALSE(r.components[0].closed);
    EXPECT_EQ(r.components[0].restoration, fairing::Restoration::None);
    EXPECT_TRUE(r.positions.allFinite());
    EXPECT_EQ(r.volume_before, 0.0);

    // Same smoothing as the consistent mesh without volume restoration.
    const TriangleMesh good = sphere();
    Options plain = o;
    plain.preserve_volume = false;
    const fairing::Result ref = fairing::fair(good, {}, plain);
    EXPECT_LT(meshes::max_row_distance(r.positions, ref.positions), 1e-9);
}
