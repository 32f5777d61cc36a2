// Basic types shared by the whole engine.
//
// Conventions (hold everywhere in fairing/):
// - Positions are an n x 3 row-major matrix of doubles, one row per vertex (x, y, z), so the
//   three coordinates of a vertex sit next to each other and one sweep over a sparse matrix
//   serves all three right-hand sides.
// - Triangles are index triples into the positions, counter-clockwise seen from outside.
// - Every error the engine detects is thrown as fairing::Error with a message that names the
//   problem, how often it occurs and, where one exists, the MeshLab filter that repairs it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace fairing {

using Vec3 = Eigen::Vector3d;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangle = std::array<int, 3>;

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace fairing
