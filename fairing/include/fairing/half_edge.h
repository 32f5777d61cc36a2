// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Compact, array-based half-edge view of an indexed triangle mesh, built once per run. Building
// it is where the input is validated.
//
// Conventions:
// - Half-edge h = 3f + k is corner k of face f; it runs from faces[f][k] to faces[f][(k+1)%3],
//   and the corner opposite to it is (k+2)%3. next(h) = 3f + (k+1)%3.
// - twin(h) is the other half-edge of the same undirected edge, -1 on a boundary. When the two
//   faces of an edge disagree on orientation, twin still pairs them and the edge is counted in
//   ValidationReport::inconsistent_edges (the operators do not depend on orientation; the
//   volume does, so such a component is not "closed").
// - outgoing(v) is a half-edge leaving v, the boundary one for a boundary vertex where one
//   leaves it, -1 for an isolated vertex.
// - Faces that repeat a vertex index are dropped before anything else (counted); `faces` holds
//   the kept ones, `input_face` maps them back.
#pragma once

#include "fairing/types.h"

#include <vector>

namespace fairing {

struct ValidationReport {
    int dropped_faces = 0;        // repeated vertex index within a face
    int isolated_vertices = 0;    // referenced by no kept face
    int zero_area_faces = 0;      // area below 1e-12 of the squared longest edge
    int inconsistent_edges = 0;   // two faces traverse the edge in the same direction
    int nonmanifold_vertices = 0; // boundary vertices with more than two boundary edges
};

struct Component {
    std::vector<int> vertices;
    std::vector<int> faces;
    bool has_boundary = false;
    bool consistently_oriented = true;
    bool closed() const { return !has_boundary && consistently_oriented; }
};

class HalfEdgeMesh {
public:
    int num_vertices() const { return static_cast<int>(outgoing_.size()); }
    int num_faces() const { return static_cast<int>(faces_.size()); }
    int num_half_edges() const { return 3 * num_faces(); }

    static int face(int h) { return h / 3; }
    static int next(int h) { return h - h % 3 + (h % 3 + 1) % 3; }
    static int prev(int h) { return h - h % 3 + (h % 3 + 2) % 3; }
    int from(int h) const { return faces_[h / 3][h % 3]; }
    int to(int h) const { return faces_[h / 3][(h % 3 + 1) % 3]; }
    int opposite_vertex(int h) const { return faces_[h / 3][(h % 3 + 2) % 3]; }
    int twin(int h) const { return twin_[h]; }
    bool is_boundary(int h) const { return twin_[h] < 0; }
    int outgoing(int v) const { return outgoing_[v]; }
    bool is_isolated(int v) const { return outgoing_[v] < 0; }
    // On a boundary edge (with inconsistent orientation its outgoing half-edge may be interior).
    bool is_boundary_vertex(int v) const { return boundary_vertex_[v] != 0; }

    const std::vector<Triangle>& faces() const { return faces_; }
    const std::vector<int>& input_face() const { return input_face_; }
    // Each loop lists its vertices in order; consecutive vertices (and last, first) share a
    // boundary edge.
    const std::vector<std::vector<int>>& boundary_loops() const { return loops_; }
    // Parallel to boundary_loops(): entry k is the boundary half-edge joining loop[k] and
    // loop[k+1] (in either direction when the orientation is inconsistent).
    const std::vector<std::vector<int>>& boundary_loop_edges() const { return loop_edges_; }
    const std::vector<Component>& components() const { return components_; }
    // -1 for isolated vertices.
    const std::vector<int>& component_of_vertex() const { return component_of_vertex_; }
    const ValidationReport& report() const { return report_; }
    // Boundary vertices with more than two boundary edges (bow-ties).
    const std::vector<int>& nonmanifold_vertices() const { return nonmanifold_vertices_; }

    // Frees the pairing of half-edges and the map to the input faces (twin(), is_boundary(h),
    // input_face(): 16 bytes per face, some 32 per vertex) for a caller that needs neither any
    // more: fair() once its last operator is assembled, so that they are not held through the
    // solves. Those three must not be called afterwards; everything else stays valid.
    void release_pairing();

    // Throws Error for: an index out of range, non-finite coordinates, a non-manifold edge.
    // threads as in Options::threads (0 = all cores); meshes below detail::kParallelRows
    // vertices are built on one thread. The result does not depend on it.
    static HalfEdgeMesh build(const Positions& positions, const std::vector<Triangle>& triangles,
                              int threads = 1);

private:
    struct Build;  // the passes of build() (half_edge.cpp)

    std::vector<Triangle> faces_;
    std::vector<int> input_face_;
    std::vector<int> twin_;
    std::vector<int> outgoing_;
    std::vector<char> boundary_vertex_;
    std::vector<std::vector<int>> loops_;
    std::vector<std::vector<int>> loop_edges_;
    std::vector<Component> components_;
    std::vector<int> component_of_vertex_;
    std::vector<int> nonmanifold_vertices_;
    ValidationReport report_;
};

}  // namespace fairing
