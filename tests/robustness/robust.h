// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Helpers of the robustness tests (issue 6): run the engine on bad input and check that the
// outcome is either a correct result or a refusal whose message names the problem, the count and
// the MeshLab filter that repairs it, with the caller's mesh bit-identical afterwards.
// The mesh generators come from tests/engine/meshes.h (included, not copied).
#pragma once

#include "meshes.h"

#include <fairing_parameters/repair_hints.h>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include <unistd.h>

namespace robust {

using fairing::Constraints;
using fairing::Operator;
using fairing::Options;
using fairing::Result;
using fairing::Triangle;
using fairing::TriangleMesh;
using meshes::Positions;
using meshes::Vec3;

// The plugin's one-click defaults (filter_parameters.h): L^2, one implicit step, volume on.
inline Options defaults(Operator op) {
    Options o;
    o.op = op;
    o.order = 2;
    switch (op) {
    case Operator::Umbrella: o.time_step = 10.0; break;
    case Operator::ScaleDependent: o.time_step = 2.5; break;
    case Operator::CurvatureFlow: o.time_step = 22.5; break;
    }
    return o;
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Bitwise equality of two meshes (NaN payloads included).
inline bool bit_identical(const TriangleMesh& a, const TriangleMesh& b) {
    if (a.positions.rows() != b.positions.rows() || a.triangles != b.triangles) return false;
    return a.positions.size() == 0 ||
           std::memcmp(a.positions.data(), b.positions.data(),
                       sizeof(double) * static_cast<std::size_t>(a.positions.size())) == 0;
}

inline bool positions_bit_identical(const Positions& a, const Positions& b) {
    return a.rows() == b.rows() &&
           (a.size() == 0 || std::memcmp(a.data(), b.data(),
                                         sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

// Runs fair() expecting a fairing::Error whose message contains every part (the problem, the
// count, the repair filter). Returns the message; checks that `mesh` is untouched.
inline std::string expect_refused(const TriangleMesh& mesh, const Constraints& c, const Options& o,
                                  std::initializer_list<std::string> parts) {
    const TriangleMesh before = mesh;
    std::string msg;
    try {
        fairing::fair(mesh, c, o);
        ADD_FAILURE() << "expected a refusal, fair() succeeded";
    } catch (const fairing::Error& e) {
        // as Debian 12's MeshLab shows it: the repair filter by its menu name
        msg = filter_parameters::render(e, filter_parameters::Host::MeshLab2020);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected fairing::Error, got another exception: " << e.what();
    }
    for (const std::string& p : parts)
        EXPECT_TRUE(contains(msg, p)) << "the message lacks '" << p << "': '" << msg << "'";
    EXPECT_TRUE(bit_identical(mesh, before)) << "the input changed during a refusal";
    return msg;
}

// Runs fair() expecting success with finite positions, one row per input vertex.
inline Result expect_result(const TriangleMesh& mesh, const Constraints& c, const Options& o) {
    const TriangleMesh before = mesh;
    Result r;
    try {
        r = fairing::fair(mesh, c, o);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "unexpected refusal: " << e.what();
        return r;
    }
    EXPECT_EQ(r.positions.rows(), mesh.positions.rows());
    EXPECT_TRUE(r.positions.allFinite()) << "non-finite output";
    EXPECT_TRUE(bit_identical(mesh, before)) << "fair() changed its input";
    return r;
}

inline bool has_warning(const Result& r, const std::string& part) {
    for (const std::string& w : r.warnings)
        if (contains(w, part)) return true;
    return false;
}

inline std::string warnings(const Result& r) {
    std::string s;
    for (const std::string& w : r.warnings) s += "[" + w + "] ";
    return s;
}

// Volume of the closed component made of `tris` (independent eq. 10, tests/engine/meshes.h).
inline double volume_of(const Positions& p, const std::vector<Triangle>& tris) {
    return meshes::volume(p, tris);
}

// The noisy sphere of the robustness tests: 642 vertices, 1280 faces.
inline TriangleMesh noisy_sphere(int levels = 3, double radius = 1.0, std::uint64_t seed = 61) {
    return meshes::radial_noise(meshes::icosphere(levels, radius), 0.03, seed);
}

// AddressSanitizer keeps freed memory in quarantine (256 MB by default): RSS figures mean nothing.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// Resident set size in bytes (Linux /proc/self/statm), -1 where unavailable.
inline long long resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    long long size = 0, resident = -1;
    if (!(statm >> size >> resident)) return -1;
    return resident * static_cast<long long>(sysconf(_SC_PAGESIZE));
}

}  // namespace robust
