// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Basic types shared by the whole engine.
//
// Conventions (hold everywhere in fairing/):
// - Positions are an n x 3 row-major matrix of doubles, one row per vertex (x, y, z), so the
//   three coordinates of a vertex sit next to each other and one sweep over a sparse matrix
//   serves all three right-hand sides.
// - Triangles are index triples into the positions, counter-clockwise seen from outside.
// - Every error the engine detects is thrown as fairing::Error with a message that names the
//   problem and how often it occurs. When a cleaning step repairs the input, the error carries
//   it as a fairing::Repair, named in neutral words in what(); front ends name the host's own
//   filter for it (fairing_parameters/repair_hints.h), the engine knows no host.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace fairing {

using Vec3 = Eigen::Vector3d;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangle = std::array<int, 3>;

// The cleaning step that makes refused input acceptable.
enum class Repair { None, NonManifoldEdges, NonManifoldVertices, DuplicateFaces, NonFiniteVertices };

// The repair in words that name no host: "repair the non-manifold edges".
inline const char* to_string(Repair r)
{
    switch (r) {
    case Repair::NonManifoldEdges: return "repair the non-manifold edges";
    case Repair::NonManifoldVertices: return "split the non-manifold vertices";
    case Repair::DuplicateFaces: return "remove the duplicated faces";
    case Repair::NonFiniteVertices: return "delete those vertices";
    case Repair::None: break;
    }
    return "";
}

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message)
        : std::runtime_error(message), problem_size_(message.size()), alternative_at_(0) {}

    // Input refused until a cleaning step repairs it. what() is
    // "<problem>; <to_string(repair)> first[, or <alternative>]".
    Error(const std::string& problem, Repair repair, const std::string& alternative = "")
        : std::runtime_error(problem + "; " + to_string(repair) + " first" +
                             (alternative.empty() ? "" : ", or " + alternative)),
          problem_size_(problem.size()),
          repair_(repair),
          alternative_at_(alternative.empty() ? 0 : what_size() - alternative.size())
    {
    }

    // What is wrong and how often, without the repair: "1 non-manifold edge (...)".
    std::string problem() const { return std::string(what(), problem_size_); }
    Repair repair() const noexcept { return repair_; }
    // Another way out than the repair ("choose another boundary mode"), or "".
    std::string alternative() const { return alternative_at_ ? what() + alternative_at_ : ""; }

private:
    std::size_t what_size() const noexcept { return std::char_traits<char>::length(what()); }

    // Offsets into what() rather than strings: copying an exception must not throw.
    std::size_t problem_size_;
    Repair repair_ = Repair::None;
    std::size_t alternative_at_;
};

}  // namespace fairing
