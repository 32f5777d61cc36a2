// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Smoothed-aggregation algebraic multigrid (Vanek, Mandel, Brezina 1996) as a preconditioner
// for the implicit systems (not installed).
//
// Systems, on the free rows (K_ff: K restricted to the free rows and columns, with the full
// diagonal K_ii, as in solver.h; vectors are zero on the fixed rows):
//
//   Kind::Real           B = D - a K_ff        (the first-order system, a = lambda_dt), SPD
//   Kind::Complex        B = D + i a K_ff      (the L^2 step's complex factor, a = sqrt(lambda_dt),
//                                               complex_factor.h), complex symmetric
//
// The real V-cycle of D - a K_ff applied to the real and imaginary parts alike also
// preconditions the complex system (its spectrum then lies on the segment [1, i]), but worse:
// measured on the 1.2 M-face bunny (curvature L^2, 1 thread) 47 / 62 COCG iterations and
// 6.12 / 7.95 s at time steps 22.5 / 360 against the complex hierarchy's 31 / 44 and
// 4.75 / 6.36 s (bench/results/issue12/preconditioners.md).
//
// Hierarchy: built once from the real SPD matrix A = D - a K_ff. Aggregates of strongly
// coupled rows (greedy, in row order: the vertex order is a space-filling curve, so aggregates
// are compact), near-null space the constants (K 1 = 0), tentative prolongator = aggregate
// indicator, smoothed once by damped Jacobi on the filtered matrix, P = (I - w D_F^-1 A_F) P_tent
// (A_F: A with its repelling couplings A_ij > 0, from obtuse angles, lumped onto the diagonal),
// w = 4 / (3 rho), rho a Gershgorin bound of rho(D_F^-1 A_F) (the smaller of the row-scaled and
// the symmetrically scaled one). Every level keeps the mass and stiffness parts apart (P^T D P
// and P^T K P), so the complex levels are P^T D P + i a P^T K P: the same real hierarchy,
// Galerkin coarse operators of the complex matrix. The coarsest level (at most kCoarsest rows)
// is solved exactly by dense LU.
//
// Cycle: one V-cycle with smoothing sweeps before and after the coarse correction, started
// from zero: on the finest level one block Gauss-Seidel sweep each way (forward, then backward:
// sweeps.h; where its blocks hold most couplings, else a damped Jacobi sweep), below damped
// Jacobi sweeps, two for Kind::Real (weight 1.85 / rho) and four for Kind::Complex (1.7 / rho,
// with the complex diagonal); rho is a Gershgorin bound on the level's own matrix, for Complex
// on the moduli |mass + i a stiff| (a bound on mass - a stiff, which cancels on the coarse
// levels, once made the cycle stall at some time steps: multigrid.cpp, jacobi_bound).
// Pre and post smoothing are transposes of each other and the coarse solve is exact, so the
// cycle is a symmetric (Real) or complex-symmetric (Complex) linear operator: valid for CG and
// COCG. Gauss-Seidel on the finest level took up to a quarter fewer cycles (3-26 %) at the same
// two passes over K, 5-19 % less time on eight of nine runs and 3 % more on the torus'
// one-click umbrella step (1 M-face torus and 1.2 M-face bunny, first order and L^2;
// bench/results/issue12/preconditioners.md, "Gauss-Seidel smoothing").
//
// Determinism: set-up is sequential; in the cycle every row of every level is computed alone
// (restriction by the stored rows of P^T), so the result has the same bits on any number of
// threads.
#pragma once

#include "fairing/operators.h"

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace fairing {
namespace detail {

class Multigrid {
public:
    enum class Kind { Real, Complex };

    // diagonal: D_i (> 0 on the free rows); free: nonzero = unknown; a > 0. op, diagonal and
    // free must outlive the Multigrid. gauss_seidel: smooth the finest level by block
    // Gauss-Seidel where it applies (sweeps.h), else by damped Jacobi.
    Multigrid(const SparseOperator& op, const std::vector<double>& diagonal,
              const std::vector<char>& free, double a, Kind kind, bool gauss_seidel = true);
    bool gauss_seidel() const;  // the finest level is smoothed by Gauss-Seidel
    ~Multigrid();
    Multigrid(const Multigrid&) = delete;
    Multigrid& operator=(const Multigrid&) = delete;

    // z ~ B^-1 r by one V-cycle. r and z are row-major with width() doubles per row: 3 for
    // Real (x, y, z), 6 for Complex (re x, y, z, im x, y, z). z is zero on the fixed rows; r
    // there is ignored. Returns the unconjugated products r^T z per column, summed in fixed
    // blocks: Real in [0..2]; Complex re in [0..2], im in [3..5]. work: width() doubles per
    // row of scratch (the solvers lend a vector that is free at that point, which saves one).
    std::array<double, 6> apply(const double* r, double* z, double* work);

    int width() const;
    int levels() const;       // including the finest and the dense coarsest
    std::size_t bytes() const;  // memory held (hierarchy and work vectors)

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace detail
}  // namespace fairing
