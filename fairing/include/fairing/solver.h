// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Preconditioned conjugate gradients for the symmetric positive definite systems of
// implicit fairing (Appendix A, with CG in place of BiCG since the system is symmetric):
//
//   order 1:  A = D - lambda_dt K              (eq. 9 multiplied by M)
//   order 2:  A = D + lambda_dt K P M^-1 K     (section 2.6 multiplied by M), applied matrix-free
//
// with D_i = M_i / w_i (soft constraints, section 2.7). Rows with free[i] == 0 are hard
// constraints: x_i keeps its value, L(x_i) = 0 there as the paper imposes (P zeroes those rows,
// so L^2 = L P L), their terms move to the right-hand side, and the system on the free rows stays
// SPD. x, y and z are advanced together (one sweep over K serves all three), each
// with its own CG coefficients.
//
// Preconditioners. Jacobi (the diagonal of A) needs O(sqrt(kappa)) iterations, and kappa grows
// as lambda_dt: a step 16x stronger costs 4x. For order 2 the Factored preconditioner
//
//   B = (D - s K) D^-1 (D - s K),   s = sqrt(lambda_dt),   B = D - 2 s K + lambda_dt K D^-1 K
//
// matches A's L^2 term exactly when D = M (no soft weights); as -K is positive semi-definite,
// A <= B <= 2 A then (per eigenmode 1 + s^2 mu^2 <= (1 + s mu)^2 <= 2 (1 + s^2 mu^2)), so the
// outer iteration needs a handful of steps whatever lambda_dt. B^-1 is applied by two
// first-order solves with D - s K (Jacobi-CG to a loose relative tolerance), whose condition
// grows as s = sqrt(lambda_dt) only: the cost grows as lambda_dt^(1/4). The inexact inner solves
// make B^-1 slightly nonlinear, so the outer iteration is flexible CG (Notay's FCG(1): the new
// direction is A-orthogonalized against the previous one).
//
// Automatic, order 2 without soft weights (D = M on the free rows, the filters' default): the
// system factors over the complex numbers, A = (M + i s K) M^-1 (M - i s K), and the step is
// x = Re (M + i s K)^-1 b, one complex solve (COCG; src/complex_factor.h). Measured against
// Jacobi and Factored (bench/results/issue12/preconditioners.md): fewer iterations than Jacobi
// on the 10 k and 100 k tori at time steps 1 and 22.5 (curvature) and on the 1 M torus and the
// 1.2 M-face bunny at the defaults, and 1.2-1.9x less CPU time than Factored (the cheaper of
// the old paths) on those two, so it replaces both there. Its preconditioner: complex Jacobi on
// the mildest systems and for the umbrella, block symmetric Gauss-Seidel in Eisenstat's form
// from a stiffness of 3.5 (half the iterations at ~1.2x the price: 1.2-1.4x faster at the
// curvature default on both meshes), the V-cycle below from 9 (the umbrella from 20; solver.cpp,
// automatic_multigrid). With soft weights Automatic keeps the Jacobi trial and Factored.
//
// Multigrid (src/multigrid.h): a smoothed-aggregation V-cycle in place of Jacobi, for the
// first-order system (CG) and the complex solve of L^2 (COCG, with the complex Galerkin
// hierarchy). Its iteration count saturates as lambda_dt grows where Jacobi's keeps growing, but
// a cycle costs about three Jacobi iterations and its set-up about ten, so Automatic takes it
// only for strong steps on large meshes (the measurements are in solver.cpp, automatic_multigrid).
#pragma once

#include "fairing/fairing.h"
#include "fairing/operators.h"

#include <array>
#include <functional>
#include <vector>

namespace fairing {

struct LinearSystem {
    const SparseOperator* op = nullptr;
    std::vector<double> diagonal;  // D_i; empty: D = 0 (apply and apply_dot only: lambda_dt C)
    std::vector<char> free;        // nonzero: unknown
    double lambda_dt = 0;
    int order = 1;

    // y = A x on all rows (fixed rows included; callers mask them).
    void apply(const Positions& x, Positions& y, Positions& scratch) const;
    // The same, fused with the per-column dot product x.y over the free rows.
    std::array<double, 3> apply_dot(const Positions& x, Positions& y, Positions& scratch) const;
    // Jacobi preconditioner: the diagonal of A.
    std::vector<double> jacobi_diagonal() const;
};

struct SolveStats {
    int iterations = 0;
    int inner_iterations = 0;  // Factored: the first-order iterations inside B^-1
    bool factored = false;
    bool complex_factor = false;  // solved as Re (M + i sqrt(lambda_dt) K)^-1 (complex_factor.h)
    bool multigrid = false;  // preconditioned by the multigrid V-cycle (src/multigrid.h)
    bool gauss_seidel = false;  // complex solve preconditioned by block Gauss-Seidel
    bool direct = false;  // solved by a sparse LDL^T (src/direct_solve.h), not by CG
    double residual = 0;  // max over columns of ||A x - b|| / ||b|| on the free rows
    bool converged = false;
};

struct SolveSettings {
    double tolerance = 1e-10;
    ResidualNorm norm = ResidualNorm::L2;
    int max_iterations = 2000;
    Preconditioner preconditioner = Preconditioner::Automatic;
    // Automatic: the solve of the previous step of the same run (the same kind of system,
    // assembled again on the smoothed mesh), if any. How it went predicts this solve's Jacobi
    // iterations better than the stiffness does (solver.cpp, automatic_multigrid).
    const SolveStats* previous = nullptr;
    // Called after each iteration with an estimate of the fraction done in [0, 1]: how far the
    // residual has come down, on a log scale, from where it started to the tolerance.
    std::function<void(double)> progress;
};

// Solves A x = D x_old on the free rows; x holds x_old on entry (warm start, and the fixed
// values) and the solution on exit. Throws Error when a value stops being finite. Non-convergence
// is reported in the stats, not thrown.
SolveStats solve(const LinearSystem& system, Positions& x, const SolveSettings& settings);

}  // namespace fairing
