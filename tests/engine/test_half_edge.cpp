// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Half-edge view (half_edge.h): connectivity invariants, boundary loops, components,
// orientation consistency and the validation report.
#include "meshes.h"

#include "fairing/half_edge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

using fairing::HalfEdgeMesh;
using fairing::Triangle;
using fairing::TriangleMesh;

namespace {

HalfEdgeMesh build(const TriangleMesh& m) { return HalfEdgeMesh::build(m.positions, m.triangles); }

// Invariants that hold on every mesh whose faces agree on orientation.
void expect_consistent_connectivity(const HalfEdgeMesh& he) {
    for (int h = 0; h < he.num_half_edges(); ++h) {
        ASSERT_EQ(HalfEdgeMesh::face(h), h / 3);
        ASSERT_EQ(HalfEdgeMesh::next(HalfEdgeMesh::prev(h)), h);
        ASSERT_EQ(HalfEdgeMesh::next(HalfEdgeMesh::next(HalfEdgeMesh::next(h))), h);
        ASSERT_EQ(he.to(h), he.from(HalfEdgeMesh::next(h)));
        ASSERT_EQ(he.opposite_vertex(h), he.to(HalfEdgeMesh::next(h)));
        const int t = he.twin(h);
        if (t < 0) continue;
        ASSERT_EQ(he.twin(t), h) << "twin(twin(h)) != h at h = " << h;
        ASSERT_NE(HalfEdgeMesh::face(t), HalfEdgeMesh::face(h));
        ASSERT_EQ(he.from(t), he.to(h)) << "h = " << h;
        ASSERT_EQ(he.to(t), he.from(h)) << "h = " << h;
    }
    for (int v = 0; v < he.num_vertices(); ++v) {
        const int h = he.outgoing(v);
        if (h < 0) continue;
        ASSERT_LT(h, he.num_half_edges());
        ASSERT_EQ(he.from(h), v) << "outgoing(v) does not leave v, v = " << v;
    }
}

}  // namespace

TEST(HalfEdge, FaceCornerConvention) {
    TriangleMesh m;
    m.positions.resize(4, 3);
    m.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
    m.triangles = {{0, 1, 2}, {1, 3, 2}};
    const HalfEdgeMesh he = build(m);
    ASSERT_EQ(he.num_faces(), 2);
    ASSERT_EQ(he.num_half_edges(), 6);
    // h = 3f + k runs from faces[f][k] to faces[f][(k+1)%3], opposite corner (k+2)%3.
    EXPECT_EQ(he.from(3 * 1 + 0), 1);
    EXPECT_EQ(he.to(3 * 1 + 0), 3);
    EXPECT_EQ(he.opposite_vertex(3 * 1 + 0), 2);
    EXPECT_EQ(HalfEdgeMesh::next(5), 3);
    EXPECT_EQ(HalfEdgeMesh::prev(3), 5);
    // The only interior edge is 1-2: half-edge 1 (1->2) of face 0 and 5 (2->1) of face 1.
    EXPECT_EQ(he.twin(1), 5);
    EXPECT_EQ(he.twin(5), 1);
    for (int h : {0, 2, 3, 4}) EXPECT_TRUE(he.is_boundary(h)) << h;
    expect_consistent_connectivity(he);
}

TEST(HalfEdge, ClosedTorusInvariants) {
    const int n = 12;
    const TriangleMesh m = meshes::torus_grid(n, n);
    const HalfEdgeMesh he = build(m);
    ASSERT_EQ(he.num_vertices(), n * n);
    ASSERT_EQ(he.num_faces(), 2 * n * n);
    expect_consistent_connectivity(he);
    for (int h = 0; h < he.num_half_edges(); ++h) ASSERT_GE(he.twin(h), 0);
    for (int v = 0; v < he.num_vertices(); ++v) {
        EXPECT_FALSE(he.is_boundary_vertex(v));
        EXPECT_FALSE(he.is_isolated(v));
    }
    EXPECT_TRUE(he.boundary_loops().empty());
    ASSERT_EQ(he.components().size(), 1u);
    EXPECT_TRUE(he.components()[0].closed());
    EXPECT_EQ(static_cast<int>(he.components()[0].vertices.size()), n * n);
    EXPECT_EQ(static_cast<int>(he.components()[0].faces.size()), 2 * n * n);
    const auto& r = he.report();
    EXPECT_EQ(r.dropped_faces, 0);
    EXPECT_EQ(r.isolated_vertices, 0);
    EXPECT_EQ(r.zero_area_faces, 0);
    EXPECT_EQ(r.inconsistent_edges, 0);
    EXPECT_EQ(r.nonmanifold_vertices, 0);
}

TEST(HalfEdge, SphereIsClosedGridIsNot) {
    const HalfEdgeMesh sphere = build(meshes::icosphere(2));
    expect_consistent_connectivity(sphere);
    ASSERT_EQ(sphere.components().size(), 1u);
    EXPECT_TRUE(sphere.components()[0].closed());
    EXPECT_FALSE(sphere.components()[0].has_boundary);

    const HalfEdgeMesh grid = build(meshes::grid(5, 4));
    expect_consistent_connectivity(grid);
    ASSERT_EQ(grid.components().size(), 1u);
    EXPECT_TRUE(grid.components()[0].has_boundary);
    EXPECT_TRUE(grid.components()[0].consistently_oriented);
    EXPECT_FALSE(grid.components()[0].closed());
}

TEST(HalfEdge, GridBoundaryLoopAndOutgoing) {
    const int nx = 6, ny = 4;
    meshes::Rng rng(1);
    const TriangleMesh m = meshes::grid(nx, ny, 1.0, 1.0, &rng);
    const HalfEdgeMesh he = build(m);
    expect_consistent_connectivity(he);

    std::set<int> expected_boundary;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            if (i == 0 || j == 0 || i == nx || j == ny)
                expected_boundary.insert(meshes::grid_index(i, j, nx));

    ASSERT_EQ(he.boundary_loops().size(), 1u);
    const std::vector<int>& loop = he.boundary_loops()[0];
    ASSERT_EQ(loop.size(), expected_boundary.size());  // 2 (nx + ny) vertices
    EXPECT_EQ(std::set<int>(loop.begin(), loop.end()), expected_boundary);

    // Consecutive loop vertices (and last, first) share a boundary half-edge.
    std::set<std::pair<int, int>> boundary_edges;
    for (int h = 0; h < he.num_half_edges(); ++h)
        if (he.is_boundary(h)) boundary_edges.insert({he.from(h), he.to(h)});
    EXPECT_EQ(boundary_edges.size(), expected_boundary.size());
    for (size_t k = 0; k < loop.size(); ++k) {
        const int a = loop[k], b = loop[(k + 1) % loop.size()];
        EXPECT_TRUE(boundary_edges.count({a, b}) || boundary_edges.count({b, a}))
            << a << " - " << b << " is not a boundary edge";
    }

    for (int v = 0; v < he.num_vertices(); ++v) {
        const bool on_boundary = expected_boundary.count(v) > 0;
        EXPECT_EQ(he.is_boundary_vertex(v), on_boundary) << "v = " << v;
        ASSERT_GE(he.outgoing(v), 0);
        EXPECT_EQ(he.from(he.outgoing(v)), v);
        // For a boundary vertex outgoing(v) is the boundary half-edge leaving it.
        if (on_boundary) {
            EXPECT_TRUE(he.is_boundary(he.outgoing(v))) << "v = " << v;
        }
    }
}

TEST(HalfEdge, AnnulusHasTwoBoundaryLoops) {
    // 8x8 grid with the central 2x2 cells removed: an outer loop of 32 vertices and an inner
    // loop of 8 vertices.
    const int n = 8;
    TriangleMesh m = meshes::grid(n, n);
    std::vector<Triangle> kept;
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const int cell = static_cast<int>(f) / 2, i = cell % n, j = cell / n;
        if (i >= 3 && i <= 4 && j >= 3 && j <= 4) continue;
        kept.push_back(m.triangles[f]);
    }
    m.triangles = kept;
    const HalfEdgeMesh he = build(m);
    expect_consistent_connectivity(he);
    ASSERT_EQ(he.boundary_loops().size(), 2u);
    std::vector<size_t> sizes = {he.boundary_loops()[0].size(), he.boundary_loops()[1].size()};
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes[0], 8u);
    EXPECT_EQ(sizes[1], 32u);
    ASSERT_EQ(he.components().size(), 1u);
    EXPECT_FALSE(he.components()[0].closed());
}

TEST(HalfEdge, ComponentsOfDisjointMeshes) {
    const TriangleMesh a = meshes::icosphere(1);
    const TriangleMesh b = meshes::translated(meshes::grid(3, 3), meshes::Vec3(5, 0, 0));
    const TriangleMesh c = meshes::translated(meshes::box(2), meshes::Vec3(-5, 0, 0));
    const TriangleMesh m = meshes::merge(meshes::merge(a, b), c);
    const HalfEdgeMesh he = build(m);
    expect_consistent_connectivity(he);
    ASSERT_EQ(he.components().size(), 3u);

    const int na = static_cast<int>(a.positions.rows()), nb = static_cast<int>(b.positions.rows());
    int closed = 0, faces = 0, vertices = 0;
    for (size_t k = 0; k < he.components().size(); ++k) {
        const fairing::Component& comp = he.components()[k];
        closed += comp.closed() ? 1 : 0;
        faces += static_cast<int>(comp.faces.size());
        vertices += static_cast<int>(comp.vertices.size());
        // All of a component's vertices come from the same input mesh, and map back to it.
        const int first = comp.vertices.front();
        const int group = first < na ? 0 : (first < na + nb ? 1 : 2);
        for (int v : comp.vertices) {
            EXPECT_EQ(v < na ? 0 : (v < na + nb ? 1 : 2), group);
            EXPECT_EQ(he.component_of_vertex()[v], static_cast<int>(k));
        }
        EXPECT_EQ(comp.closed(), group != 1);
    }
    EXPECT_EQ(closed, 2);
    EXPECT_EQ(faces, static_cast<int>(m.triangles.size()));
    EXPECT_EQ(vertices, static_cast<int>(m.positions.rows()));
}

TEST(HalfEdge, FlippedFaceMakesComponentInconsistent) {
    // Two spheres; one face of the first one is flipped. Its three edges become inconsistent,
    // the twins still pair, and that component (only that one) is no longer closed.
    TriangleMesh a = meshes::icosphere(1);
    const int na = static_cast<int>(a.positions.rows());
    std::swap(a.triangles[7][1], a.triangles[7][2]);
    const TriangleMesh m =
        meshes::merge(a, meshes::icosphere(1, 0.5, meshes::Vec3(4, 0, 0)));
    const HalfEdgeMesh he = build(m);
    EXPECT_EQ(he.report().inconsistent_edges, 3);
    for (int h = 0; h < he.num_half_edges(); ++h) {
        ASSERT_GE(he.twin(h), 0) << "a closed mesh has no boundary even when inconsistent";
        ASSERT_EQ(he.twin(he.twin(h)), h);
        // The same undirected edge, whatever the orientation.
        const std::set<int> e1 = {he.from(h), he.to(h)};
        const std::set<int> e2 = {he.from(he.twin(h)), he.to(he.twin(h))};
        ASSERT_EQ(e1, e2);
    }
    ASSERT_EQ(he.components().size(), 2u);
    for (const fairing::Component& comp : he.components()) {
        EXPECT_FALSE(comp.has_boundary);
        const bool flipped_one = comp.vertices.front() < na;
        EXPECT_EQ(comp.consistently_oriented, !flipped_one);
        EXPECT_EQ(comp.closed(), !flipped_one);
    }
}

TEST(HalfEdge, IsolatedVertexAndDroppedFace) {
    TriangleMesh m = meshes::grid(3, 3);
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 1, 3);
    m.positions.row(n) << 7, 7, 7;                   // referenced by no face
    m.triangles.insert(m.triangles.begin() + 2, Triangle{0, 0, 1});  // repeated index
    const HalfEdgeMesh he = build(m);
    EXPECT_EQ(he.report().isolated_vertices, 1);
    EXPECT_EQ(he.report().dropped_faces, 1);
    EXPECT_TRUE(he.is_isolated(n));
    EXPECT_EQ(he.outgoing(n), -1);
    EXPECT_EQ(he.component_of_vertex()[n], -1);
    ASSERT_EQ(he.num_faces(), static_cast<int>(m.triangles.size()) - 1);
    ASSERT_EQ(he.input_face().size(), he.faces().size());
    for (int f = 0; f < he.num_faces(); ++f) {
        const int g = he.input_face()[f];
        EXPECT_NE(g, 2);
        EXPECT_EQ(he.faces()[f], m.triangles[g]);
    }
    expect_consistent_connectivity(he);
}

// fair() frees the pairing before its solves (HalfEdgeMesh::release_pairing); what the solves,
// the volume restoration and the report read afterwards must stay as built.
TEST(HalfEdge, ReleasingThePairingKeepsEverythingElse) {
    const TriangleMesh m = meshes::merge(meshes::grid(5, 4), meshes::icosphere(2));
    const HalfEdgeMesh built = build(m);
    HalfEdgeMesh he = built;
    he.release_pairing();
    EXPECT_TRUE(he.input_face().empty());
    ASSERT_EQ(he.num_vertices(), built.num_vertices());
    EXPECT_EQ(he.faces(), built.faces());
    EXPECT_EQ(he.boundary_loops(), built.boundary_loops());
    EXPECT_EQ(he.boundary_loop_edges(), built.boundary_loop_edges());
    EXPECT_EQ(he.component_of_vertex(), built.component_of_vertex());
    ASSERT_EQ(he.components().size(), built.components().size());
    for (std::size_t c = 0; c < he.components().size(); ++c) {
        EXPECT_EQ(he.components()[c].vertices, built.components()[c].vertices);
        EXPECT_EQ(he.components()[c].faces, built.components()[c].faces);
        EXPECT_EQ(he.components()[c].closed(), built.components()[c].closed());
    }
    for (int v = 0; v < he.num_vertices(); ++v) {
        EXPECT_EQ(he.outgoing(v), built.outgoing(v));
        EXPECT_EQ(he.is_boundary_vertex(v), built.is_boundary_vertex(v));
    }
}

TEST(HalfEdge, BowTieVertexIsReported) {
    // Two triangles sharing only vertex 0: vertex 0 has four boundary edges.
    TriangleMesh m;
    m.positions.resize(5, 3);
    m.positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
    m.triangles = {{0, 1, 2}, {0, 3, 4}};
    const HalfEdgeMesh he = build(m);
    EXPECT_EQ(he.report().nonmanifold_vertices, 1);
    ASSERT_EQ(he.nonmanifold_vertices().size(), 1u);
    EXPECT_EQ(he.nonmanifold_vertices()[0], 0);
    EXPECT_TRUE(he.is_boundary_vertex(0));
    expect_consistent_connectivity(he);
}

TEST(HalfEdge, ZeroAreaFaceIsCounted) {
    // Vertex (2,1) of a 4x3 integer grid moved to (1.5, 1.5), exactly on the diagonal
    // (1,1)-(2,2) of the triangle (1,1) (2,1) (2,2): that triangle is degenerate, the others not.
    TriangleMesh m = meshes::grid(4, 3, 4.0, 3.0);
    m.positions.row(meshes::grid_index(2, 1, 4)) << 1.5, 1.5, 0.0;
    const HalfEdgeMesh he = build(m);
    EXPECT_EQ(he.report().zero_area_faces, 1);
}

TEST(HalfEdge, BuildRejectsBadInput) {
    TriangleMesh m = meshes::icosphere(1);
    {
        TriangleMesh bad = m;
        bad.triangles[3][1] = static_cast<int>(bad.positions.rows());
        EXPECT_THROW(build(bad), fairing::Error);
        bad.triangles[3][1] = -1;
        EXPECT_THROW(build(bad), fairing::Error);
    }
    {
        TriangleMesh bad = m;
        bad.positions(4, 2) = std::nan("");
        EXPECT_THROW(build(bad), fairing::Error);
    }
    {
        // A fin: a third face on the edge of faces 0 and its neighbour.
        TriangleMesh bad = m;
        const int n = static_cast<int>(bad.positions.rows());
        bad.positions.conservativeResize(n + 1, 3);
        bad.positions.row(n) << 3, 3, 3;
        bad.triangles.push_back({m.triangles[0][0], m.triangles[0][1], n});
        EXPECT_THROW(build(bad), fairing::Error);
    }
}

namespace {

// Above detail::kParallelRows vertices, with everything the build has to find: holes (some of
// them bow-ties), faces of flipped orientation, a face repeating a vertex, a zero-area face, an
// isolated vertex and a second component.
TriangleMesh large_untidy_mesh() {
    TriangleMesh sphere = meshes::radial_noise(meshes::icosphere(7), 0.002);
    std::vector<Triangle> kept;
    for (std::size_t f = 0; f < sphere.triangles.size(); ++f) {
        if (f % 97 == 0 || f % 1013 == 5) continue;
        Triangle t = sphere.triangles[f];
        if (f % 5003 == 7) std::swap(t[0], t[1]);
        if (f % 7919 == 3) t[2] = t[0];
        kept.push_back(t);
    }
    sphere.triangles = kept;
    const Triangle& flat = sphere.triangles[100];  // its edge (0, 1) collapses
    sphere.positions.row(flat[0]) = sphere.positions.row(flat[1]);
    TriangleMesh m = meshes::merge(sphere, meshes::grid(30, 20));
    const int n = static_cast<int>(m.positions.rows());
    m.positions.conservativeResize(n + 1, 3);
    m.positions.row(n) << 5, 5, 5;
    return m;
}

void expect_same_mesh(const HalfEdgeMesh& a, const HalfEdgeMesh& b) {
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_faces(), b.num_faces());
    EXPECT_EQ(a.faces(), b.faces());
    EXPECT_EQ(a.input_face(), b.input_face());
    for (int h = 0; h < a.num_half_edges(); ++h) ASSERT_EQ(a.twin(h), b.twin(h)) << "h = " << h;
    for (int v = 0; v < a.num_vertices(); ++v) {
        ASSERT_EQ(a.outgoing(v), b.outgoing(v)) << "v = " << v;
        ASSERT_EQ(a.is_boundary_vertex(v), b.is_boundary_vertex(v)) << "v = " << v;
    }
    EXPECT_EQ(a.boundary_loops(), b.boundary_loops());
    EXPECT_EQ(a.boundary_loop_edges(), b.boundary_loop_edges());
    EXPECT_EQ(a.component_of_vertex(), b.component_of_vertex());
    EXPECT_EQ(a.nonmanifold_vertices(), b.nonmanifold_vertices());
    ASSERT_EQ(a.components().size(), b.components().size());
    for (std::size_t c = 0; c < a.components().size(); ++c) {
        EXPECT_EQ(a.components()[c].vertices, b.components()[c].vertices);
        EXPECT_EQ(a.components()[c].faces, b.components()[c].faces);
        EXPECT_EQ(a.components()[c].has_boundary, b.components()[c].has_boundary);
        EXPECT_EQ(a.components()[c].consistently_oriented, b.components()[c].consistently_oriented);
    }
    const fairing::ValidationReport& ra = a.report();
    const fairing::ValidationReport& rb = b.report();
    EXPECT_EQ(ra.dropped_faces, rb.dropped_faces);
    EXPECT_EQ(ra.isolated_vertices, rb.isolated_vertices);
    EXPECT_EQ(ra.zero_area_faces, rb.zero_area_faces);
    EXPECT_EQ(ra.inconsistent_edges, rb.inconsistent_edges);
    EXPECT_EQ(ra.nonmanifold_vertices, rb.nonmanifold_vertices);
}

std::string build_error(const TriangleMesh& m, int threads) {
    try {
        HalfEdgeMesh::build(m.positions, m.triangles, threads);
    } catch (const fairing::Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// The build splits its passes over threads on large meshes; the result must not depend on it.
TEST(HalfEdge, SameMeshOnAnyNumberOfThreads) {
    const TriangleMesh m = large_untidy_mesh();
    const HalfEdgeMesh one = HalfEdgeMesh::build(m.positions, m.triangles, 1);
    const fairing::ValidationReport& r = one.report();
    EXPECT_GT(r.dropped_faces, 0);
    EXPECT_EQ(r.isolated_vertices, 1);
    EXPECT_GT(r.zero_area_faces, 0);
    EXPECT_GT(r.inconsistent_edges, 0);
    EXPECT_GT(r.nonmanifold_vertices, 0);
    EXPECT_GT(one.boundary_loops().size(), 10u);
    EXPECT_EQ(one.components().size(), 2u);
    for (int threads : {2, 3, 0}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        expect_same_mesh(one, HalfEdgeMesh::build(m.positions, m.triangles, threads));
    }
}

// The same errors, with the same counts, in the same order of precedence.
TEST(HalfEdge, SameErrorsOnAnyNumberOfThreads) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(7), 0.002);
    const int n = static_cast<int>(m.positions.rows());
    std::vector<TriangleMesh> bad(4, m);
    bad[0].triangles[10][1] = n;                   // out of range (and a NaN: reported second)
    bad[0].triangles[99999][2] = -1;
    bad[0].positions(7, 0) = std::nan("");
    bad[1].positions(7, 0) = INFINITY;             // non-finite
    bad[2].triangles.push_back(m.triangles[500]);  // duplicated face
    bad[3].positions.conservativeResize(n + 1, 3);  // non-manifold edge (a fin)
    bad[3].positions.row(n) << 3, 3, 3;
    bad[3].triangles.push_back({m.triangles[0][0], m.triangles[0][1], n});
    for (const TriangleMesh& b : bad) {
        const std::string one = build_error(b, 1);
        EXPECT_FALSE(one.empty());
        EXPECT_EQ(build_error(b, 2), one);
    }
    EXPECT_NE(build_error(bad[0], 2).find("2 face corners"), std::string::npos);
}
