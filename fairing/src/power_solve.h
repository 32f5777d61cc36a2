// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The L^3 and L^4 steps (the paper's section 2.6 and Figure 3a: "the higher the power of the
// Laplacian, the closer to a low-pass filter") by partial fractions (not installed).
//
// Without soft weights (D = M on the free rows) the free block of the L^p system is
//
//   A = M + lambda_dt C1 (M^-1 C1)^(p-1) = M^1/2 (I + lambda_dt G1^p) M^1/2,
//
// C1 = -K on the free rows (P zeroes L at the fixed ones), G1 = M^-1/2 C1 M^-1/2. With
// c = lambda_dt^(1/p), theta_m = pi (2m + 1) / p and sigma_m = -c e^(-i theta_m),
//
//   A^-1 = (1/p) sum_{m=0..p-1} (M + sigma_m C1)^-1
//
// (the scalar identity is derived in lanczos_filter.h). The roots pair up, so for a real
// right-hand side A^-1 b = (1/p) (M + c C1)^-1 b [p odd] + (2/p) sum_{theta_m < pi}
// Re (M + sigma_m C1)^-1 b: L^3 costs one first-order solve and one complex solve, L^4 two complex
// solves, each with the sparsity of a first-order step, where A itself couples the p-ring (the
// paper: "the matrix becomes less and less sparse"). Each complex matrix is complex symmetric and
// e^(-i psi) (M + sigma C1) has a positive definite real part for some psi (arg sigma < pi), so
// COCG (conjugate orthogonal CG, van der Vorst and Melissen 1990) with complex Jacobi applies; on
// the noisy elephant it needs about as many iterations as the L^2 complex solve of the same
// lambda_dt (bench/results/issue11/session28-order4). An error e in a part shows in the L^p
// residual amplified by up to (c g)^(p-1) at the stiff end of the spectrum, so the solve refines:
// r = b - A x, x += A~^-1 r, until the L^p residual itself meets the goal. That residual is what
// makes strong steps costly here (rounds) or out of reach (the iteration cap), so fair() takes a
// surface step with the L2 norm and the automatic preconditioner as the frozen steps' matrix
// function instead (fairing.cpp, lanczos_power_step), whose rule bounds the error of the result;
// this solve serves the other norms and preconditioners and the boundary curve.
#pragma once

#include "fairing/solver.h"

#include <array>

namespace fairing {
namespace detail {

// Order 3 or 4 and D = M (mass > 0) on every free row.
bool power_solve_applies(const LinearSystem& system);

// Solves A x = b on the free rows (x: the start and the fixed values on entry, the solution on
// exit) until the residual's norm per column is at most goal. Throws Error when a value stops
// being finite.
SolveStats solve_power(const LinearSystem& system, Positions& x, const Positions& b,
                       const std::array<double, 3>& goal, const SolveSettings& settings);

}  // namespace detail
}  // namespace fairing
