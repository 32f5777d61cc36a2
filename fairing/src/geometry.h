// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Small geometric helpers shared by the engine's translation units (not installed).
#pragma once

#include "fairing/half_edge.h"
#include "fairing/types.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

namespace fairing {
namespace detail {

inline Vec3 row(const Positions& x, int i) { return x.row(i).transpose(); }

// A face is of zero area when twice its area is below 1e-12 of its squared longest edge: the
// sine of its largest angle is then below about 1e-12, and its cotangents are meaningless. The
// test is relative, so it does not depend on the mesh's units.
inline bool is_zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double twice_area = (b - a).cross(c - a).norm();
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(),
                                     (a - c).squaredNorm()});
    return !(twice_area > 1e-12 * longest);
}

// Per vertex of `mesh`, the sum of its faces' area vectors at x (twice the area times the unit
// normal): the area-weighted vertex normal before normalizing.
inline Positions area_normal_sums(const HalfEdgeMesh& mesh, const Positions& x) {
    Positions sums = Positions::Zero(mesh.num_vertices(), 3);
    for (const Triangle& t : mesh.faces()) {
        const Vec3 a = row(x, t[0]);
        const Eigen::RowVector3d area_vector =
            (row(x, t[1]) - a).cross(row(x, t[2]) - a).transpose();
        for (int k = 0; k < 3; ++k) sums.row(t[k]) += area_vector;
    }
    return sums;
}

// Every row scaled to unit length; a zero row stays zero.
inline void normalize_rows(Positions& p) {
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
        const double length = p.row(i).norm();
        if (length > 0) p.row(i) /= length;
        else p.row(i).setZero();
    }
}

// splitmix64 (Steele, Lea & Flood 2014): random bits from a vertex's index alone, so that probes
// and draws do not depend on the thread count or the standard library.
inline std::uint64_t splitmix64(std::uint64_t v) {
    v += 0x9e3779b97f4a7c15ull;
    v = (v ^ (v >> 30)) * 0xbf58476d1ce4e5b9ull;
    v = (v ^ (v >> 27)) * 0x94d049bb133111ebull;
    return v ^ (v >> 31);
}

// "3 non-manifold edges" / "1 non-manifold edge": messages name the count.
inline std::string count_of(long long n, const std::string& singular, const std::string& plural) {
    std::ostringstream s;
    s << n << ' ' << (n == 1 ? singular : plural);
    return s.str();
}

}  // namespace detail
}  // namespace fairing
