// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The paper's three Laplacians in symmetric form L = M^-1 K (operators.h): structure of K and M,
// definiteness of the implicit systems, and eq. 7 / eq. 11 / eq. 14 recomputed by hand.
#include "meshes.h"

#include "fairing/half_edge.h"
#include "fairing/operators.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

using fairing::HalfEdgeMesh;
using fairing::Operator;
using fairing::SparseOperator;
using fairing::TriangleMesh;
using meshes::Positions;
using meshes::Vec3;

namespace {

using meshes::kOperators;

struct Assembled {
    HalfEdgeMesh mesh;
    SparseOperator op;
};

Assembled assemble(Operator op, const TriangleMesh& m, bool normalized = false,
                   fairing::AssemblyReport* report = nullptr) {
    Assembled a{HalfEdgeMesh::build(m.positions, m.triangles), {}};
    a.op = fairing::assemble(op, a.mesh, m.positions, normalized, report);
    return a;
}

// Sum of the CSR weights stored for each ordered pair (i, j).
std::map<std::pair<int, int>, double> weight_map(const SparseOperator& op) {
    std::map<std::pair<int, int>, double> w;
    for (int i = 0; i < op.size(); ++i)
        for (int e = op.row_start[i]; e < op.row_start[i + 1]; ++e) w[{i, op.column[e]}] += op.weight[e];
    return w;
}

double weight(const std::map<std::pair<int, int>, double>& w, int i, int j) {
    auto it = w.find({i, j});
    return it == w.end() ? 0.0 : it->second;
}

TriangleMesh noisy_sphere() { return meshes::radial_noise(meshes::icosphere(2), 0.05, 21); }
TriangleMesh noisy_grid() { return meshes::noisy_open_grid(7, 0.2, 0.3, 4); }

double angle_at(const Vec3& apex, const Vec3& a, const Vec3& b) {
    return std::acos((a - apex).normalized().dot((b - apex).normalized()));
}

}  // namespace

// K is given by its off-diagonal weights: structure, symmetry, zero row sums, the diagonal.
TEST(Operators, SymmetricZeroRowSumsAndDiagonal) {
    for (const TriangleMesh& m : {noisy_sphere(), noisy_grid()}) {
        for (Operator op : kOperators) {
            SCOPED_TRACE(fairing::to_string(op));
            const Assembled a = assemble(op, m);
            const int n = static_cast<int>(m.positions.rows());
            ASSERT_EQ(a.op.size(), n);
            ASSERT_EQ(static_cast<int>(a.op.row_start.size()), n + 1);
            ASSERT_EQ(a.op.row_start[0], 0);
            ASSERT_EQ(static_cast<size_t>(a.op.row_start[n]), a.op.column.size());
            ASSERT_EQ(a.op.column.size(), a.op.weight.size());

            const auto nb = meshes::neighbours(m.triangles, n);
            const auto w = weight_map(a.op);
            double scale = 0;
            for (const auto& kv : w) scale = std::max(scale, std::abs(kv.second));
            for (int i = 0; i < n; ++i) {
                std::set<int> columns;
                double sum = 0;
                for (int e = a.op.row_start[i]; e < a.op.row_start[i + 1]; ++e) {
                    const int j = a.op.column[e];
                    ASSERT_GE(j, 0);
                    ASSERT_LT(j, n);
                    ASSERT_NE(j, i) << "K is stored by its off-diagonal part only";
                    ASSERT_TRUE(std::isfinite(a.op.weight[e]));
                    columns.insert(j);
                    sum += a.op.weight[e];
                }
                // Row i couples i with its one-ring exactly.
                EXPECT_EQ(columns, nb[i]) << "row " << i;
                // K_ii = -sum_j w_ij: the rows of K sum to zero.
                EXPECT_NEAR(a.op.diagonal(i), -sum, 1e-13 * scale * nb[i].size()) << "row " << i;
                EXPECT_GT(a.op.mass[i], 0.0) << "row " << i;
                for (int j : nb[i])
                    EXPECT_NEAR(weight(w, i, j), weight(w, j, i), 1e-14 * scale)
                        << "w_ij != w_ji for " << i << ", " << j;
            }
        }
    }
}

// apply_k and apply_l agree with the dense K and M^-1 K; constants are in the kernel.
TEST(Operators, ApplyMatchesDenseMatrix) {
    meshes::Rng rng(9);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const TriangleMesh m = noisy_sphere();
        const Assembled a = assemble(op, m);
        const int n = a.op.size();
        const Eigen::MatrixXd K = meshes::dense_k(a.op);
        const Eigen::VectorXd M = meshes::mass_vector(a.op);
        Positions x(n, 3);
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) x(i, k) = rng.symmetric();
        Positions y(n, 3), l(n, 3);
        a.op.apply_k(x, y);
        a.op.apply_l(x, l);
        const Eigen::MatrixXd expected_k = K * meshes::to_dense(x);
        const Eigen::MatrixXd expected_l = M.cwiseInverse().asDiagonal() * expected_k;
        const double scale = K.cwiseAbs().maxCoeff();
        EXPECT_LT((meshes::to_dense(y) - expected_k).cwiseAbs().maxCoeff(), 1e-12 * scale);
        EXPECT_LT((meshes::to_dense(l) - expected_l).cwiseAbs().maxCoeff(),
                  1e-12 * expected_l.cwiseAbs().maxCoeff());

        Positions constant(n, 3);
        for (int i = 0; i < n; ++i) constant.row(i) << 3.0, -2.0, 0.5;
        a.op.apply_k(constant, y);
        EXPECT_LT(meshes::to_dense(y).cwiseAbs().maxCoeff(), 1e-12 * scale * 3.0 * 8);
    }
}

// K is negative semi-definite, so M - lambda_dt K (order 1) and M + lambda_dt K M^-1 K (order 2)
// are symmetric positive definite for every lambda_dt >= 0.
TEST(Operators, ImplicitSystemsAreSymmetricPositiveDefinite) {
    for (const TriangleMesh& m : {noisy_sphere(), noisy_grid()}) {
        for (Operator op : kOperators) {
            SCOPED_TRACE(fairing::to_string(op));
            const Assembled a = assemble(op, m);
            const Eigen::MatrixXd K = meshes::dense_k(a.op);
            const Eigen::VectorXd M = meshes::mass_vector(a.op);
            const double scale = K.cwiseAbs().maxCoeff();
            EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-13 * scale);

            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (K + K.transpose()));
            EXPECT_LT(eig.eigenvalues().maxCoeff(), 1e-10 * scale) << "K must be NSD";

            // lambda_dt in the operator's units: L = M^-1 K ~ 1/h^2 for the two geometric ones.
            const double h = meshes::mean_edge_length(m.positions, m.triangles);
            const double unit = op == Operator::Umbrella ? 1.0 : h * h;
            for (double t : {1e-3, 1.0, 1e3}) {
                const double lambda_dt = t * unit;
                const Eigen::MatrixXd A1 = Eigen::MatrixXd(M.asDiagonal()) - lambda_dt * K;
                const Eigen::MatrixXd A2 = Eigen::MatrixXd(M.asDiagonal()) +
                                           lambda_dt * K * M.cwiseInverse().asDiagonal() * K;
                for (const Eigen::MatrixXd* A : {&A1, &A2}) {
                    const Eigen::MatrixXd S = 0.5 * (*A + A->transpose());
                    EXPECT_LT((*A - A->transpose()).cwiseAbs().maxCoeff(),
                              1e-12 * A->cwiseAbs().maxCoeff());
                    Eigen::LLT<Eigen::MatrixXd> llt(S);
                    EXPECT_EQ(llt.info(), Eigen::Success) << "lambda_dt = " << lambda_dt;
                    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e(S);
                    EXPECT_GT(e.eigenvalues().minCoeff(), 0.0) << "lambda_dt = " << lambda_dt;
                }
            }
        }
    }
}

// Eq. 7 on the regular valence-6 torus: L x_i = (1/6) sum over the six neighbour offsets.
TEST(Operators, UmbrellaEqualsEquation7OnRegularGrid) {
    const int nu = 9, nv = 7;
    TriangleMesh m = meshes::torus_grid(nu, nv);
    const Assembled a = assemble(Operator::Umbrella, m);
    Positions l(a.op.size(), 3);
    a.op.apply_l(m.positions, l);
    for (int v = 0; v < nv; ++v) {
        for (int u = 0; u < nu; ++u) {
            const int i = meshes::torus_index(u, v, nu, nv);
            EXPECT_DOUBLE_EQ(a.op.mass[i], 6.0);
            Vec3 expected = Vec3::Zero();
            for (const auto& d : meshes::torus_neighbour_offsets())
                expected += meshes::row(m.positions, meshes::torus_index(u + d[0], v + d[1], nu, nv)) -
                            meshes::row(m.positions, i);
            expected /= 6.0;
            EXPECT_LT((meshes::row(l, i) - expected).norm(), 1e-13) << "u = " << u << " v = " << v;
        }
    }
}

// Eq. 7 on an irregular mesh: weight 1 per edge, mass = valence m.
TEST(Operators, UmbrellaWeightsAndValence) {
    for (const TriangleMesh& m : {noisy_sphere(), noisy_grid()}) {
        const Assembled a = assemble(Operator::Umbrella, m);
        const auto nb = meshes::neighbours(m.triangles, static_cast<int>(m.positions.rows()));
        const auto w = weight_map(a.op);
        for (int i = 0; i < a.op.size(); ++i) {
            EXPECT_EQ(a.op.mass[i], static_cast<double>(nb[i].size()));
            for (int j : nb[i]) EXPECT_EQ(weight(w, i, j), 1.0);
        }
        // Normalized umbrella (section 5.5): no change.
        const Assembled b = assemble(Operator::Umbrella, m, true);
        for (int i = 0; i < b.op.size(); ++i)
            EXPECT_EQ(b.op.mass[i], static_cast<double>(nb[i].size()));
    }
}

// Eq. 11: L x_i = (2/E) sum_j (x_j - x_i)/|e_ij|, E = sum_j |e_ij|.
TEST(Operators, ScaleDependentEqualsEquation11) {
    for (const TriangleMesh& m : {noisy_sphere(), noisy_grid()}) {
        const Assembled a = assemble(Operator::ScaleDependent, m);
        const auto nb = meshes::neighbours(m.triangles, static_cast<int>(m.positions.rows()));
        const auto w = weight_map(a.op);
        Positions l(a.op.size(), 3);
        a.op.apply_l(m.positions, l);
        for (int i = 0; i < a.op.size(); ++i) {
            const Vec3 xi = meshes::row(m.positions, i);
            double E = 0;
            Vec3 sum = Vec3::Zero();
            for (int j : nb[i]) {
                const Vec3 e = meshes::row(m.positions, j) - xi;
                E += e.norm();
                sum += e / e.norm();
                EXPECT_NEAR(weight(w, i, j), 1.0 / e.norm(), 1e-13 / e.norm());
            }
            EXPECT_NEAR(a.op.mass[i], E / 2.0, 1e-13 * E);
            const Vec3 expected = 2.0 / E * sum;
            EXPECT_LT((meshes::row(l, i) - expected).norm(), 1e-12 * expected.norm() + 1e-13)
                << "vertex " << i;
        }
    }
}

// Eq. 14 on a hand-made, non-planar fan of five triangles around vertex 0 (one obtuse angle at
// the center): L x_0 = (1/4A) sum_j (cot alpha_j + cot beta_j)(x_j - x_0), A the one-ring area.
// Angles are measured with acos, independently of any cross/dot cotangent formula.
TEST(Operators, CurvatureFlowEqualsEquation14OnFan) {
    const double deg = meshes::kPi / 180.0;
    const double angles[5] = {0, 70, 200, 250, 310};
    const double radii[5] = {1.0, 0.8, 1.2, 0.9, 1.1};
    const double heights[5] = {0.0, 0.1, -0.05, 0.2, 0.0};
    TriangleMesh m;
    m.positions.resize(6, 3);
    m.positions.row(0) << 0.05, -0.02, 0.3;
    for (int k = 0; k < 5; ++k)
        m.positions.row(k + 1) << radii[k] * std::cos(angles[k] * deg),
            radii[k] * std::sin(angles[k] * deg), heights[k];
    for (int k = 0; k < 5; ++k) m.triangles.push_back({0, 1 + k, 1 + (k + 1) % 5});

    const Assembled a = assemble(Operator::CurvatureFlow, m);
    const auto w = weight_map(a.op);
    auto x = [&](int i) { return meshes::row(m.positions, i); };
    auto rim = [](int k) { return 1 + ((k % 5) + 5) % 5; };

    double A = 0;
    for (const auto& t : m.triangles) A += meshes::triangle_area(m.positions, t);
    Vec3 expected = Vec3::Zero();
    for (int k = 0; k < 5; ++k) {
        const int j = rim(k);
        // Edge (0, j) is shared by triangles (0, j-1, j) and (0, j, j+1); the opposite angles are
        // at j-1 and at j+1.
        const double alpha = angle_at(x(rim(k - 1)), x(0), x(j));
        const double beta = angle_at(x(rim(k + 1)), x(0), x(j));
        const double wij = 1.0 / std::tan(alpha) + 1.0 / std::tan(beta);
        EXPECT_NEAR(weight(w, 0, j), wij, 1e-12) << "center - rim " << k;
        expected += wij * (x(j) - x(0));
        // Rim edge (j, j+1): one triangle, the opposite angle is at the center.
        const double gamma = angle_at(x(0), x(j), x(rim(k + 1)));
        EXPECT_NEAR(weight(w, j, rim(k + 1)), 1.0 / std::tan(gamma), 1e-12) << "rim " << k;
        // Rim mass: 4 x the area of its two triangles.
        const double Aj = meshes::triangle_area(m.positions, {0, rim(k - 1), j}) +
                          meshes::triangle_area(m.positions, {0, j, rim(k + 1)});
        EXPECT_NEAR(a.op.mass[j], 4.0 * Aj, 1e-13);
    }
    // One center angle (130 degrees apart in the plan) is obtuse: its cotangent is negative and
    // eq. 14 keeps it.
    EXPECT_LT(weight(w, rim(1), rim(2)), 0.0);
    EXPECT_NEAR(a.op.mass[0], 4.0 * A, 1e-13);
    expected /= 4.0 * A;
    Positions l(6, 3);
    a.op.apply_l(m.positions, l);
    EXPECT_LT((meshes::row(l, 0) - expected).norm(), 1e-12 * expected.norm());
}

// Closed forms: regular tetrahedron and octahedron (all angles 60 degrees: w = 2 cot 60 =
// 2/sqrt 3; mass 4A = 4 x valence x sqrt(3)/4 a^2) and a unit square cut along a diagonal
// (opposite angles 90 degrees: w = 0 on the diagonal; 45 degrees: w = 1 on the sides).
TEST(Operators, CurvatureFlowClosedForms) {
    {
        const double a = 2.0 * std::sqrt(2.0);  // edge length of the tetrahedron below
        TriangleMesh m;
        m.positions.resize(4, 3);
        m.positions << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
        m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
        const Assembled s = assemble(Operator::CurvatureFlow, m);
        for (int i = 0; i < 4; ++i) {
            EXPECT_NEAR(s.op.mass[i], 3.0 * std::sqrt(3.0) * a * a, 1e-12);
            for (int e = s.op.row_start[i]; e < s.op.row_start[i + 1]; ++e)
                EXPECT_NEAR(s.op.weight[e], 2.0 / std::sqrt(3.0), 1e-14);
        }
    }
    {
        TriangleMesh m;
        m.positions.resize(6, 3);
        m.positions << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
        m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
        const double a2 = 2.0;  // squared edge length
        const Assembled s = assemble(Operator::CurvatureFlow, m);
        for (int i = 0; i < 6; ++i) {
            EXPECT_NEAR(s.op.mass[i], 4.0 * std::sqrt(3.0) * a2, 1e-12);
            EXPECT_EQ(s.op.row_start[i + 1] - s.op.row_start[i], 4);
            for (int e = s.op.row_start[i]; e < s.op.row_start[i + 1]; ++e)
                EXPECT_NEAR(s.op.weight[e], 2.0 / std::sqrt(3.0), 1e-14);
        }
    }
    {
        TriangleMesh m;
        m.positions.resize(4, 3);
        m.positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
        m.triangles = {{0, 1, 2}, {0, 2, 3}};
        const Assembled s = assemble(Operator::CurvatureFlow, m);
        const auto w = weight_map(s.op);
        EXPECT_NEAR(weight(w, 0, 2), 0.0, 1e-15);
        EXPECT_NEAR(weight(w, 0, 1), 1.0, 1e-15);
        EXPECT_NEAR(weight(w, 1, 2), 1.0, 1e-15);
        EXPECT_NEAR(weight(w, 2, 3), 1.0, 1e-15);
        EXPECT_NEAR(weight(w, 3, 0), 1.0, 1e-15);
        EXPECT_NEAR(s.op.mass[0], 4.0, 1e-15);
        EXPECT_NEAR(s.op.mass[2], 4.0, 1e-15);
        EXPECT_NEAR(s.op.mass[1], 2.0, 1e-15);
        EXPECT_NEAR(s.op.mass[3], 2.0, 1e-15);
    }
}

// Section 5.2: the curvature normal of an interior vertex of a flat region is zero, whatever the
// triangulation; the umbrella and eq. 11 are not (they slide vertices in the plane).
TEST(Operators, CurvatureNormalVanishesOnFlatPatch) {
    const TriangleMesh m = meshes::irregular_plane(10);
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    const double h = meshes::mean_edge_length(m.positions, m.triangles);
    double umbrella_max = 0;
    for (Operator op : kOperators) {
        const SparseOperator s = fairing::assemble(op, he, m.positions);
        Positions l(s.size(), 3);
        s.apply_l(m.positions, l);
        double worst = 0;
        for (int i = 0; i < s.size(); ++i) {
            if (he.is_boundary_vertex(i)) continue;
            worst = std::max(worst, meshes::row(l, i).norm());
        }
        if (op == Operator::CurvatureFlow) {
            EXPECT_LT(worst * h, 1e-12);  // L in 1/length^2: |L x| h is dimensionless
        } else if (op == Operator::Umbrella) {
            umbrella_max = worst / h;  // dimensionless L: |L x| / h
        }
    }
    EXPECT_GT(umbrella_max, 1e-2);
}

// Section 5.5: normalized operators have mass_i = sum_j w_ij.
TEST(Operators, NormalizedMassIsRowSum) {
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const TriangleMesh m = noisy_sphere();
        const Assembled plain = assemble(op, m, false);
        const Assembled norm = assemble(op, m, true);
        ASSERT_EQ(plain.op.weight.size(), norm.op.weight.size());
        for (int i = 0; i < norm.op.size(); ++i) {
            double sum = 0;
            for (int e = norm.op.row_start[i]; e < norm.op.row_start[i + 1]; ++e)
                sum += norm.op.weight[e];
            EXPECT_NEAR(norm.op.mass[i], sum, 1e-13 * std::abs(sum));
            EXPECT_NEAR(norm.op.diagonal(i), plain.op.diagonal(i),
                        1e-13 * std::abs(plain.op.diagonal(i)));
        }
    }
}

// Units (operators.h): umbrella K, M dimensionless; scale-dependent K ~ 1/length, M ~ length;
// curvature K dimensionless, M ~ length^2.
TEST(Operators, UnitsUnderScaling) {
    const double s = 1e3;
    const TriangleMesh m = noisy_sphere();
    const TriangleMesh big = meshes::scaled(m, s);
    const struct {
        Operator op;
        double k, mass;
    } cases[] = {{Operator::Umbrella, 1, 1},
                 {Operator::ScaleDependent, 1 / s, s},
                 {Operator::CurvatureFlow, 1, s * s}};
    for (const auto& c : cases) {
        SCOPED_TRACE(fairing::to_string(c.op));
        const Assembled a = assemble(c.op, m), b = assemble(c.op, big);
        const auto wa = weight_map(a.op), wb = weight_map(b.op);
        ASSERT_EQ(wa.size(), wb.size());
        for (const auto& kv : wa)
            EXPECT_NEAR(weight(wb, kv.first.first, kv.first.second), c.k * kv.second,
                        1e-12 * std::abs(c.k * kv.second) + 1e-15);
        for (int i = 0; i < a.op.size(); ++i)
            EXPECT_NEAR(b.op.mass[i], c.mass * a.op.mass[i], 1e-12 * c.mass * a.op.mass[i]);
    }
}

// Faces of zero area contribute nothing to eq. 14 (section 5.4); they are counted.
TEST(Operators, CurvatureSkipsZeroAreaFaces) {
    // 4x3 integer grid, vertex (2,1) moved onto the diagonal (1,1)-(2,2): the triangle
    // (1,1) (2,1) (2,2) is degenerate (cotangents 0 and 180 degrees would be infinite).
    TriangleMesh m = meshes::grid(4, 3, 4.0, 3.0);
    const int moved = meshes::grid_index(2, 1, 4), p11 = meshes::grid_index(1, 1, 4);
    const int p22 = meshes::grid_index(2, 2, 4);
    m.positions.row(moved) << 1.5, 1.5, 0.0;
    fairing::AssemblyReport report;
    const Assembled a = assemble(Operator::CurvatureFlow, m, false, &report);
    EXPECT_EQ(report.zero_area_faces, 1);
    for (double v : a.op.weight) EXPECT_TRUE(std::isfinite(v));
    for (double v : a.op.mass) EXPECT_TRUE(std::isfinite(v));
    const auto w = weight_map(a.op);
    // Edge (1,1)-(2,2): only triangle (1,1) (2,2) (1,2) remains, right angle at (1,2): cot = 0.
    EXPECT_NEAR(weight(w, p11, p22), 0.0, 1e-14);
    // Edge (1,1)-moved: only triangle (1,0) (moved) (1,1) remains; at (1,0) the edges are
    // u = (0,1) and v = (0.5,1.5): cot = u.v / |u x v| = 1.5 / 0.5 = 3.
    EXPECT_NEAR(weight(w, p11, moved), 3.0, 1e-13);
}

// A closed part shrunk towards a point keeps the shape of its faces, so none of them has zero
// area, but the L^2 system's inverse mass overflows (fairing::kNegligibleArea). Below that share of
// the mean vertex area the curvature operator counts a vertex as massless, with its edges
// dropped; the other part's rows stay exactly what it has alone. Not so just above the bound,
// nor for the normalized operator, whose mass is its weights' sum (shape only).
TEST(Operators, CurvatureCountsNegligibleAreasAsMassless) {
    const TriangleMesh big = meshes::icosphere(2);
    const int nb = static_cast<int>(big.positions.rows());
    const Assembled alone = assemble(Operator::CurvatureFlow, big);
    for (double size : {1e-7, 1e-5}) {
        SCOPED_TRACE(testing::Message() << "small part " << size << " across");
        const TriangleMesh m = meshes::merge(
            big, meshes::translated(meshes::scaled(meshes::icosphere(1), size), Vec3(3, 0, 0)));
        const int n = static_cast<int>(m.positions.rows());
        const bool negligible = size == 1e-7;  // areas 5e-14 and 5e-10 of the mean
        fairing::AssemblyReport report;
        const Assembled a = assemble(Operator::CurvatureFlow, m, false, &report);
        EXPECT_EQ(report.zero_area_faces, 0);
        EXPECT_EQ(report.massless_vertices, 0);
        EXPECT_EQ(report.negligible_vertices, negligible ? n - nb : 0);
        for (int v = nb; v < n; ++v) {
            EXPECT_EQ(a.op.mass[v] == 0, negligible) << "vertex " << v;
            EXPECT_EQ(a.op.row_start[v + 1] == a.op.row_start[v], negligible) << "vertex " << v;
        }
        for (int v = 0; v < nb; ++v) EXPECT_EQ(a.op.mass[v], alone.op.mass[v]) << "vertex " << v;
        const std::vector<double> big_weights(a.op.weight.begin(),
                                              a.op.weight.begin() + a.op.row_start[nb]);
        EXPECT_EQ(big_weights, alone.op.weight);
        fairing::AssemblyReport normalized;
        assemble(Operator::CurvatureFlow, m, true, &normalized);
        EXPECT_EQ(normalized.negligible_vertices, 0);
    }
}

TEST(Operators, MeanEdgeLengthByHand) {
    // 4x3 unit cells cut by one diagonal each: 16 + 15 unit edges and 12 diagonals of sqrt 2.
    const TriangleMesh m = meshes::grid(4, 3, 4.0, 3.0);
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    EXPECT_NEAR(fairing::mean_edge_length(he, m.positions), (31.0 + 12.0 * std::sqrt(2.0)) / 43.0,
                1e-15);
}

// Section 5.3: eq. 11 restricted to the two boundary neighbours of each boundary vertex.
TEST(Operators, BoundaryCurveOperator) {
    const TriangleMesh m = noisy_grid();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    const SparseOperator s = fairing::assemble_boundary_curve(he, m.positions);
    const auto loops = meshes::boundary_loops(m.triangles);
    ASSERT_EQ(loops.size(), 1u);
    const std::vector<int>& loop = loops[0];
    std::vector<char> on_loop(m.positions.rows(), 0);
    for (int v : loop) on_loop[v] = 1;
    ASSERT_EQ(s.size(), static_cast<int>(m.positions.rows()));
    for (int i = 0; i < s.size(); ++i) {
        if (!on_loop[i]) {
            EXPECT_EQ(s.row_start[i + 1] - s.row_start[i], 0) << "interior row " << i;
            EXPECT_EQ(s.mass[i], 0.0) << "interior row " << i;
        }
    }
    const auto w = weight_map(s);
    const int L = static_cast<int>(loop.size());
    for (int k = 0; k < L; ++k) {
        const int i = loop[k], prev = loop[(k + L - 1) % L], next = loop[(k + 1) % L];
        EXPECT_EQ(s.row_start[i + 1] - s.row_start[i], 2) << "boundary row " << i;
        const double lp = (meshes::row(m.positions, i) - meshes::row(m.positions, prev)).norm();
        const double ln = (meshes::row(m.positions, i) - meshes::row(m.positions, next)).norm();
        EXPECT_NEAR(weight(w, i, prev), 1.0 / lp, 1e-13 / lp);
        EXPECT_NEAR(weight(w, i, next), 1.0 / ln, 1e-13 / ln);
        EXPECT_NEAR(s.mass[i], (lp + ln) / 2.0, 1e-13);
    }
}

namespace {

// Above detail::kParallelRows vertices, with holes, zero-area faces, a vertex whose whole star is
// degenerate (massless) and an edge much shorter than the mean (floored).
TriangleMesh large_untidy_mesh() {
    TriangleMesh m = meshes::radial_noise(meshes::icosphere(7), 0.002);
    std::vector<fairing::Triangle> kept;
    for (std::size_t f = 0; f < m.triangles.size(); ++f)
        if (f % 211 != 0) kept.push_back(m.triangles[f]);
    m.triangles = kept;
    const auto ring = meshes::neighbours(m.triangles, static_cast<int>(m.positions.rows()));
    for (int v : ring[1000]) m.positions.row(v) = m.positions.row(1000);
    m.positions.row(20000) = m.positions.row(20001) + 1e-9 * m.positions.row(20001);
    return m;
}

void expect_same_operator(const SparseOperator& a, const SparseOperator& b) {
    EXPECT_EQ(a.row_start, b.row_start);
    EXPECT_EQ(a.column, b.column);
    // Bitwise: the same sums in the same order.
    EXPECT_EQ(a.weight, b.weight);
    EXPECT_EQ(a.mass, b.mass);
}

}  // namespace

// Assembly splits its passes over threads on large meshes; the result must not depend on it.
TEST(Operators, SameOperatorsOnAnyNumberOfThreads) {
    const TriangleMesh m = large_untidy_mesh();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles, 2);
    const double mean = fairing::mean_edge_length(he, m.positions, 1);
    for (Operator op : kOperators)
        for (bool normalized : {false, true}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << (normalized ? " normalized" : ""));
            fairing::AssemblyReport r1, r;
            const SparseOperator one = fairing::assemble(op, he, m.positions, normalized, &r1, 1);
            if (op == Operator::CurvatureFlow) {
                EXPECT_GT(r1.zero_area_faces, 0);
                EXPECT_GT(r1.massless_vertices, 0);
            }
            if (op == Operator::ScaleDependent) {
                EXPECT_GT(r1.floored_edges, 0);
            }
            for (int threads : {2, 3, 0}) {
                SCOPED_TRACE(testing::Message() << threads << " threads");
                expect_same_operator(one, fairing::assemble(op, he, m.positions, normalized, &r, threads));
                EXPECT_EQ(r.zero_area_faces, r1.zero_area_faces);
                EXPECT_EQ(r.floored_edges, r1.floored_edges);
                EXPECT_EQ(r.massless_vertices, r1.massless_vertices);
                EXPECT_EQ(r.needle_faces, r1.needle_faces);
            }
        }
    const SparseOperator curve = fairing::assemble_boundary_curve(he, m.positions, 1);
    EXPECT_GT(curve.column.size(), 0u);
    for (int threads : {2, 3, 0}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        expect_same_operator(curve, fairing::assemble_boundary_curve(he, m.positions, threads));
        EXPECT_EQ(fairing::mean_edge_length(he, m.positions, threads), mean);
    }
}

// On a mesh of fewer than 16,384 half-edges the mean edge length is the plain running sum.
TEST(Operators, MeanEdgeLengthOfASmallMeshIsTheRunningSum) {
    const TriangleMesh m = noisy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    double sum = 0;
    int count = 0;
    for (int h = 0; h < he.num_half_edges(); ++h)
        if (he.twin(h) < 0 || he.twin(h) > h) {
            sum += (m.positions.row(he.to(h)) - m.positions.row(he.from(h))).norm();
            ++count;
        }
    EXPECT_EQ(fairing::mean_edge_length(he, m.positions), sum / count);
}

// Needles (operators.cpp, kCotangentCap): a T-vertex 1e-7 off the diagonal of its quad makes two
// faces with an angle of ~1e-7 (cotangents ~1e7) and one of ~pi. Their cotangents are capped, so
// every weight stays within the cap's reach (an edge joins a capped corner, <= kCotangentCap,
// and at most one exact corner across it, |cot| < 10 on this grid), the operator
// stays negative semi-definite (x . K x <= 0 for any x), and a face that is no sliver keeps its
// exact weights: the same mesh with the T-vertex 0.05 off (an angle of 5.7 degrees, cotangent
// 10) has no needle and its weights below the cap. 0.013 off makes a sliver that is no needle
// (angles of 1.5 degrees, cotangents 38): capped too, since such slivers stall the solves.
TEST(Operators, NeedleCotangentsAreCappedAndStayNegativeSemiDefinite) {
    for (double off : {1e-7, 0.013, 0.05}) {
        SCOPED_TRACE(testing::Message() << "offset " << off);
        TriangleMesh m = meshes::grid(8, 6, 8, 6);
        meshes::Rng rng(4);
        for (int i = 0; i < m.positions.rows(); ++i) m.positions(i, 2) = 0.3 * rng.symmetric();
        const int a = meshes::grid_index(2, 2, 8), moved = meshes::grid_index(3, 2, 8);
        const int c = meshes::grid_index(3, 3, 8);
        m.positions.row(a) << 2.0, 2.0, 0.0;
        m.positions.row(c) << 3.0, 3.0, 0.0;
        m.positions.row(moved) << 2.5 + off, 2.5 - off, 0.0;
        const HalfEdgeMesh mesh = HalfEdgeMesh::build(m.positions, m.triangles);
        fairing::AssemblyReport report;
        const SparseOperator op =
            fairing::assemble(Operator::CurvatureFlow, mesh, m.positions, false, &report);
        if (off < 1e-3) EXPECT_GE(report.needle_faces, 1);
        else EXPECT_EQ(report.needle_faces, 0);
        double largest = 0;
        for (int i = 0; i < op.size(); ++i)
            for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
                if (op.column[k] != i) largest = std::max(largest, std::abs(op.weight[k]));
        EXPECT_LE(largest, fairing::kCotangentCap + 10);
        if (off < 0.02) EXPECT_GT(largest, 0.9 * fairing::kCotangentCap);  // the sliver's edge
        else EXPECT_LT(largest, fairing::kCotangentCap);
        Positions x(op.size(), 3), kx;
        for (int trial = 0; trial < 20; ++trial) {
            for (int i = 0; i < x.rows(); ++i)
                for (int j = 0; j < 3; ++j) x(i, j) = rng.symmetric();
            op.apply_k(x, kx);
            EXPECT_LE((x.array() * kx.array()).sum(), 1e-9 * largest);
        }
    }
}

// Eq. 11 takes 1/|e| of an edge at least kShortEdge times the mean edge long: shorter edges
// (here 0.3 % of the mean, as strong steps leave them where thin parts collapse, and 0.005 %, a
// duplicated vertex) weigh as one of that length, in K and in the mass E/2, and only the second
// is counted as floored; an edge of 5 % keeps its exact weight.
TEST(Operators, ScaleDependentShortEdgesWeighAsTheFloor) {
    for (double fraction : {0.05, 0.003, 5e-5}) {
        SCOPED_TRACE(testing::Message() << "edge of " << fraction << " mean edges");
        TriangleMesh m = meshes::grid(6, 6);
        const int a = meshes::grid_index(3, 3, 6), b = meshes::grid_index(4, 3, 6);
        // b slides towards a until |ab| is `fraction` of the mesh's mean edge (which moves with it).
        double mean = 1, length = 1;
        for (int k = 0; k < 60; ++k) {
            m.positions.row(b) = m.positions.row(a);
            m.positions(b, 0) += fraction * mean;
            const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
            mean = fairing::mean_edge_length(he, m.positions);
            length = (m.positions.row(b) - m.positions.row(a)).norm();
        }
        ASSERT_NEAR(length / mean, fraction, 1e-9 * fraction);
        fairing::AssemblyReport report;
        const Assembled s = assemble(Operator::ScaleDependent, m, false, &report);
        const auto w = weight_map(s.op);
        const double counted = std::max(length, fairing::kShortEdge * mean);
        EXPECT_NEAR(weight(w, a, b), 1.0 / counted, 1e-12 / counted);
        EXPECT_NEAR(weight(w, b, a), 1.0 / counted, 1e-12 / counted);
        EXPECT_LE(weight(w, a, b), 1.0 / (fairing::kShortEdge * mean) * (1 + 1e-12));
        const auto nb = meshes::neighbours(m.triangles, static_cast<int>(m.positions.rows()));
        double E = 0;
        for (int j : nb[a]) {
            const double e = (meshes::row(m.positions, j) - meshes::row(m.positions, a)).norm();
            E += std::max(e, fairing::kShortEdge * mean);
        }
        EXPECT_NEAR(s.op.mass[a], E / 2, 1e-13 * E);
        EXPECT_EQ(report.floored_edges, fraction < fairing::kDuplicateEdge ? 1 : 0);
        if (fraction > fairing::kShortEdge) {
            EXPECT_NEAR(weight(w, a, b), 1.0 / length, 1e-12 / length);
        }
    }
}

// The umbrella's K has every weight 1 (eq. 7), which assembly records so that products skip
// reading them; the other operators' weights vary. Products with and without the shortcut give
// the same bits (1 * d = d).
TEST(Operators, UnitWeightsAreFlaggedAndSkippedExactly) {
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        const Assembled a = assemble(op, noisy_sphere());
        EXPECT_EQ(a.op.unit_weights, op == Operator::Umbrella);
        const Positions x = meshes::radial_noise(meshes::icosphere(2), 0.3, 5).positions;
        SparseOperator plain = a.op;
        plain.unit_weights = false;
        Positions fast, slow, fast_l, slow_l;
        a.op.apply_k(x, fast);
        plain.apply_k(x, slow);
        a.op.apply_l(x, fast_l);
        plain.apply_l(x, slow_l);
        ASSERT_EQ(fast.size(), slow.size());
        EXPECT_EQ(0, std::memcmp(fast.data(), slow.data(), sizeof(double) * fast.size()));
        EXPECT_EQ(0, std::memcmp(fast_l.data(), slow_l.data(), sizeof(double) * fast_l.size()));
        EXPECT_GT(fast.norm(), 0);
    }
}
