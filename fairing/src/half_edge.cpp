#include "fairing/half_edge.h"

#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace fairing {
namespace {

int find_root(std::vector<int>& parent, int v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

}  // namespace

HalfEdgeMesh HalfEdgeMesh::build(const Positions& positions,
                                 const std::vector<Triangle>& triangles) {
    HalfEdgeMesh mesh;
    const int n = static_cast<int>(positions.rows());

    long long out_of_range = 0;
    for (const Triangle& t : triangles)
        for (int v : t)
            if (v < 0 || v >= n) ++out_of_range;
    if (out_of_range > 0)
        throw Error(detail::count_of(out_of_range, "face corner", "face corners") +
                    " refer to a vertex index out of range (the mesh has " +
                    std::to_string(n) + " vertices); the mesh is corrupt");

    long long non_finite = 0;
    for (int v = 0; v < n; ++v)
        if (!positions.row(v).allFinite()) ++non_finite;
    if (non_finite > 0)
        throw Error(detail::count_of(non_finite, "vertex has", "vertices have") +
                    " non-finite coordinates (NaN or Inf): select them with MeshLab's "
                    "'Conditional Vertex Selection' filter (x != x || y != y || z != z || "
                    "abs(x) + abs(y) + abs(z) > 1e38) and run 'Delete Selected Vertices' first");

    for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
        const Triangle& t = triangles[f];
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
            ++mesh.report_.dropped_faces;
            continue;
        }
        mesh.faces_.push_back(t);
        mesh.input_face_.push_back(f);
    }
    const int num_half_edges = 3 * mesh.num_faces();

    // Pair half-edges on their undirected edge (lower vertex, higher vertex): a counting sort on
    // the lower vertex, then a sort of each small bucket on the higher one. Linear in practice
    // and cache-friendly, unlike one big indirect sort.
    std::vector<int> low(num_half_edges), high(num_half_edges);
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const Triangle& t = mesh.faces_[f];
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            low[3 * f + k] = std::min(a, b);
            high[3 * f + k] = std::max(a, b);
        }
    }
    const auto lower = [&](int h) { return low[h]; };
    const auto higher = [&](int h) { return high[h]; };
    const auto key = [&](int h) {
        return static_cast<std::uint64_t>(low[h]) << 32 | static_cast<std::uint32_t>(high[h]);
    };
    std::vector<int> order(num_half_edges);
    {
        std::vector<int> bucket_start(n + 1, 0);
        for (int h = 0; h < num_half_edges; ++h) ++bucket_start[lower(h) + 1];
        std::partial_sum(bucket_start.begin(), bucket_start.end(), bucket_start.begin());
        std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
        for (int h = 0; h < num_half_edges; ++h) order[fill[lower(h)]++] = h;
        for (int v = 0; v < n; ++v)
            if (bucket_start[v + 1] - bucket_start[v] > 1)
                std::sort(order.begin() + bucket_start[v], order.begin() + bucket_start[v + 1],
                          [&](int a, int b) {
                              return higher(a) != higher(b) ? higher(a) < higher(b) : a < b;
                          });
    }
    mesh.twin_.assign(num_half_edges, -1);
    long long non_manifold = 0;
    for (int i = 0; i < num_half_edges;) {
        int j = i + 1;
        while (j < num_half_edges && key(order[j]) == key(order[i])) ++j;
        if (j - i == 2) {
            const int a = order[i], b = order[i + 1];
            mesh.twin_[a] = b;
            mesh.twin_[b] = a;
            if (mesh.from(a) == mesh.from(b)) ++mesh.report_.inconsistent_edges;
        } else if (j - i > 2) {
            ++non_manifold;
        }
        i = j;
    }
    // Faces with the same three vertices as another face, in any order (MeshLab's definition),
    // show up as edges with too many faces or faces of opposite orientation: only then are they
    // looked for, so clean meshes do not pay for the sort.
    if (non_manifold > 0 || mesh.report_.inconsistent_edges > 0) {
        std::vector<Triangle> sorted(mesh.faces_);
        for (Triangle& t : sorted) std::sort(t.begin(), t.end());
        std::sort(sorted.begin(), sorted.end());
        long long duplicated = 0;
        for (std::size_t f = 1; f < sorted.size(); ++f)
            if (sorted[f] == sorted[f - 1]) ++duplicated;
        if (duplicated > 0)
            throw Error(detail::count_of(duplicated, "duplicated face", "duplicated faces") +
                        " (the same three vertices as another face): run MeshLab's 'Remove "
                        "Duplicate Faces' filter (Filters > Cleaning and Repairing) first");
    }
    if (non_manifold > 0)
        throw Error(detail::count_of(non_manifold, "non-manifold edge", "non-manifold edges") +
                    " (shared by three or more faces): the one-ring of their vertices is "
                    "undefined. Run MeshLab's 'Repair non Manifold Edges' filter (Filters > "
                    "Cleaning and Repairing) first");

    // One outgoing half-edge per vertex, the boundary one where there is one.
    mesh.outgoing_.assign(n, -1);
    for (int h = 0; h < num_half_edges; ++h) {
        int& out = mesh.outgoing_[mesh.from(h)];
        if (out < 0 || (mesh.twin_[h] < 0 && mesh.twin_[out] >= 0)) out = h;
    }
    mesh.boundary_vertex_.assign(n, 0);
    for (int h = 0; h < num_half_edges; ++h)
        if (mesh.twin_[h] < 0) mesh.boundary_vertex_[mesh.from(h)] = mesh.boundary_vertex_[mesh.to(h)] = 1;
    for (int v = 0; v < n; ++v)
        if (mesh.outgoing_[v] < 0) ++mesh.report_.isolated_vertices;

    // Boundary loops: walk the boundary edges as an undirected graph.
    std::vector<int> boundary_start(n + 1, 0);
    std::vector<int> boundary_half_edges;
    for (int h = 0; h < num_half_edges; ++h)
        if (mesh.twin_[h] < 0) {
            ++boundary_start[mesh.from(h) + 1];
            ++boundary_start[mesh.to(h) + 1];
        }
    std::partial_sum(boundary_start.begin(), boundary_start.end(), boundary_start.begin());
    boundary_half_edges.resize(boundary_start[n]);
    {
        std::vector<int> fill(boundary_start.begin(), boundary_start.end() - 1);
        for (int h = 0; h < num_half_edges; ++h)
            if (mesh.twin_[h] < 0) {
                boundary_half_edges[fill[mesh.from(h)]++] = h;
                boundary_half_edges[fill[mesh.to(h)]++] = h;
            }
    }
    for (int v = 0; v < n; ++v)
        if (boundary_start[v + 1] - boundary_start[v] > 2) {
            mesh.nonmanifold_vertices_.push_back(v);
            ++mesh.report_.nonmanifold_vertices;
        }
    std::vector<char> used(num_half_edges, 0);
    for (int h0 = 0; h0 < num_half_edges; ++h0) {
        if (mesh.twin_[h0] >= 0 || used[h0]) continue;
        std::vector<int> loop, loop_edges;
        int h = h0;
        int v = mesh.from(h0);
        while (true) {
            used[h] = 1;
            loop.push_back(v);
            loop_edges.push_back(h);
            v = mesh.from(h) == v ? mesh.to(h) : mesh.from(h);
            // Prefer the edge that continues in the walking direction (matters at bow-ties).
            int next_h = -1;
            for (int k = boundary_start[v]; k < boundary_start[v + 1]; ++k) {
                const int c = boundary_half_edges[k];
                if (used[c]) continue;
                if (next_h < 0 || mesh.from(c) == v) next_h = c;
                if (mesh.from(c) == v) break;
            }
            if (next_h < 0) break;
            h = next_h;
        }
        mesh.loops_.push_back(std::move(loop));
        mesh.loop_edges_.push_back(std::move(loop_edges));
    }

    // Connected components through shared vertices.
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    for (const Triangle& t : mesh.faces_) {
        const int r0 = find_root(parent, t[0]);
        const int r1 = find_root(parent, t[1]);
        const int r2 = find_root(parent, t[2]);
        parent[r1] = r0;
        parent[find_root(parent, r2)] = r0;
    }
    mesh.component_of_vertex_.assign(n, -1);
    std::vector<int> component_of_root(n, -1);
    for (int v = 0; v < n; ++v) {
        if (mesh.outgoing_[v] < 0) continue;
        const int r = find_root(parent, v);
        if (component_of_root[r] < 0) {
            component_of_root[r] = static_cast<int>(mesh.components_.size());
            mesh.components_.emplace_back();
        }
        mesh.component_of_vertex_[v] = component_of_root[r];
        mesh.components_[component_of_root[r]].vertices.push_back(v);
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
        Component& c = mesh.components_[mesh.component_of_vertex_[mesh.faces_[f][0]]];
        c.faces.push_back(f);
        for (int k = 0; k < 3; ++k) {
            const int h = 3 * f + k;
            if (mesh.twin_[h] < 0) c.has_boundary = true;
            else if (mesh.from(mesh.twin_[h]) == mesh.from(h)) c.consistently_oriented = false;
        }
    }

    for (const Triangle& t : mesh.faces_)
        if (detail::is_zero_area(detail::row(positions, t[0]), detail::row(positions, t[1]),
                                 detail::row(positions, t[2])))
            ++mesh.report_.zero_area_faces;
    return mesh;
}

}  // namespace fairing
