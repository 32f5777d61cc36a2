// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "vertex_order.h"

#include <algorithm>
#include <cstdlib>

namespace fairing {
namespace detail {
namespace {

// The vertices reached from `from` breadth-first over the edges (start, column: adjacency),
// appended to `order`; returns the last one reached. `seen` marks them with `mark`.
int breadth_first(int from, const int* start, const int* column, int* seen, int mark,
                  std::vector<int>& order) {
    std::size_t head = order.size();
    order.push_back(from);
    seen[from] = mark;
    int last = from;
    for (; head < order.size(); ++head) {
        last = order[head];
        for (int k = start[last]; k < start[last + 1]; ++k) {
            if (seen[column[k]] == mark) continue;
            seen[column[k]] = mark;
            order.push_back(column[k]);
        }
    }
    return last;
}

}  // namespace

std::vector<int> locality_order(const TriangleMesh& mesh) {
    const int n = static_cast<int>(mesh.positions.rows());
    const long long faces = static_cast<long long>(mesh.triangles.size());
    if (n < kReorderVertices || faces == 0) return {};
    for (const Triangle& t : mesh.triangles)
        for (int v : t)
            if (v < 0 || v >= n) return {};
    if (!mesh.positions.allFinite()) return {};

    // Median index gap over the edges of up to 8192 evenly spaced faces.
    std::vector<int> gaps;
    const long long stride = std::max(1LL, faces / 8192);
    for (long long f = 0; f < faces; f += stride) {
        const Triangle& t = mesh.triangles[static_cast<std::size_t>(f)];
        for (int k = 0; k < 3; ++k) gaps.push_back(std::abs(t[k] - t[(k + 1) % 3]));
    }
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    if (gaps[gaps.size() / 2] <= kReorderMedianGap) return {};

    // Each face's three directed edges both ways, as adjacency lists (a repeated edge is
    // listed twice: the search skips what it has seen).
    std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
    for (const Triangle& t : mesh.triangles)
        for (int v : t) start[static_cast<std::size_t>(v) + 1] += 2;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) start[i + 1] += start[i];
    std::vector<int> column(static_cast<std::size_t>(start.back()));
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const Triangle& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            int& at = fill[static_cast<std::size_t>(t[k])];
            column[static_cast<std::size_t>(at++)] = t[(k + 1) % 3];
            column[static_cast<std::size_t>(at++)] = t[(k + 2) % 3];
        }

    // Per connected component, in the order of its first input vertex: a breadth-first search
    // from the vertex the search from that first one reaches last (a far end of the component,
    // as in Cuthill-McKee's pseudo-peripheral start), so that the fronts, and with them the
    // index gap of every edge, stay short.
    std::vector<int> order;
    order.reserve(static_cast<std::size_t>(n));
    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; ++i) {
        if (seen[static_cast<std::size_t>(i)] != 0) continue;
        const std::size_t component = order.size();
        const int far_end = breadth_first(i, start.data(), column.data(), seen.data(), 1, order);
        order.resize(component);  // only its last vertex was wanted
        breadth_first(far_end, start.data(), column.data(), seen.data(), 2, order);
    }
    return order;
}

TriangleMesh renumbered(const TriangleMesh& mesh, const std::vector<int>& order) {
    const int n = static_cast<int>(order.size());
    std::vector<int> new_index(static_cast<std::size_t>(n));
    TriangleMesh out;
    out.positions.resize(n, 3);
    for (int i = 0; i < n; ++i) {
        new_index[static_cast<std::size_t>(order[i])] = i;
        out.positions.row(i) = mesh.positions.row(order[i]);
    }
    // Faces by their smallest new vertex, stably: a counting sort.
    std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
    std::vector<Triangle> faces(mesh.triangles.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        Triangle& t = faces[f];
        for (int k = 0; k < 3; ++k) t[k] = new_index[static_cast<std::size_t>(mesh.triangles[f][k])];
        ++start[static_cast<std::size_t>(std::min({t[0], t[1], t[2]})) + 1];
    }
    for (int i = 0; i < n; ++i) start[i + 1] += start[i];
    out.triangles.resize(faces.size());
    for (const Triangle& t : faces)
        out.triangles[static_cast<std::size_t>(start[static_cast<std::size_t>(std::min({t[0], t[1], t[2]}))]++)] = t;
    return out;
}

Constraints renumbered(const Constraints& constraints, const std::vector<int>& order) {
    Constraints out;
    if (!constraints.fixed.empty()) {
        out.fixed.resize(order.size());
        for (std::size_t i = 0; i < order.size(); ++i) out.fixed[i] = constraints.fixed[order[i]];
    }
    if (!constraints.weights.empty()) {
        out.weights.resize(order.size());
        for (std::size_t i = 0; i < order.size(); ++i) out.weights[i] = constraints.weights[order[i]];
    }
    return out;
}

}  // namespace detail
}  // namespace fairing
