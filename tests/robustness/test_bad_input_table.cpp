// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// One test per row of docs/bad-input.md, through the engine: each bad input gives either a
// correct result or a refusal whose message names the problem, the count and the MeshLab filter
// that repairs it, and the caller's mesh is bit-identical after a refusal.
#include "robust.h"

#include <cmath>
#include <limits>

using namespace robust;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// A bumpy open grid on integer coordinates, nx x ny quads.
TriangleMesh bumpy_grid(int nx, int ny, std::uint64_t seed = 4) {
    TriangleMesh m = meshes::grid(nx, ny, nx, ny);
    meshes::Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i) m.positions(i, 2) = 0.3 * rng.symmetric();
    return m;
}

int count_moved(const Positions& a, const Positions& b) {
    int moved = 0;
    for (int i = 0; i < a.rows(); ++i) moved += a.row(i) != b.row(i) ? 1 : 0;
    return moved;
}

}  // namespace

// ---- empty and face-less meshes ---------------------------------------------------------------

TEST(BadInputTable, EmptyMeshIsRefused) {
    const TriangleMesh m;
    for (Operator op : meshes::kOperators)
        expect_refused(m, {}, defaults(op), {"no faces", "0 vertices", "0 faces"});
}

TEST(BadInputTable, OnlyIsolatedVerticesAreRefused) {
    TriangleMesh m;
    m.positions.resize(5, 3);
    m.positions.setRandom();
    expect_refused(m, {}, defaults(Operator::CurvatureFlow), {"no faces", "5 vertices", "0 faces"});
    // faces that all repeat an index leave no face either
    m.triangles = {{0, 0, 1}, {2, 3, 3}};
    expect_refused(m, {}, defaults(Operator::Umbrella), {"no faces", "5 vertices", "2 faces"});
}

// ---- a single triangle --------------------------------------------------------------------------

TEST(BadInputTable, SingleTriangleFixedBoundaryIsUnchanged) {
    TriangleMesh m;
    m.positions.resize(3, 3);
    m.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    m.triangles = {{0, 1, 2}};
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_TRUE(positions_bit_identical(r.positions, m.positions));
        EXPECT_EQ(r.vertices_moved, 0);
        EXPECT_EQ(r.vertices_fixed, 3);
        EXPECT_EQ(r.boundary_loops, 1);
        // Nothing could move: the user is told why.
        EXPECT_TRUE(has_warning(r, "no vertex was free to move")) << warnings(r);
    }
}

TEST(BadInputTable, SingleTriangleMovableBoundaryStaysFinite) {
    TriangleMesh m;
    m.positions.resize(3, 3);
    m.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    m.triangles = {{0, 1, 2}};
    for (Operator op : meshes::kOperators)
        for (auto mode : {fairing::BoundaryMode::SmoothCurve, fairing::BoundaryMode::VirtualVertex})
            for (auto inv : {fairing::OpenInvariant::None, fairing::OpenInvariant::Area}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << ", "
                                                << fairing::to_string(mode));
                Options o = defaults(op);
                o.boundary = mode;
                o.open_invariant = inv;
                // The curvature flow's steps flatten the triangle about its virtual vertex;
                // scaling its area back would enlarge it: refused (Run::restore).
                if (op == Operator::CurvatureFlow && inv == fairing::OpenInvariant::Area &&
                    mode == fairing::BoundaryMode::VirtualVertex) {
                    expect_refused(m, {}, o, {"flattened every component", "restoring its area"});
                    continue;
                }
                const Result r = expect_result(m, {}, o);
                if (inv == fairing::OpenInvariant::Area && !r.components.empty()) {
                    EXPECT_NEAR(r.components[0].measure_after, 0.5, 1e-9);
                }
            }
}

// ---- non-manifold input -------------------------------------------------------------------------

TEST(BadInputTable, NonManifoldEdgeIsRefusedWithCountAndFilter) {
    TriangleMesh m = bumpy_grid(6, 6);
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 2, 3);
    m.positions.row(n) << 2.5, 2.5, 3.0;
    m.positions.row(n + 1) << 3.5, 1.5, 3.0;
    // two fins on two interior edges
    m.triangles.push_back({m.triangles[14][0], m.triangles[14][1], n});
    m.triangles.push_back({m.triangles[30][1], m.triangles[30][2], n + 1});
    for (Operator op : meshes::kOperators)
        expect_refused(m, {}, defaults(op),
                       {"2 non-manifold edges", "Repair non Manifold Edges"});
}

// Two grids touching at one corner: an open bow-tie vertex.
TriangleMesh open_bowtie() {
    const TriangleMesh a = bumpy_grid(4, 4, 1), b0 = bumpy_grid(4, 4, 2);
    TriangleMesh b = meshes::translated(b0, Vec3(4, 4, 0));
    b.positions(0, 2) = a.positions(meshes::grid_index(4, 4, 4), 2);
    TriangleMesh m = meshes::merge(a, b);
    // glue b's corner (0, 0) onto a's corner (4, 4)
    const int na = static_cast<int>(a.positions.rows()), corner = meshes::grid_index(4, 4, 4);
    for (Triangle& t : m.triangles)
        for (int& v : t)
            if (v == na) v = corner;
    return m;  // vertex na is now isolated
}

TEST(BadInputTable, OpenBowTieVertexFixedBoundarySmooths) {
    const TriangleMesh m = open_bowtie();
    const int corner = meshes::grid_index(4, 4, 4);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_EQ(r.isolated_vertices, 1);
        EXPECT_GT(r.vertices_moved, 0);
        EXPECT_TRUE(r.positions.row(corner) == m.positions.row(corner));
    }
}

TEST(BadInputTable, OpenBowTieVertexVirtualVertexIsRefused) {
    const TriangleMesh m = open_bowtie();
    Options o = defaults(Operator::CurvatureFlow);
    o.boundary = fairing::BoundaryMode::VirtualVertex;
    expect_refused(m, {}, o, {"1 boundary vertex is non-manifold", "Repair non Manifold Vertices"});
}

TEST(BadInputTable, OpenBowTieVertexSmoothCurveWarns) {
    const TriangleMesh m = open_bowtie();
    Options o = defaults(Operator::ScaleDependent);
    o.boundary = fairing::BoundaryMode::SmoothCurve;
    const Result r = expect_result(m, {}, o);
    EXPECT_TRUE(has_warning(r, "1 non-manifold boundary vertex")) << warnings(r);
    const int corner = meshes::grid_index(4, 4, 4);
    EXPECT_TRUE(r.positions.row(corner) == m.positions.row(corner));
}

// Two closed spheres sharing one vertex: every edge has two faces, the shared vertex has two fans.
TEST(BadInputTable, ClosedBowTieVertexSmoothsAndKeepsVolume) {
    const TriangleMesh a = noisy_sphere(2, 1.0, 7);
    // icosahedron vertex 3 is antipodal to vertex 0: translate a copy by 2 p0 and glue them.
    const Vec3 p0 = meshes::icosphere(2).positions.row(0).transpose();
    TriangleMesh b = meshes::translated(meshes::icosphere(2), 2 * p0);
    TriangleMesh m = meshes::merge(a, b);
    const int na = static_cast<int>(a.positions.rows());
    m.positions.row(na + 3) = a.positions.row(0);
    for (Triangle& t : m.triangles)
        for (int& v : t)
            if (v == na + 3) v = 0;
    const double v0 = volume_of(m.positions, m.triangles);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_EQ(r.isolated_vertices, 1);
        ASSERT_EQ(r.components.size(), 1u);
        EXPECT_TRUE(r.components[0].closed);
        EXPECT_NEAR(volume_of(r.positions, m.triangles), v0, 1e-9 * v0);
        EXPECT_GT(r.vertices_moved, na / 2);
    }
}

// ---- degenerate faces ---------------------------------------------------------------------------

TEST(BadInputTable, ZeroAreaFacesAreCountedWithFilter) {
    TriangleMesh m = bumpy_grid(8, 6);
    const int a = meshes::grid_index(2, 2, 8), moved = meshes::grid_index(3, 2, 8);
    const int c = meshes::grid_index(3, 3, 8);
    m.positions.row(a) << 2.0, 2.0, 0.0;
    m.positions.row(c) << 3.0, 3.0, 0.0;
    m.positions.row(moved) << 2.5, 2.5, 0.0;  // on the diagonal a-c: one zero-area face
    for (Operator op : meshes::kOperators)
        for (int order : {1, 2, 3, 4}) {
            Options o = defaults(op);
            o.order = order;
            const Result r = expect_result(m, {}, o);
            EXPECT_EQ(r.zero_area_faces, 1);
            EXPECT_TRUE(has_warning(r, "1 face has zero area")) << warnings(r);
            EXPECT_TRUE(has_warning(r, "Remove Zero Area Faces")) << warnings(r);
            EXPECT_GT(r.vertices_moved, 10);
        }
}

TEST(BadInputTable, NeedleFacesSmoothOrAreExplained) {
    // Needles: a T-vertex 1e-7 (then 1e-5) edge lengths off the diagonal of its quad; the two
    // faces next to it have angles of ~1e-7 and ~pi, cotangents of ~1e7. A correct result, or a
    // refusal that names the needles and the MeshLab filters that repair them. The curvature
    // flow caps the needles' cotangents (operators.cpp), so it smooths, and says so.
    for (double off : {1e-7, 1e-5}) {
        TriangleMesh m = bumpy_grid(8, 6);
        const int a = meshes::grid_index(2, 2, 8), moved = meshes::grid_index(3, 2, 8);
        const int c = meshes::grid_index(3, 3, 8);
        m.positions.row(a) << 2.0, 2.0, 0.0;
        m.positions.row(c) << 3.0, 3.0, 0.0;
        m.positions.row(moved) << 2.5 + off, 2.5 - off, 0.0;
        for (Operator op : meshes::kOperators) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << ", offset " << off);
            const TriangleMesh before = m;
            try {
                const Result r = fairing::fair(m, {}, defaults(op));
                EXPECT_TRUE(r.positions.allFinite());
                EXPECT_EQ(r.zero_area_faces, 0);
                // the needle does not blow up its neighbourhood
                EXPECT_LT(meshes::max_row_distance(r.positions, m.positions), 2.0);
                if (op == Operator::CurvatureFlow) {
                    EXPECT_TRUE(has_warning(r, "cotangent weights were capped at 19.1")) << warnings(r);
                }
            } catch (const fairing::Error& e) {
                const std::string msg = e.what();
                EXPECT_NE(op, Operator::CurvatureFlow) << msg;
                EXPECT_TRUE(contains(msg, "did not converge") && contains(msg, "residual")) << msg;
                EXPECT_TRUE(contains(msg, "needle")) << msg;
                EXPECT_TRUE(contains(msg, "Remove T-Vertices by Edge Flip")) << msg;
            }
            EXPECT_TRUE(bit_identical(m, before));
        }
    }
}

TEST(BadInputTable, EveryFaceDegenerateLeavesMeshUnchanged) {
    // All faces collinear: no face has area, every vertex is massless.
    TriangleMesh m;
    m.positions.resize(4, 3);
    m.positions << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0;
    m.triangles = {{0, 1, 2}, {1, 3, 2}};
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_EQ(r.zero_area_faces, 2);
        EXPECT_TRUE(positions_bit_identical(r.positions, m.positions));
    }
}

// ---- duplicated vertices and faces ---------------------------------------------------------------

TEST(BadInputTable, CoincidentReferencedVerticesAreFlooredAndWarned) {
    // Two neighbours at the same position (duplicated vertices, both referenced): a zero-length
    // edge and two zero-area faces, handled and warned with the repair filter.
    TriangleMesh m = bumpy_grid(6, 6);
    const int v = meshes::grid_index(3, 3, 6), w = meshes::grid_index(4, 3, 6);
    m.positions.row(w) = m.positions.row(v);  // edge v-w has length 0
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        // 1/|e| is bounded (scale-dependent); the cotangent operator skips the flat faces
        if (op == Operator::ScaleDependent) {
            EXPECT_TRUE(has_warning(r, "1 edge is shorter than 0.01 % of the mean edge"))
                << warnings(r);
            EXPECT_TRUE(has_warning(r, "Merge Close Vertices")) << warnings(r);
        }
        EXPECT_EQ(r.zero_area_faces, 2);
        EXPECT_TRUE(has_warning(r, "2 faces have zero area")) << warnings(r);
    }
}

TEST(BadInputTable, TriangleSoupMovesNothingAndSaysWhy) {
    // STL-like soup: every face has its own three vertices (duplicated vertices).
    const TriangleMesh s = noisy_sphere(1);
    TriangleMesh m;
    m.positions.resize(3 * static_cast<int>(s.triangles.size()), 3);
    for (std::size_t f = 0; f < s.triangles.size(); ++f) {
        for (int k = 0; k < 3; ++k)
            m.positions.row(3 * static_cast<int>(f) + k) = s.positions.row(s.triangles[f][k]);
        const int b = 3 * static_cast<int>(f);
        m.triangles.push_back({b, b + 1, b + 2});
    }
    const Result r = expect_result(m, {}, defaults(Operator::CurvatureFlow));
    EXPECT_EQ(r.vertices_moved, 0);
    EXPECT_EQ(r.components.size(), s.triangles.size());
    EXPECT_TRUE(has_warning(r, "no vertex was free to move")) << warnings(r);
    EXPECT_TRUE(has_warning(r, "Remove Duplicate Vertices")) << warnings(r);
}

TEST(BadInputTable, DuplicatedFacesAreRefusedWithFilter) {
    TriangleMesh m = noisy_sphere(2);
    m.triangles.push_back(m.triangles[3]);
    const Triangle t = m.triangles[9];
    m.triangles.push_back({t[1], t[0], t[2]});  // same vertices, opposite orientation
    for (Operator op : meshes::kOperators)
        expect_refused(m, {}, defaults(op), {"2 duplicated faces", "Remove Duplicate Faces"});
}

TEST(BadInputTable, UnreferencedDuplicateVerticesAreLeftOut) {
    TriangleMesh m = noisy_sphere(2);
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 3, 3);
    for (int k = 0; k < 3; ++k) m.positions.row(n + k) = m.positions.row(5 * k);
    const Result r = expect_result(m, {}, defaults(Operator::Umbrella));
    EXPECT_EQ(r.isolated_vertices, 3);
    EXPECT_TRUE(has_warning(r, "3 isolated vertices")) << warnings(r);
    EXPECT_TRUE(has_warning(r, "Remove Unreferenced Vertices")) << warnings(r);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(r.positions.row(n + k) == m.positions.row(n + k));
}

// ---- non-finite coordinates -----------------------------------------------------------------------

TEST(BadInputTable, NonFiniteCoordinatesAreRefusedWithCountAndFilter) {
    for (double bad : {kNaN, kInf, -kInf}) {
        TriangleMesh m = noisy_sphere(2);
        m.positions(10, 1) = bad;
        m.positions(20, 0) = bad;
        m.positions(20, 2) = bad;
        for (Operator op : meshes::kOperators)
            expect_refused(m, {}, defaults(op),
                           {"2 vertices have non-finite coordinates", "Conditional Vertex Selection",
                            "Delete Selected Vertices"});
    }
    // a non-finite isolated vertex is refused as well: the result would carry it
    TriangleMesh m = noisy_sphere(2);
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 1, 3);
    m.positions.row(n) << kNaN, 0, 0;
    expect_refused(m, {}, defaults(Operator::Umbrella), {"1 vertex has non-finite coordinates"});
}

// ---- orientation -----------------------------------------------------------------------------

TEST(BadInputTable, InconsistentOrientationIsWarnedWithFilter) {
    TriangleMesh m = noisy_sphere(2);
    std::swap(m.triangles[5][0], m.triangles[5][1]);
    std::swap(m.triangles[50][0], m.triangles[50][1]);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_EQ(r.inconsistent_edges, 6);
        ASSERT_EQ(r.components.size(), 1u);
        EXPECT_FALSE(r.components[0].closed);
        EXPECT_TRUE(has_warning(r, "6 edges join")) << warnings(r);
        EXPECT_TRUE(has_warning(r, "Re-Orient all faces coherentely")) << warnings(r);
    }
}

// ---- open meshes and several components ------------------------------------------------------------

TEST(BadInputTable, SeveralComponentsKeepTheirOwnVolume) {
    const TriangleMesh a = noisy_sphere(2, 1.0, 8);
    const TriangleMesh b = meshes::translated(noisy_sphere(2, 0.3, 9), Vec3(5, 0, 0));
    const TriangleMesh g = meshes::translated(bumpy_grid(6, 6), Vec3(-10, 0, 0));
    const TriangleMesh m = meshes::merge(meshes::merge(a, b), g);
    const std::vector<Triangle> ta = a.triangles;
    std::vector<Triangle> tb;
    const int na = static_cast<int>(a.positions.rows());
    for (Triangle t : b.triangles) tb.push_back({t[0] + na, t[1] + na, t[2] + na});
    const double va = volume_of(m.positions, ta), vb = volume_of(m.positions, tb);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        ASSERT_EQ(r.components.size(), 3u);
        EXPECT_NEAR(volume_of(r.positions, ta), va, 1e-10 * va);
        EXPECT_NEAR(volume_of(r.positions, tb), vb, 1e-10 * vb);
        EXPECT_TRUE(has_warning(r, "1 open component encloses no volume")) << warnings(r);
        int closed = 0;
        for (const auto& c : r.components) closed += c.closed ? 1 : 0;
        EXPECT_EQ(closed, 2);
    }
}

TEST(BadInputTable, OpenMeshKeepsAreaWhenAsked) {
    const TriangleMesh m = bumpy_grid(8, 8);
    for (Operator op : meshes::kOperators) {
        Options o = defaults(op);
        o.open_invariant = fairing::OpenInvariant::Area;
        o.boundary = fairing::BoundaryMode::SmoothCurve;
        const Result r = expect_result(m, {}, o);
        ASSERT_EQ(r.components.size(), 1u);
        EXPECT_NEAR(meshes::area(r.positions, m.triangles), meshes::area(m.positions, m.triangles),
                    1e-9 * meshes::area(m.positions, m.triangles));
    }
}

// ---- selections (hard constraints) -----------------------------------------------------------------

TEST(BadInputTable, AllSelectedIsLikeNoSelection) {
    const TriangleMesh m = noisy_sphere(2);
    fairing::Constraints all;
    all.fixed.assign(m.positions.rows(), 0);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, all, defaults(op));
        const Result ref = expect_result(m, {}, defaults(op));
        EXPECT_TRUE(positions_bit_identical(r.positions, ref.positions));
    }
}

TEST(BadInputTable, NoneSelectedLeavesMeshUnchangedAndSaysWhy) {
    const TriangleMesh m = noisy_sphere(2);
    fairing::Constraints none;
    none.fixed.assign(m.positions.rows(), 1);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, none, defaults(op));
        EXPECT_TRUE(positions_bit_identical(r.positions, m.positions));
        EXPECT_EQ(r.vertices_moved, 0);
        EXPECT_TRUE(has_warning(r, "no vertex was free to move")) << warnings(r);
    }
}

TEST(BadInputTable, OneSelectedVertexMovesAlone) {
    const TriangleMesh m = noisy_sphere(2);
    fairing::Constraints one;
    one.fixed.assign(m.positions.rows(), 1);
    one.fixed[17] = 0;
    for (Operator op : meshes::kOperators) {
        for (bool volume : {false, true}) {
            Options o = defaults(op);
            o.preserve_volume = volume;
            const Result r = expect_result(m, one, o);
            EXPECT_EQ(count_moved(r.positions, m.positions), 1);
            EXPECT_TRUE(r.positions.row(17) != m.positions.row(17));
            if (volume) {
                EXPECT_NEAR(volume_of(r.positions, m.triangles), volume_of(m.positions, m.triangles),
                            1e-9);
            }
        }
    }
}

// ---- per-vertex weights (what the adapter makes of vertex quality) ------------------------------------

TEST(BadInputTable, WeightsNaNNegativeOrAboveOneAreRefusedWithCount) {
    const TriangleMesh m = noisy_sphere(2);
    for (double w : {kNaN, -0.5, 1.5, kInf}) {
        fairing::Constraints c;
        c.weights.assign(m.positions.rows(), 0.5);
        c.weights[3] = w;
        c.weights[4] = w;
        expect_refused(m, c, defaults(Operator::Umbrella),
                       {"2 vertex weights are outside [0, 1] or not a number"});
    }
}

TEST(BadInputTable, WeightsAtTheEndsOfTheRange) {
    const TriangleMesh m = noisy_sphere(2);
    fairing::Constraints c;
    c.weights.assign(m.positions.rows(), 1.0);
    for (int i = 0; i < m.positions.rows(); i += 2) c.weights[i] = 0.0;
    const Result r = expect_result(m, c, defaults(Operator::CurvatureFlow));
    for (int i = 0; i < m.positions.rows(); i += 2)
        EXPECT_TRUE(r.positions.row(i) == m.positions.row(i)) << "weight-0 vertex " << i << " moved";
    EXPECT_GT(r.vertices_moved, 0);
}

// ---- time step, tolerance, iteration cap ----------------------------------------------------------

TEST(BadInputTable, TimeStepZeroIsANoOp) {
    const TriangleMesh m = noisy_sphere(2);
    for (Operator op : meshes::kOperators) {
        Options o = defaults(op);
        o.time_step = 0;
        const Result r = expect_result(m, {}, o);
        EXPECT_TRUE(positions_bit_identical(r.positions, m.positions));
        EXPECT_EQ(r.steps, 0);
    }
}

TEST(BadInputTable, NegativeOrNonFiniteTimeStepIsRefused) {
    const TriangleMesh m = noisy_sphere(2);
    for (double t : {-1.0, -1e-300, kNaN, kInf}) {
        Options o = defaults(Operator::Umbrella);
        o.time_step = t;
        expect_refused(m, {}, o, {"time step must be a finite number >= 0"});
    }
}

TEST(BadInputTable, HugeTimeStepConvergesOrIsReported) {
    // 1e12: implicit steps are stable; the volume is kept. If a solve cannot reach the tolerance
    // the refusal reports the residual.
    const TriangleMesh m = noisy_sphere(2);
    const double v0 = volume_of(m.positions, m.triangles);
    for (Operator op : meshes::kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = defaults(op);
            o.order = order;
            o.time_step = 1e12;
            try {
                const Result r = fairing::fair(m, {}, o);
                EXPECT_TRUE(r.positions.allFinite());
                EXPECT_NEAR(volume_of(r.positions, m.triangles), v0, 1e-9 * v0);
                EXPECT_LT(meshes::bbox_diagonal(r.positions), 10.0);
            } catch (const fairing::Error& e) {
                const std::string msg = e.what();
                EXPECT_TRUE(contains(msg, "did not converge") && contains(msg, "residual")) << msg;
            }
        }
}

TEST(BadInputTable, ToleranceZeroIsRefused) {
    const TriangleMesh m = noisy_sphere(2);
    for (double tol : {0.0, -1e-8, kNaN}) {
        Options o = defaults(Operator::CurvatureFlow);
        o.tolerance = tol;
        expect_refused(m, {}, o, {"solver tolerance must be a finite number > 0"});
    }
}

TEST(BadInputTable, IterationCapBelowOneIsRefused) {
    const TriangleMesh m = noisy_sphere(2);
    Options o = defaults(Operator::Umbrella);
    o.max_iterations = 0;
    expect_refused(m, {}, o, {"iteration cap must be at least 1 (got 0)"});
}

// ---- extreme coordinates ------------------------------------------------------------------------

TEST(BadInputTable, CoordinatesAround1e7GiveTheSameResult) {
    const TriangleMesh m = noisy_sphere(3);
    const Vec3 far(1e7, -2e7, 3e7);
    const TriangleMesh shifted = meshes::translated(m, far);
    for (Operator op : meshes::kOperators) {
        const Result ref = expect_result(m, {}, defaults(op));
        const Result r = expect_result(shifted, {}, defaults(op));
        Positions back = r.positions;
        for (int i = 0; i < back.rows(); ++i) back.row(i) -= far.transpose();
        // double spacing at 3e7 is 4e-9; the sphere has radius 1
        EXPECT_LT(meshes::max_row_distance(back, ref.positions), 1e-6);
        EXPECT_GT(r.vertices_moved, static_cast<int>(m.positions.rows()) / 2);
    }
}

TEST(BadInputTable, CoordinatesAround1e7WithRadius1e3) {
    // as a float host stores it: a sphere of radius 1000 centred at 1e7
    const TriangleMesh m = meshes::translated(noisy_sphere(3, 1e3), Vec3(1e7, 1e7, 1e7));
    const double v0 = volume_of(m.positions, m.triangles);
    for (Operator op : meshes::kOperators) {
        const Result r = expect_result(m, {}, defaults(op));
        EXPECT_NEAR(volume_of(r.positions, m.triangles), v0, 1e-9 * v0);
    }
}

TEST(BadInputTable, CoordinatesAround1e7MinusGiveTheSameResultScaled) {
    const TriangleMesh m = noisy_sphere(3);
    const TriangleMesh tiny = meshes::scaled(m, 1e-7);
    for (Operator op : meshes::kOperators) {
        const Result ref = expect_result(m, {}, defaults(op));
        const Result r = expect_result(tiny, {}, defaults(op));
        EXPECT_LT(meshes::max_row_distance(r.positions / 1e-7, ref.positions), 1e-7);
        EXPECT_NEAR(volume_of(r.positions, m.triangles) / volume_of(tiny.positions, m.triangles),
                    1.0, 1e-9);
    }
}
