// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The boundary loops' automatic time step (section 5.3 under issue 11's automatic strength), by
// direct solves of the loops' systems (not installed).
//
// A loop of eq. 11 is a cyclic chain: its implicit system (direct_solve.h: D + lambda C, C =
// (-1)^p (K M^-1)^(p-1) K for L^p, on the free loop rows) is banded, and a sparse LDL^T factors
// it in time linear in the loop's length. So the risk of the loops' s steps is measured exactly at
// 17 time steps over ten decades (every decade, then every quarter decade near the lowest),
// instead of through auto_strength.h's Lanczos model, which on a few hundred loop vertices of
// very uneven edges (libcgal-demo's turbine blade: nine in ten loop edges under a fifth of the
// mean edge) has little to converge on.
//
// Risk: the loops' error in their normal planes, in two directions per free loop vertex i: n_i,
// the surface's robust unit normal, and b_i, normal to the loop's tangent and n_i (in the surface,
// across the loop). For each, Stein's unbiased risk (auto_strength.h)
//   sum_i (d_i . r_i)^2 + 2 sigma_d^2 div_d - N sigma_d^2,   r_i the loop's movement,
// with sigma_n the surface's noise level and sigma_b the loops' own across them: the robust
// spread of each vertex's offset along b from the chord of its neighbours (0 for noise along
// the normals, up to their tilt; sigma for noise in all directions). Across a loop the movement
// is curve shortening: with sigma_b = 0 it counts as error in full, since noise along the normals
// has no part there. Measured along the normals only, a hole's loop shrank into the hole and a
// flat sheet's outline rounded by 1.14 cells at a quarter cell of noise (auto-gap.md, sections
// 29-30). The loop's weights 1/|e| follow the noise when its edges are shorter than the noise, so
// tr H is not the filter's divergence: div_d is the Monte-Carlo divergence (Ramani, Blu & Unser
// 2008), one Rademacher probe along d with the operator assembled again at the probed data.
//
// Limits: the loops keep their first step's operator (as fair() applies them); implicit steps
// of any order (explicit ones: auto_strength.h). The loops' vertices alone estimate sigma_b;
// with fewer than 8 of them it is taken as 0.
#pragma once

#include "fairing/operators.h"

#include <functional>
#include <vector>

namespace fairing {
namespace detail {

struct LoopStrengthProblem {
    const SparseOperator* op = nullptr;       // assemble_boundary_curve at *x
    const std::vector<char>* free = nullptr;  // the free loop rows
    const std::vector<double>* weight = nullptr;  // soft weights w (D = M / w); null: all 1
    const Positions* x = nullptr;
    const Positions* normals = nullptr;  // unit normals of the surface at the data
    const HalfEdgeMesh* mesh = nullptr;  // its boundary loops
    double noise_level = 0;              // sigma, in the positions' units
    double length_unit = 1;              // lambda_dt per unit time step
    int order = 1;                       // 1 to 4
    int steps = 1;
    // The loop operator at other positions (the Monte-Carlo divergence).
    std::function<SparseOperator(const Positions&)> assemble_at;
};

// The loops' time step; 0 with no free loop vertex or no noise. Throws Error when the systems
// fail to factor at every time step.
double loop_time_step(const LoopStrengthProblem& p);

}  // namespace detail
}  // namespace fairing
