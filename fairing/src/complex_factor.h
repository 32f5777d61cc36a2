// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The L^2 step as one complex solve (not installed).
//
// Without soft weights (D = M on the free rows) the free block of the L^2 system factors over
// the complex numbers:
//
//   A = M + s^2 K M^-1 K = (M + i s K) M^-1 (M - i s K),   s = sqrt(lambda_dt),
//
// (on the free rows, with K restricted to them: P zeroes L at the fixed rows), and for any real
// right-hand side g
//
//   A^-1 g = Re[(M + i s K)^-1 g],
//
// since per generalized eigenmode (K v = mu M v, mu <= 0, v real) 1 / (1 + s^2 mu^2) =
// Re 1 / (1 + i s mu). So an L^2 step costs one solve with the complex symmetric matrix
// M + i s K, which has the sparsity of the first-order matrix M - s K of the same cutoff. Its
// spectrum (after Jacobi scaling) is the segment 1 + i s mu: a Krylov method converges on it
// about as fast as CG on the real segment 1 - s mu, i.e. like the first-order step itself, where
// the L^2 system (1 + s^2 mu^2) needs the square root of a squared condition number. The
// method is COCG (conjugate orthogonal CG, van der Vorst and Melissen 1990: CG with the
// unconjugated bilinear form x^T y, valid for complex symmetric matrices).
//
// Preconditioners: the multigrid V-cycle (multigrid.h) when given, else symmetric Gauss-Seidel
// by blocks, P = (D + L) D^-1 (D + L^T) with D the complex diagonal and L the strictly lower
// couplings inside each block of kSweepBlock rows (sweeps.h: so the result does not depend on
// the number of threads; couplings between blocks are left to the Krylov method), or complex
// Jacobi. Gauss-Seidel runs in Eisenstat's form (Eisenstat 1981, "Efficient implementation of
// a class of preconditioned conjugate gradient methods"): COCG on E^-1 A E^-T with
// E = (D + L) D^-1/2, whose product costs one backward and one forward sweep, together one pass
// over the matrix like a product with A, so an iteration costs ~1.2 Jacobi iterations and it
// needs about half as many (bench/results/issue12/preconditioners.md, "Symmetric Gauss-Seidel").
//
// The complex residual does not bound the L^2 residual tightly (per mode the L^2 residual is up
// to sqrt(1 + s^2 mu^2) times larger), so the iteration stops on the L^2 residual itself,
// Re r_c + s K M^-1 Im r_c, and solve() confirms it on b - A x, correcting again if needed. The
// solver's three complex vectors (144 bytes per vertex; a fourth with Gauss-Seidel or the
// V-cycle) and b are all the solve holds.
#pragma once

#include "fairing/solver.h"

#include <array>
#include <functional>

namespace fairing {
namespace detail {

class Multigrid;

// True when the L^2 system factors as above: order 2 and D = M on every free row.
bool complex_factor_applies(const LinearSystem& system);
// True when the system's C is the power of the first-order C1 = -K in M's metric on the free
// rows, C = C1 (M^-1 C1)^(order-1): order 2 or more and D = M on every free row (the Lanczos
// processes of frozen_steps.h and auto_strength.h then run on G1).
bool powers_first_order(const LinearSystem& system);

class ComplexFactorSolver {
public:
    // Preconditioned by B (width 6, complex symmetric: multigrid.h) when given, else by block
    // symmetric Gauss-Seidel (or complex Jacobi when gauss_seidel is false); B must outlive the
    // solver. B and Gauss-Seidel cost one more complex vector than Jacobi.
    ComplexFactorSolver(const LinearSystem& system, Multigrid* preconditioner,
                        bool gauss_seidel = true);

    // Whether it sweeps (Gauss-Seidel asked for and applicable: complex_factor.cpp).
    bool gauss_seidel() const { return gauss_seidel_; }

    // g = b - A x, the residual of the real L^2 system on the free rows (zero on the fixed
    // ones), kept as the complex solve's right-hand side; returns its norms per column.
    std::array<double, 3> set_residual(const Positions& b, const Positions& x, ResidualNorm norm);

    // x += Re[(M + i s K)^-1 g] on the free rows for the g of set_residual, by COCG from zero
    // (x accumulates the real part of the iterate; its imaginary part is never kept). Column c
    // iterates while active[c] and stops once the L^2 residual of the new x is <= goal[c]. At
    // most cap iterations; returns the iterations done. after_iteration gets the complex
    // residual norms.
    int correct(Positions& x, const std::array<double, 3>& goal,
                ResidualNorm norm, int cap, std::array<bool, 3> active,
                const std::function<void(const std::array<double, 3>&)>& after_iteration);

private:
    using Complex6 = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;
    // q = (M + i s K) p, returning the unconjugated products p^T q per column (re, im).
    std::array<double, 6> product(const Complex6& p, Complex6& q) const;
    // One pass over the rows: with alpha (re, im per column), x += Re(alpha p) and
    // r -= alpha q; then u = J^-1 r, and per column the residual norm (squares or maxima of
    // |r|) in [0..2] and r^T u in [3..8] (re, im). first: p = u (the first direction).
    std::array<double, 9> update(const double* alpha, bool first, ResidualNorm norm, Positions* x);
    // With a preconditioner B: u = B^-1 r, and r^T u per column (re in [0..2], im in [3..5]);
    // first: p = u.
    std::array<double, 6> precondition(bool first);
    // p = J^-1 r + beta p (or u + beta p) on the columns whose beta (re, im per column) is not
    // NaN.
    void next_direction(const double* beta);
    // Norms of the L^2 residual g - A (x + Re z) per column, from r_c alone (uses q as scratch).
    std::array<double, 3> l2_residual_norms(ResidualNorm norm);

    // Gauss-Seidel (Eisenstat's form), in the variables v~ = D^-1/2 v^ of the transformed
    // system: r = r~, p = p~, u = E^-T p^, q = the forward sweep's y, with A^ p^ = D^1/2 (u + y).
    // r~ = (D + L)^-1 r in place (r = g on entry), p~ = r~; returns the norms of r^ per column
    // in [0..2] and r^T r^ (re, im per column) in [3..8].
    std::array<double, 9> sweep_start(ResidualNorm norm);
    // u and y for A^ p^, after p~ = r~ + beta p~ where beta is given (not NaN); returns p^T A^ p^
    // (re, im per column).
    std::array<double, 6> sweep_product(const double* beta);
    // x += Re(alpha u), r~ -= alpha (u + y); returns what sweep_start does.
    std::array<double, 9> sweep_update(const double* alpha, ResidualNorm norm, Positions& x);
    // The complex residual E r^ = (D + L) r~: real part in q's columns 3..5, imaginary part
    // divided by M in its columns 0..2 (what l2_residual_norms needs).
    void sweep_residual();
    // s K_ii per row (D_i = M_i + i s K_ii), 0 on fixed rows.
    std::vector<double> imaginary_diagonal() const;
    // What the sweeps read: the free rows, D's real (M) and imaginary (s K_ii) parts, K's rows
    // (weight null: all 1) and s.
    struct SweepView {
        const char* free;
        const double* mass;
        const double* imaginary;
        const int* start;
        const int* column;
        const double* weight;
        double s;
    };
    SweepView sweep_view() const;

    const LinearSystem& system_;
    double s_ = 0;
    std::vector<double> inverse_;  // Jacobi: 1 / (M_i + i s K_ii): re, im per row; 0 on fixed rows
    std::vector<double> imaginary_;  // Gauss-Seidel: s K_ii (imaginary_diagonal)
    bool gauss_seidel_ = false;
    int block_ = 0;  // rows per sweep block
    std::array<double, 3> start_norms_{0, 0, 0};  // of g, from set_residual
    Complex6 r_, p_, q_;
    Multigrid* preconditioner_ = nullptr;
    Complex6 u_;  // B^-1 r with a preconditioner; Gauss-Seidel: E^-T p^
};

}  // namespace detail
}  // namespace fairing
