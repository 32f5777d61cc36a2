// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "vertex_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>

namespace fairing {
namespace detail {
namespace {

// The 21 low bits of v spread to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
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

    const Eigen::RowVector3d lo = mesh.positions.colwise().minCoeff();
    const Eigen::RowVector3d extent = mesh.positions.colwise().maxCoeff() - lo;
    const double cells = static_cast<double>((1 << 21) - 1);
    std::vector<std::pair<std::uint64_t, int>> keyed(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        std::uint64_t key = 0;
        for (int c = 0; c < 3; ++c) {
            const double unit = extent[c] > 0 ? (mesh.positions(i, c) - lo[c]) / extent[c] : 0.0;
            key |= spread_bits(static_cast<std::uint64_t>(unit * cells)) << c;
        }
        keyed[static_cast<std::size_t>(i)] = {key, i};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = keyed[static_cast<std::size_t>(i)].second;
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
