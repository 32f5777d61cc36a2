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

// The passes run in three parallel regions (validation; pairing; everything else), each thread
// on a contiguous range of faces or vertices. Wherever the serial order matters (faces kept,
// half-edges in a bucket, outgoing half-edges, component lists) the threads' ranges are put back
// in order, so the result does not depend on the number of threads.
HalfEdgeMesh HalfEdgeMesh::build(const Positions& positions, const std::vector<Triangle>& triangles,
                                 int threads) {
    HalfEdgeMesh mesh;
    const int n = static_cast<int>(positions.rows());
    const int num_input = static_cast<int>(triangles.size());
    const int team_size = detail::threads_for(n, threads);
    (void)team_size;

    // Validation, and the faces that do not repeat a vertex, kept in order: each thread copies
    // its range after the faces kept by the threads before it. Nothing here reads a position
    // through an index, so the errors can wait for the end of the region.
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
                    " non-finite coordinates (NaN or Inf): select them with MeshLab's "
                    "'Conditional Vertex Selection' filter (x != x || y != y || z != z || "
                    "abs(x) + abs(y) + abs(z) > 1e38) and run 'Delete Selected Vertices' first");
    const int num_faces = mesh.num_faces();
    mesh.report_.dropped_faces = num_input - num_faces;
    const int num_half_edges = 3 * num_faces;
    mesh.twin_.resize(num_half_edges);
    const std::vector<Triangle>& faces = mesh.faces_;

    // Pair half-edges on their undirected edge (lower vertex, higher vertex): a counting sort on
    // the lower vertex, then a sort of each small bucket on the higher one. Linear in practice
    // and cache-friendly, unlike one big indirect sort. The buckets hold half-edge numbers only;
    // the vertices are looked up again in the faces, which takes half the memory of storing them.
    const auto lower = [&faces](int h) {
        const Triangle& t = faces[h / 3];
        return std::min(t[h % 3], t[(h % 3 + 1) % 3]);
    };
    const auto higher = [&faces](int h) {
        const Triangle& t = faces[h / 3];
        return std::max(t[h % 3], t[(h % 3 + 1) % 3]);
    };
    detail::BucketFill buckets(n + 1, team_size);
    long long non_manifold = 0, inconsistent = 0;
    {
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
                    const int a = static_cast<int>(key[i] & 0xffffffffu);
                    if (j - i == 2) {
                        const int b = static_cast<int>(key[i + 1] & 0xffffffffu);
                        mesh.twin_[a] = b;
                        mesh.twin_[b] = a;
                        if (mesh.from(a) == mesh.from(b)) ++inconsistent;
                    } else {
                        if (j - i > 2) ++non_manifold;
                        for (int k = i; k < j; ++k)
                            mesh.twin_[static_cast<int>(key[k] & 0xffffffffu)] = -1;
                    }
                    i = j;
                }
            }
        }
    }
    mesh.report_.inconsistent_edges = static_cast<int>(inconsistent);
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

    // Outgoing half-edges, boundary half-edges, zero-area faces and components. Each thread keeps
    // the best outgoing half-edge of its faces in its own histogram, keyed so that the smallest
    // key wins: boundary half-edges (h - H) before interior ones (h), each the smallest.
    mesh.outgoing_.resize(n);
    mesh.component_of_vertex_.resize(n);
    std::vector<int> boundary;  // boundary half-edges, increasing
    std::vector<int> boundary_before(team_size + 1, 0);
    std::vector<int> roots_before(team_size + 1, 0);
    ConcurrentSets sets(n);
    std::unique_ptr<int[]> start(new int[n + 1]);
    long long isolated = 0, zero_area = 0;
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1)
                   reduction(+ : isolated, zero_area))
    {
        const detail::Team team = detail::this_team();
        const int v0 = team.begin(n), v1 = team.end(n);
        const int f0 = team.begin(num_faces), f1 = team.end(num_faces);
        for (int v = v0; v < v1; ++v) sets.reset(v);
        int* best = buckets.histogram(team.id);
        std::fill(best, best + n, num_half_edges);
        int boundary_count = 0;
        for (int f = f0; f < f1; ++f) {
            const Triangle& t = faces[f];
            for (int k = 0; k < 3; ++k) {
                const int h = 3 * f + k;
                const bool on_boundary = mesh.twin_[h] < 0;
                best[t[k]] = std::min(best[t[k]], on_boundary ? h - num_half_edges : h);
                boundary_count += on_boundary;
            }
            if (detail::is_zero_area(detail::row(positions, t[0]), detail::row(positions, t[1]),
                                     detail::row(positions, t[2])))
                ++zero_area;
        }
        boundary_before[team.id + 1] = boundary_count;
        detail::barrier();

        for (int v = v0; v < v1; ++v) {
            int key = num_half_edges;
            for (int t = 0; t < team.size; ++t) key = std::min(key, buckets.histogram(t)[v]);
            mesh.outgoing_[v] = key == num_half_edges ? -1 : key < 0 ? key + num_half_edges : key;
            if (key == num_half_edges) ++isolated;
        }
        FAIRING_PRAGMA(omp single)
        {
            std::partial_sum(boundary_before.begin(), boundary_before.end(),
                             boundary_before.begin());
            boundary.resize(boundary_before.back());
        }
        int b = boundary_before[team.id];
        for (int h = 3 * f0; h < 3 * f1; ++h)
            if (mesh.twin_[h] < 0) boundary[b++] = h;
        for (int f = f0; f < f1; ++f) {
            sets.unite(faces[f][0], faces[f][1]);
            sets.unite(faces[f][0], faces[f][2]);
        }
        detail::barrier();

        // Components are numbered in the order of their smallest vertex, their root.
        int roots = 0;
        for (int v = v0; v < v1; ++v) {
            const int root = sets.find(v);
            sets.set_root(v, root);
            roots += root == v && mesh.outgoing_[v] >= 0;
        }
        roots_before[team.id + 1] = roots;
        detail::barrier();
        int component = 0;
        for (int t = 0; t <= team.id; ++t) component += roots_before[t];
        for (int v = v0; v < v1; ++v)
            if (sets.parent(v) == v)
                mesh.component_of_vertex_[v] = mesh.outgoing_[v] >= 0 ? component++ : -1;
        FAIRING_PRAGMA(omp single)
        mesh.components_.resize(std::accumulate(roots_before.begin(), roots_before.end(), 0));
        for (int v = v0; v < v1; ++v)
            if (sets.parent(v) != v)
                mesh.component_of_vertex_[v] = mesh.component_of_vertex_[sets.parent(v)];
        const int num_components = static_cast<int>(mesh.components_.size());

        // Vertex and face lists of the components, by a counting sort on the component.
        int* position = buckets.clear(team, num_components);
        for (int v = v0; v < v1; ++v)
            if (mesh.component_of_vertex_[v] >= 0) ++position[mesh.component_of_vertex_[v]];
        buckets.to_positions(team, start.get());
        FAIRING_PRAGMA(omp for schedule(static))
        for (int c = 0; c < num_components; ++c)
            mesh.components_[c].vertices.resize(start[c + 1] - start[c]);
        for (int v = v0; v < v1; ++v) {
            const int c = mesh.component_of_vertex_[v];
            if (c >= 0) mesh.components_[c].vertices[position[c]++ - start[c]] = v;
        }
        position = buckets.clear(team, num_components);  // to_positions waits for the fills
        for (int f = f0; f < f1; ++f) ++position[mesh.component_of_vertex_[faces[f][0]]];
        buckets.to_positions(team, start.get());
        FAIRING_PRAGMA(omp for schedule(static))
        for (int c = 0; c < num_components; ++c)
            mesh.components_[c].faces.resize(start[c + 1] - start[c]);
        for (int f = f0; f < f1; ++f) {
            const int c = mesh.component_of_vertex_[faces[f][0]];
            mesh.components_[c].faces[position[c]++ - start[c]] = f;
        }
    }
    mesh.report_.isolated_vertices = static_cast<int>(isolated);
    mesh.report_.zero_area_faces = static_cast<int>(zero_area);
    for (int h : boundary)
        mesh.components_[mesh.component_of_vertex_[mesh.from(h)]].has_boundary = true;
    if (mesh.report_.inconsistent_edges > 0)
        for (int h = 0; h < num_half_edges; ++h)
            if (mesh.twin_[h] >= 0 && mesh.from(mesh.twin_[h]) == mesh.from(h))
                mesh.components_[mesh.component_of_vertex_[mesh.from(h)]]
                    .consistently_oriented = false;

    // Boundary loops: walk the boundary edges as an undirected graph. Serial, but over the
    // boundary only.
    mesh.boundary_vertex_.assign(n, 0);
    if (boundary.empty()) return mesh;
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
    return mesh;
}

}  // namespace fairing
