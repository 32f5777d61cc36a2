// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// s implicit steps with a frozen operator (section 4.3) as one matrix function (not installed).
//
// Algebra (the same as auto_strength.h's). With D = M/w and C = -K (order 1) or K P M^-1 K
// (order 2) as in solver.h, one step solves (D + lambda C_ff) x' = D x + b_fixed on the free
// rows, i.e. x' - x = -lambda D^-1/2 (I + lambda G)^-1 D^-1/2 (C x)_f with
// G = D^-1/2 C_ff D^-1/2 symmetric positive semi-definite and C acting on every position (fixed
// values included, so fixed vertices and the affine right-hand side need nothing special). As
// (C x_{j+1})_f = (I + lambda G)^-1-image of (C x_j)_f, s steps move the free vertices by exactly
//
//   x_s - x_0 = -D^-1/2 phi(G) u,   u = D^-1/2 (C x_0)_f,
//   phi(g) = lambda sum_{j=1..s} (1 + lambda g)^-j = (1 - (1 + lambda g)^-s) / g.
//
// Order 2 without soft weights (D = M on the free rows, complex_factor.h's case): G = G1^2 with
// G1 = M^-1/2 (-K_ff) M^-1/2, so the Krylov space is built with G1 (one product with K per
// step, the conditioning of a first-order step) and the function is phi(g^2), whose poles
// g = +-i / sqrt(lambda) are as far from the spectrum as the complex solve's. Orders 3 and 4
// (the paper's Figure 3a) the same way: G = G1^p, the function phi(g^p), its tridiagonal solves
// by partial fractions over the p-th roots of -1/lambda (lanczos_filter.h).
//
// phi has the pole of a single step, so the Lanczos process on G (or G1) started at u,
// phi(G) u ~ |u| V_k phi(T_k) e1 (Golub and Meurant, "Matrices, Moments and Quadrature"),
// converges at the asymptotic rate of one solve; the pole of order s makes the function steeper,
// though (s steps of lambda smooth about like one of s lambda), so it takes more steps than one
// solve: 228 Lanczos steps for 10 curvature L^2 steps at 22.5 against 116 COCG iterations for
// one on the 1.2 M-face bunny, 204 against 181 on the 1 M-face torus
// (bench/results/issue12/frozen.md). phi(T_k) e1 is summed from s tridiagonal solves
// (complex ones, (I +- i sqrt(lambda) T_k), for order 2 via G1; for order p one per conjugate
// pair of roots, and a real one for odd p). Two passes: the first builds
// T_k and stops when the coefficient vector |u| phi(T_k) e1, padded with zeros, moves by less
// than kSafety * tolerance * |D^1/2 x_0| (per column, the D-norm of the error of the step's
// result: one solve to `tolerance` guarantees that bound, as A >= D) between checks 4 Lanczos
// steps apart; the second recomputes the same basis bit for bit (the same arithmetic on the
// same data) and accumulates V_k phi(T_k) e1. The basis is never stored: four n x 3 arrays
// (96 bytes per vertex) and the sum, plus 12 (s - 1) bytes per vertex when the intermediate
// results are wanted (volume restoration, below). Every sum is blocked (kernels.h), so the
// result is bit-identical for any number of threads.
//
// Volume restoration after each step (fairing.h) rescales each closed component about its
// centroid. The filter is linear and keeps constants on a component whose vertices are all
// free, so with X_k the unrestored k-step result the step-by-step path yields exactly
// g_s + a_s (X_s - g_s) + delta, with a_k = (V_0 / V(X_k))^(1/3) (area: ^(1/2)), g_k the
// centroid of X_k and delta = sum_k (a_{k-1} - a_k) (g_k - g_s) (a_0 = 1). The scale depends on
// X_s alone, but delta needs every X_k (smoothing moves the centroid of an asymmetric solid:
// restoring once at the end is off by delta, 1e-6 to 1e-4 of the radius on the tests' lumpy
// sphere), so the second pass also accumulates X_1..X_{s-1}: in single precision, as their
// differences from X_s (so rounded relative to |X_k - X_s|, and entering delta only multiplied
// by a_{k-1} - a_k), or, when that rounding could exceed a tenth of the tolerance (strong
// shrinkage, tolerances near 1e-12), in double precision by a second try of the second pass
// (24 (s - 1) bytes per vertex). Their volumes and centroids are then measured on the mesh,
// s - 1 sweeps over its faces. When even double precision could exceed it (a solid collapsing
// under a huge step) the process gives up.
//
// The caller decides when this applies (fairing.cpp); here the process gives up (x untouched,
// FrozenOutcome::taken false) when it does not converge within max_iterations Lanczos steps, a
// restored measure stops being positive or its replay is too inexact (above), and the caller
// then takes the steps one by one.
#pragma once

#include "fairing/half_edge.h"
#include "fairing/solver.h"

#include <functional>
#include <vector>

namespace fairing {
namespace detail {

struct FrozenProblem {
    const LinearSystem* system = nullptr;  // one step's system: op, D, free, lambda_dt, order
    int steps = 2;
    double tolerance = 1e-8;  // Options::tolerance, in the sense above
    int max_iterations = 2000;  // Lanczos steps of the first pass
    // Components rescaled after every step (all their vertices free in `system`), with the
    // measure to restore (volume when closed, area when open) and the mesh to measure them on.
    const HalfEdgeMesh* mesh = nullptr;
    std::vector<int> rescaled;
    std::vector<double> target;
    std::function<void(double)> progress;  // fraction done, in [0, 1]
};

struct FrozenOutcome {
    bool taken = false;    // x holds the result; else x is untouched
    int lanczos_steps = 0;
    int products = 0;      // products with the system's operator, both passes
    double error = 0;      // the estimate that stopped the first pass, relative as above
};

// Takes problem.steps frozen steps on x (centred positions; fixed rows keep their values).
FrozenOutcome take_frozen_steps(const FrozenProblem& problem, Positions& x);

}  // namespace detail
}  // namespace fairing
