// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Small geometric helpers shared by the engine's translation units (not installed).
#pragma once

#include "fairing/types.h"

#include <algorithm>
#include <cmath>
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

// "3 non-manifold edges" / "1 non-manifold edge": messages name the count.
inline std::string count_of(long long n, const std::string& singular, const std::string& plural) {
    std::ostringstream s;
    s << n << ' ' << (n == 1 ? singular : plural);
    return s.str();
}

}  // namespace detail
}  // namespace fairing
