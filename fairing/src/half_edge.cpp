// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "fairing/half_edge.h"

#include "geometry.h"
#include "parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>

namespace fairing {
namespace {

// Union-find shared by the threads of a region. A root is only ever linked below a smaller root
// (by compare-and-swap, so two threads cannot both link it), hence parents only decrease, every
// value a parent ever held stays an ancestor, and the root of a set is its smallest vertex
// whatever the order of the unions: the components come out the same on any number of threads.
class ConcurrentSets {
public:
    explicit ConcurrentSets(int n) : parent_(new std::atomic<int>[n]) {}
    void reset(int v) { parent_[v].store(v, std::memory_order_relaxed); }
    int find(int v) {
        while (true) {
            const int p = parent_[v].load(std::memory_order_relaxed);
            if (p == v) return v;
            const int g = parent_[p].load(std::memory_order_relaxed);
            // Path halving: v is not a root, so only halving ever rewrites its parent, and any
            // ancestor is a correct value.
            if (g != p) parent_[v].store(g, std::memory_order_relaxed);
            v = g;
        }
    }
    void unite(int a, int b) {
        while (true) {
            a = find(a);
            b = find(b);
            if (a == b) return;
            if (a > b) std::swap(a, b);
            int expected = b;
            if (parent_[b].compare_exchange_weak(expected, a, std::memory_order_relaxed)) return;
        }
    }
    // Once no union is under way: the root found earlier, without walking again.
    void set_root(int v, int root) { parent_[v].store(root, std::memory_order_relaxed); }
    int parent(int v) const { return parent_[v].load(std::memory_order_relaxed); }

private:
    std::unique_ptr<std::atomic<int>[]> parent_;
};

// Sorts a bucket of a few entries (a vertex's valence) in place.
void insertion_sort(std::uint64_t* begin, std::uint64_t* end) {
    if (end - begin < 2) return;  // also keeps begin + 1 off an empty vector's null data()
    for (std::uint64_t* i = begin + 1; i < end; ++i) {
        const std::uint64_t x = *i;
        std::uint64_t* j = i;
        for (; j > begin && *(j - 1) > x; --j) *j = *(j - 1);
        *j = x;
    }
}

}  // namespace

// The passes of build(), in order; nested in HalfEdgeMesh so that they may fill its arrays.
struct HalfEdgeMesh::Build {
    static void keep_faces(HalfEdgeMesh& mesh, const Positions& positions,
                           const std::vector<Triangle>& triangles, int team_size);
    static long long pair_half_edges(HalfEdgeMesh& mesh, int n, detail::BucketFill& buckets,
                                     int team_size);
    static void refuse_duplicates_and_fins(const HalfEdgeMesh& mesh, long long non_manifold);
    class VertexPass;
    static std::vector<int> vertices_and_components(HalfEdgeMesh& mesh, const Positions& positions,
                                                    detail::BucketFill& buckets, int team_size);
    static void boundary_loops(HalfEdgeMesh& mesh, const std::vector<int>& boundary);
};

// The passes run in three parallel regions (validation; pairing; everything else), each thread
// on a contiguous range of faces or vertices. Wherever the serial order matters (faces kept,
// half-edges in a bucket, outgoing half-edges, component lists) the threads' ranges are put back
// in order, so the result does not depend on the number of threads.
HalfEdgeMesh HalfEdgeMesh::build(const Positions& positions, const std::vector<Triangle>& triangles,
                                 int threads) {
    HalfEdgeMesh mesh;
    const int n = static_cast<int>(positions.rows());
    const int team_size = detail::threads_for(n, threads);
    Build::keep_faces(mesh, positions, triangles, team_size);
    mesh.report_.dropped_faces = static_cast<int>(triangles.size()) - mesh.num_faces();
    detail::BucketFill buckets(n + 1, team_size);
    const long long non_manifold = Build::pair_half_edges(mesh, n, buckets, team_size);
    Build::refuse_duplicates_and_fins(mesh, non_manifold);
    const std::vector<int> boundary =
        Build::vertices_and_components(mesh, positions, buckets, team_size);
    Build::boundary_loops(mesh, boundary);
    return mesh;
}

void HalfEdgeMesh::release_pairing() {
    std::vector<int>().swap(twin_);
    std::vector<int>().swap(input_face_);
}

// Validation, and the faces that do not repeat a vertex, kept in order: each thread copies its
// range after the faces kept by the threads before it. Nothing here reads a position through an
// index, so the errors can wait for the end of the region.
void HalfEdgeMesh::Build::keep_faces(HalfEdgeMesh& mesh, const Positions& positions,
                                     const std::vector<Triangle>& triangles, int team_size) {
    const int n = static_cast<int>(positions.rows());
    const int num_input = static_cast<int>(triangles.size());
    long long out_of_range = 0, non_finite = 0;
    std::vector<int> kept_before(team_size + 1, 0);
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1)
                   reduction(+ : out_of_range, non_finite))
    {
        const detail::Team team = detail::this_team();
        const int f0 = team.begin(num_input), f1 = team.end(num_input);
        const auto keep = [&triangles](int f) {
            const Triangle& t = triangles[f];
            return t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
        };
        int kept = 0;
        for (int f = f0; f < f1; ++f) {
            for (int v : triangles[f])
                if (v < 0 || v >= n) ++out_of_range;
            kept += keep(f);
        }
        kept_before[team.id + 1] = kept;
        for (int v = team.begin(n); v < team.end(n); ++v)
            if (!positions.row(v).allFinite()) ++non_finite;
        detail::barrier();
        FAIRING_PRAGMA(omp single)
        {
            std::partial_sum(kept_before.begin(), kept_before.end(), kept_before.begin());
            mesh.faces_.resize(kept_before.back());
            mesh.input_face_.resize(kept_before.back());
        }
        kept = kept_before[team.id];
        for (int f = f0; f < f1; ++f)
            if (keep(f)) {
                mesh.faces_[kept] = triangles[f];
                mesh.input_face_[kept++] = f;
            }
    }
    if (out_of_range > 0)
        throw Error(detail::count_of(out_of_range, "face corner", "face corners") +
                    " refer to a vertex index out of range (the mesh has " +
                    std::to_string(n) + " vertices); the mesh is corrupt");
    if (non_finite > 0)
        throw Error(detail::count_of(non_finite, "vertex has", "vertices have") +
                        " non-finite coordinates (NaN or Inf)",
                    Repair::NonFiniteVertices);
}

// Pairs half-edges on their undirected edge (lower vertex, higher vertex): a counting sort on
// the lower vertex, then a sort of each small bucket on the higher one. Linear in practice and
// cache-friendly, unlike one big indirect sort. The buckets hold half-edge numbers only; the
// vertices are looked up again in the faces, which takes half the memory of storing them.
// Fills twin_ (-1 on the boundary and on non-manifold edges) and counts inconsistent edges;
// returns the number of non-manifold edges.
long long HalfEdgeMesh::Build::pair_half_edges(HalfEdgeMesh& mesh, int n,
                                               detail::BucketFill& buckets, int team_size) {
    const std::vector<Triangle>& faces = mesh.faces_;
    const int num_faces = mesh.num_faces(), num_half_edges = 3 * num_faces;
    mesh.twin_.resize(num_half_edges);
    const auto lower = [&faces](int h) {
        const Triangle& t = faces[h / 3];
        return std::min(t[h % 3], t[(h % 3 + 1) % 3]);
    };
    const auto higher = [&faces](int h) {
        const Triangle& t = faces[h / 3];
        return std::max(t[h % 3], t[(h % 3 + 1) % 3]);
    };
    const auto half_edge = [](std::uint64_t key) { return static_cast<int>(key & 0xffffffffu); };
    (void)team_size;  // used by OpenMP only
    long long non_manifold = 0, inconsistent = 0;
    std::unique_ptr<int[]> order(new int[num_half_edges]);
    std::unique_ptr<int[]> bucket_start(new int[n + 1]);
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1))
    {
        const detail::Team team = detail::this_team();
        const int h0 = 3 * team.begin(num_faces), h1 = 3 * team.end(num_faces);
        int* position = buckets.clear(team, n);
        for (int h = h0; h < h1; ++h) ++position[lower(h)];
        buckets.to_positions(team, bucket_start.get());
        for (int h = h0; h < h1; ++h) order[position[lower(h)]++] = h;
        detail::barrier();

        std::vector<std::uint64_t> key;  // this thread's bucket: higher vertex, half-edge
        FAIRING_PRAGMA(omp for schedule(static) reduction(+ : non_manifold, inconsistent))
        for (int v = 0; v < n; ++v) {
            key.clear();
            for (int k = bucket_start[v]; k < bucket_start[v + 1]; ++k)
                key.push_back(static_cast<std::uint64_t>(higher(order[k])) << 32 |
                              static_cast<std::uint32_t>(order[k]));
            insertion_sort(key.data(), key.data() + key.size());
            const int size = static_cast<int>(key.size());
            for (int i = 0; i < size;) {
                int j = i + 1;
                while (j < size && key[j] >> 32 == key[i] >> 32) ++j;
                if (j - i == 2) {
                    const int a = half_edge(key[i]), b = half_edge(key[i + 1]);
                    mesh.twin_[a] = b;
                    mesh.twin_[b] = a;
                    if (mesh.from(a) == mesh.from(b)) ++inconsistent;
                } else {
                    if (j - i > 2) ++non_manifold;
                    for (int k = i; k < j; ++k) mesh.twin_[half_edge(key[k])] = -1;
                }
                i = j;
            }
        }
    }
    mesh.report_.inconsistent_edges = static_cast<int>(inconsistent);
    return non_manifold;
}

// Faces with the same three vertices as another face, in any order (MeshLab's definition), show
// up as edges with too many faces or faces of opposite orientation: only then are they looked
// for, so clean meshes do not pay for the sort. They are named before the non-manifold edges
// they cause, since removing them is the repair.
void HalfEdgeMesh::Build::refuse_duplicates_and_fins(const HalfEdgeMesh& mesh,
                                                     long long non_manifold) {
    if (non_manifold > 0 || mesh.report_.inconsistent_edges > 0) {
        std::vector<Triangle> sorted(mesh.faces_);
        for (Triangle& t : sorted) std::sort(t.begin(), t.end());
        std::sort(sorted.begin(), sorted.end());
        long long duplicated = 0;
        for (std::size_t f = 1; f < sorted.size(); ++f)
            if (sorted[f] == sorted[f - 1]) ++duplicated;
        if (duplicated > 0)
            throw Error(detail::count_of(duplicated, "duplicated face", "duplicated faces") +
                            " (the same three vertices as another face)",
                        Repair::DuplicateFaces);
    }
    if (non_manifold > 0)
        throw Error(detail::count_of(non_manifold, "non-manifold edge", "non-manifold edges") +
                        " (shared by three or more faces): the one-ring of their vertices is "
                        "undefined",
                    Repair::NonManifoldEdges);
}

// The third region: outgoing half-edges, boundary half-edges, zero-area faces and components.
// Every thread runs the phases in order on its own ranges of vertices and faces; the phases
// meet at barriers, and the state they share lives here.
class HalfEdgeMesh::Build::VertexPass {
public:
    VertexPass(HalfEdgeMesh& mesh, const Positions& positions, detail::BucketFill& buckets,
               int team_size)
        : mesh_(mesh), positions_(positions), buckets_(buckets),
          n_(static_cast<int>(positions.rows())), num_half_edges_(3 * mesh.num_faces()),
          sets_(n_), start_(new int[n_ + 1]), boundary_before_(team_size + 1, 0),
          roots_before_(team_size + 1, 0) {
        mesh.outgoing_.resize(n_);
        mesh.component_of_vertex_.resize(n_);
    }

    // Each thread keeps the best outgoing half-edge of its faces in its own histogram, keyed so
    // that the smallest key wins: boundary half-edges (h - H) before interior ones (h), each the
    // smallest. Returns the zero-area faces of the thread's range.
    long long scan_faces(const detail::Team& team) {
        const int f0 = team.begin(mesh_.num_faces()), f1 = team.end(mesh_.num_faces());
        for (int v = team.begin(n_); v < team.end(n_); ++v) sets_.reset(v);
        int* best = buckets_.histogram(team.id);
        std::fill(best, best + n_, num_half_edges_);
        int boundary_count = 0;
        long long zero_area = 0;
        for (int f = f0; f < f1; ++f) {
            const Triangle& t = mesh_.faces_[f];
            for (int k = 0; k < 3; ++k) {
                const int h = 3 * f + k;
                const bool on_boundary = mesh_.twin_[h] < 0;
                best[t[k]] = std::min(best[t[k]], on_boundary ? h - num_half_edges_ : h);
                boundary_count += on_boundary;
            }
            if (detail::is_zero_area(detail::row(positions_, t[0]), detail::row(positions_, t[1]),
                                     detail::row(positions_, t[2])))
                ++zero_area;
        }
        boundary_before_[team.id + 1] = boundary_count;
        return zero_area;
    }

    // After scan_faces on every thread: outgoing half-edges, the boundary half-edges in order,
    // and the union of each face's vertices. Returns the isolated vertices of the thread's range.
    long long outgoing_boundary_unions(const detail::Team& team) {
        long long isolated = 0;
        for (int v = team.begin(n_); v < team.end(n_); ++v) {
            int key = num_half_edges_;
            for (int t = 0; t < team.size; ++t) key = std::min(key, buckets_.histogram(t)[v]);
            mesh_.outgoing_[v] =
                key == num_half_edges_ ? -1 : key < 0 ? key + num_half_edges_ : key;
            if (key == num_half_edges_) ++isolated;
        }
        FAIRING_PRAGMA(omp single)
        {
            std::partial_sum(boundary_before_.begin(), boundary_before_.end(),
                             boundary_before_.begin());
            boundary.resize(boundary_before_.back());
        }
        const int f0 = team.begin(mesh_.num_faces()), f1 = team.end(mesh_.num_faces());
        int b = boundary_before_[team.id];
        for (int h = 3 * f0; h < 3 * f1; ++h)
            if (mesh_.twin_[h] < 0) boundary[b++] = h;
        for (int f = f0; f < f1; ++f) {
            sets_.unite(mesh_.faces_[f][0], mesh_.faces_[f][1]);
            sets_.unite(mesh_.faces_[f][0], mesh_.faces_[f][2]);
        }
        return isolated;
    }

    // After every union: components numbered in the order of their smallest vertex, their root.
    void number_components(const detail::Team& team) {
        const int v0 = team.begin(n_), v1 = team.end(n_);
        int roots = 0;
        for (int v = v0; v < v1; ++v) {
            const int root = sets_.find(v);
            sets_.set_root(v, root);
            roots += root == v && mesh_.outgoing_[v] >= 0;
        }
        roots_before_[team.id + 1] = roots;
        detail::barrier();
        int component = 0;
        for (int t = 0; t <= team.id; ++t) component += roots_before_[t];
        for (int v = v0; v < v1; ++v)
            if (sets_.parent(v) == v)
                mesh_.component_of_vertex_[v] = mesh_.outgoing_[v] >= 0 ? component++ : -1;
        FAIRING_PRAGMA(omp single)
        mesh_.components_.resize(std::accumulate(roots_before_.begin(), roots_before_.end(), 0));
        for (int v = v0; v < v1; ++v)
            if (sets_.parent(v) != v)
                mesh_.component_of_vertex_[v] = mesh_.component_of_vertex_[sets_.parent(v)];
    }

    // Vertex and face lists of the components, by a counting sort on the component.
    void list_components(const detail::Team& team) {
        const int v0 = team.begin(n_), v1 = team.end(n_);
        const int f0 = team.begin(mesh_.num_faces()), f1 = team.end(mesh_.num_faces());
        const std::vector<int>& component_of = mesh_.component_of_vertex_;
        const int num_components = static_cast<int>(mesh_.components_.size());
        int* position = buckets_.clear(team, num_components);
        for (int v = v0; v < v1; ++v)
            if (component_of[v] >= 0) ++position[component_of[v]];
        buckets_.to_positions(team, start_.get());
        FAIRING_PRAGMA(omp for schedule(static))
        for (int c = 0; c < num_components; ++c)
            mesh_.components_[c].vertices.resize(start_[c + 1] - start_[c]);
        for (int v = v0; v < v1; ++v) {
            const int c = component_of[v];
            if (c >= 0) mesh_.components_[c].vertices[position[c]++ - start_[c]] = v;
        }
        position = buckets_.clear(team, num_components);  // to_positions waits for the fills
        for (int f = f0; f < f1; ++f) ++position[component_of[mesh_.faces_[f][0]]];
        buckets_.to_positions(team, start_.get());
        FAIRING_PRAGMA(omp for schedule(static))
        for (int c = 0; c < num_components; ++c)
            mesh_.components_[c].faces.resize(start_[c + 1] - start_[c]);
        for (int f = f0; f < f1; ++f) {
            const int c = component_of[mesh_.faces_[f][0]];
            mesh_.components_[c].faces[position[c]++ - start_[c]] = f;
        }
    }

    std::vector<int> boundary;  // boundary half-edges, increasing

private:
    HalfEdgeMesh& mesh_;
    const Positions& positions_;
    detail::BucketFill& buckets_;
    const int n_, num_half_edges_;
    ConcurrentSets sets_;
    std::unique_ptr<int[]> start_;
    std::vector<int> boundary_before_, roots_before_;
};

// Returns the boundary half-edges, increasing.
std::vector<int> HalfEdgeMesh::Build::vertices_and_components(HalfEdgeMesh& mesh,
                                                             const Positions& positions,
                                                             detail::BucketFill& buckets,
                                                             int team_size) {
    VertexPass pass(mesh, positions, buckets, team_size);
    long long isolated = 0, zero_area = 0;
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1)
                   reduction(+ : isolated, zero_area))
    {
        const detail::Team team = detail::this_team();
        zero_area += pass.scan_faces(team);
        detail::barrier();
        isolated += pass.outgoing_boundary_unions(team);
        detail::barrier();
        pass.number_components(team);
        pass.list_components(team);
    }
    mesh.report_.isolated_vertices = static_cast<int>(isolated);
    mesh.report_.zero_area_faces = static_cast<int>(zero_area);
    for (int h : pass.boundary)
        mesh.components_[mesh.component_of_vertex_[mesh.from(h)]].has_boundary = true;
    if (mesh.report_.inconsistent_edges > 0)
        for (int h = 0; h < 3 * mesh.num_faces(); ++h)
            if (mesh.twin_[h] >= 0 && mesh.from(mesh.twin_[h]) == mesh.from(h))
                mesh.components_[mesh.component_of_vertex_[mesh.from(h)]]
                    .consistently_oriented = false;
    return std::move(pass.boundary);
}

// Boundary loops: walk the boundary edges as an undirected graph. Serial, but over the boundary
// only. Also marks the boundary vertices and lists the non-manifold ones (more than two
// boundary edges).
void HalfEdgeMesh::Build::boundary_loops(HalfEdgeMesh& mesh, const std::vector<int>& boundary) {
    const int n = mesh.num_vertices();
    mesh.boundary_vertex_.assign(n, 0);
    if (boundary.empty()) return;
    const int num_boundary = static_cast<int>(boundary.size());
    std::vector<int> boundary_start(n + 1, 0);
    for (int h : boundary) {
        mesh.boundary_vertex_[mesh.from(h)] = mesh.boundary_vertex_[mesh.to(h)] = 1;
        ++boundary_start[mesh.from(h) + 1];
        ++boundary_start[mesh.to(h) + 1];
    }
    std::partial_sum(boundary_start.begin(), boundary_start.end(), boundary_start.begin());
    std::vector<int> boundary_at(boundary_start[n]);  // indices into `boundary`, per vertex
    {
        std::vector<int> fill(boundary_start.begin(), boundary_start.end() - 1);
        for (int i = 0; i < num_boundary; ++i) {
            boundary_at[fill[mesh.from(boundary[i])]++] = i;
            boundary_at[fill[mesh.to(boundary[i])]++] = i;
        }
    }
    for (int v = 0; v < n; ++v)
        if (boundary_start[v + 1] - boundary_start[v] > 2) {
            mesh.nonmanifold_vertices_.push_back(v);
            ++mesh.report_.nonmanifold_vertices;
        }
    std::vector<char> used(num_boundary, 0);
    for (int i0 = 0; i0 < num_boundary; ++i0) {
        if (used[i0]) continue;
        std::vector<int> loop, loop_edges;
        int i = i0;
        int v = mesh.from(boundary[i0]);
        while (true) {
            const int h = boundary[i];
            used[i] = 1;
            loop.push_back(v);
            loop_edges.push_back(h);
            v = mesh.from(h) == v ? mesh.to(h) : mesh.from(h);
            // Prefer the edge that continues in the walking direction (matters at bow-ties).
            int next = -1;
            for (int k = boundary_start[v]; k < boundary_start[v + 1]; ++k) {
                const int c = boundary_at[k];
                if (used[c]) continue;
                if (next < 0 || mesh.from(boundary[c]) == v) next = c;
                if (mesh.from(boundary[c]) == v) break;
            }
            if (next < 0) break;
            i = next;
        }
        mesh.loops_.push_back(std::move(loop));
        mesh.loop_edges_.push_back(std::move(loop_edges));
    }
}

}  // namespace fairing
