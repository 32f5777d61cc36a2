// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Implicit steps of any order solved by a sparse LDL^T instead of conjugate gradients (not
// installed).
//
// The systems are solver.h's, on the free rows f of an operator:
//   order 1:  A = D - lambda K_ff,               b = D x_f + lambda K_fc x_c
//   order 2:  A = D + lambda K_ff M_f^-1 K_ff,   b = D x_f - lambda K_ff M_f^-1 K_fc x_c
//   order p:  A = D + lambda (-1)^p (K_ff M_f^-1)^(p-1) K_ff,
//             b = D x_f + lambda (-1)^(p-1) (K_ff M_f^-1)^(p-1) K_fc x_c
// (the fixed columns c moved to the right; P zeroes L at fixed rows, so L^p = L P L ... P L). A
// is symmetric positive definite whenever D > 0, and Eigen's SimplicialLDLT (approximate minimum
// degree ordering) factors it. A direct solve is backward stable: its residual is rounding's,
// however ill-conditioned A is, where CG on the same system stalls (needle triangles, whose
// cotangent weights reach the cap, or loops far finer than the mean edge).
//
// Used for the boundary loops' cyclic bands (always: their factor is linear in the loop's
// length, a band of width 2p + 1; the iterative L^4 solve of libcgal-demo's open turbine blade's
// loops stalled at residuals of 2e-8 to 4e-5), for their automatic time step (loop_strength.h,
// every implicit order), and as the surface's fallback when its iterative solve does not
// converge on a mesh small enough to factor (fairing.cpp, Run::integrate; the factor of an L^p
// system couples p rings, so its fill grows faster than the mesh).
#pragma once

#include "fairing/operators.h"
#include "fairing/solver.h"

#include <Eigen/Sparse>

#include <limits>
#include <vector>

namespace fairing {
namespace detail {

using SparseMatrix = Eigen::SparseMatrix<double>;

// A(lambda) = D + lambda C on the free rows, and g, the fixed columns' part of the right-hand
// side per unit lambda. `a` holds A's storage (C's pattern, whose diagonal is structural) and
// `diagonal` where each diagonal entry lies, so that A(lambda) is written over one allocation.
struct DirectSystem {
    SparseMatrix c;
    Eigen::VectorXd d;
    Eigen::MatrixXd g;
    SparseMatrix a;
    std::vector<Eigen::Index> diagonal;
};

// The system of `op` on rows (index: each row of op's position in rows, or -1), at positions y
// (only the fixed columns' values are read). D = M / w (weight null: w = 1), or
// `system_diagonal` (per row of op) when given.
DirectSystem direct_system(const SparseOperator& op, const Positions& y,
                           const std::vector<int>& rows, const std::vector<int>& index,
                           const std::vector<double>* weight, int order,
                           const std::vector<double>* system_diagonal = nullptr);

// `steps` steps of lambda from y (the free rows' positions): x, and in rhs the last step's
// right-hand side. ldlt must have analysed s.a's pattern. false if A did not factor or the
// result is not finite.
bool take_direct_steps(DirectSystem& s, double lambda, int steps, const Eigen::MatrixXd& y,
                       Eigen::SimplicialLDLT<SparseMatrix>& ldlt, Eigen::MatrixXd& x,
                       Eigen::MatrixXd& rhs);

// The largest over the three columns of ||residual|| / ||b|| (0 for a zero column of b).
double relative_residual(const Eigen::MatrixXd& residual, const Eigen::MatrixXd& b);

// One step of `system` (order 1 to 4, D = system.diagonal): x's free rows take the result. A
// result over max_residual is solved again with each part of the free rows that no fixed row
// touches moved to its centroid (the step commutes with translating such a part), and the
// residual of that counts against the full right-hand side.
// Stats: no iterations, `direct`, the relative residual max over the columns of
// ||A x - b|| / ||b|| (measured, not a stopping rule). converged = false with x untouched when
// the system does not factor, has a free row without a positive diagonal, or leaves a residual
// above max_residual: rounding's, but amplified by the decades M^-1 spans, p - 1 times in L^p,
// and the error of the result with it (fairing.cpp, kDirectResidual).
SolveStats solve_directly(const LinearSystem& system, Positions& x,
                          double max_residual = std::numeric_limits<double>::infinity());

}  // namespace detail
}  // namespace fairing
