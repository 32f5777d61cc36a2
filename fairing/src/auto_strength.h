// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Automatic strength: the time step that minimizes Stein's unbiased risk estimate (SURE) of the
// error along the normals, estimated from the noisy mesh alone (not installed).
//
// What it implements, and where from:
// - One step (or `steps` steps with a frozen operator) is a linear filter on the free vertices.
//   With D = M/w and C = -K (order 1) or K P M^-1 K (order 2) on the free rows (solver.h), the
//   implicit system is D + lambda C = D^1/2 (I + lambda G) D^1/2, G = D^-1/2 C D^-1/2 symmetric
//   positive semi-definite. With u = D^-1/2 (C x) (fixed-vertex terms included: C acts on every
//   position), s implicit steps of lambda each (as fair() takes them) move the free vertices by
//   exactly (operator frozen)
//     r(lambda) = D^-1/2 phi(G) u,   phi(g) = (1 - (1 + lambda g)^-s) / g,
//   and filter the noise by H = D^-1/2 (I + lambda G)^-s D^1/2 (explicit: (1 - lambda g)^s, and
//   phi(g) = (1 - (1 - lambda g)^s) / g).
// - The Lanczos process on G started at u (Golub & Meurant, "Matrices, Moments and
//   Quadrature", 1994/2010) gives r(lambda) ~ |u| D^-1/2 V_k phi(T_k) e1 for every lambda at
//   once (phi(T_k) e1 by tridiagonal solves); stochastic Lanczos quadrature with three
//   Rademacher probes (Hutchinson 1990; Ubaru, Chen & Saad, SIAM J. Matrix Anal. Appl. 38(4),
//   2017) gives tr H(lambda) for every lambda. The basis V_k is never kept: only a CountSketch of
//   its normal components (Charikar, Chen & Farach-Colton 2002; exact below 8192 vertices), from
//   which the normal residual follows for any lambda. The process stops when the risk's
//   minimizer has settled and the curves have converged (2 % between checkpoints, three
//   checkpoints for points far past the last converged ones; every point judged again at every
//   checkpoint) up to twice the minimizer (with a sketched residual, also not before the risk
//   has risen past the sketch's error: auto_strength.cpp, kSketchFlat), or at 296 steps. Cost:
//   two products with the system per Lanczos step, in two passes over the vectors; as many
//   steps as Jacobi-preconditioned CG would need at the chosen step to a loose tolerance.
// - Risk (Stein 1981): with noise of standard deviation sigma along the normals n_i (in all
//   directions: its normal component), and normals taken as fixed,
//     E sum_i (n_i . (x'_i - f_i))^2 = sum_i (n_i . r_i)^2 + 2 sigma^2 tr H - N sigma^2,
//   so the chosen lambda minimizes RSS_n(lambda) + 2 sigma^2 tr H(lambda). Tangential sliding
//   (the umbrella evens out triangles) is no error and does not count, and neither does the
//   part of the normal residual that the volume restoration puts back (a rescaling, or a normal
//   offset, per closed component: a shrinking sphere under curvature flow is no error).
// - sigma is estimated robustly from the data (Donoho & Johnstone's 1.4826 x median absolute
//   deviation, 1994) of the normal component of the uniform bi-Laplacian at every interior
//   vertex, each divided by the exact norm of its own stencil; on a smooth surface the
//   bi-Laplacian of the positions is of fourth order in the edge length, so curvature hardly
//   inflates it. On a coarse structured mesh (a parametric tube, a CAD tessellation) it does:
//   each vertex type (its valence and its neighbours') has a clean value of its own, and the
//   spread between types read as noise (CGAL's knot at 0.1 edge: 1.9x). So each value counts
//   from the median of its type's values where at least 64 vertices share the type, else from
//   that of its valence's, else from that of the rest; noise has median 0 in every type.
//
// - Divergence: SURE's 2 sigma^2 tr H is the divergence of the filter f(y) = H y only when H does
//   not depend on y. The weights of eq. 11 and eq. 14 are computed on the noisy mesh, so the
//   filter's true divergence is tr H plus sum_i b_i n_i . (dH/dy [b n]) y, which tr H misses
//   (measured: the effective divergence of one curvature-flow L^2 step on a sphere with half an
//   edge of noise is 1.6-1.8 tr H below time step 100, and the risk minimum moves 40x). For
//   them the divergence is estimated by Monte-Carlo SURE (Ramani, Blu & Unser, "Monte-Carlo
//   SURE: a black-box optimization of regularization parameters for general denoising
//   algorithms", IEEE TIP 17(9), 2008): div f ~ b . (f(y + eps b) - f(y)) / eps with one
//   Rademacher probe b along the normals, where f(y + eps b) comes from a second Lanczos process
//   on the operator assembled at y + eps b (started at its own u), run in lockstep with the
//   first, so that for every lambda at once div(lambda) = N - b . (r'(lambda) - r(lambda)) / eps
//   (r: the movement, f = y - r). It replaces the Hutchinson probes, at the same cost.
//
// - Several steps: with a recomputed operator (steps > 1, not frozen) only the first step's
//   weights come from the noisy mesh; the later ones come from a smoothed mesh and damage a
//   smooth shape less (a sphere is a fixed point of the curvature flow with its volume restored)
//   or, on scans whose noisy weights held the first step back, more. The s steps are modelled
//   as s steps on their mean operator: one s-th the operator at the data, the rest the operator
//   at a lightly smoothed copy of it (two lazy passes: the umbrella's, or for the scale-dependent
//   operator its own weights', which keep the irregular triangles' edge lengths closer to what
//   the later steps see; StrengthProblem::pilot; K and M are linear in the weights
//   and masses, so the mean is one symmetric operator and one Lanczos process serves). The
//   Monte-Carlo divergence perturbs the data and builds the same mean at the perturbed data.
//   The mean overstates what strong steps cost on smooth shapes, where the risk is flat about its
//   minimum: for several first-order steps the choice is the strongest step whose risk lies within
//   one standard error of the minimum (Breiman et al.'s rule, choose below), and so for the
//   curvature flow's L^2 steps below, up to kLaterRuleReach times the minimizer; the
//   scale-dependent L^2 steps keep the minimizer. (The umbrella takes the rule too: its risk is the
//   error along the normals, whose best step on featured and detailed scans is weaker than the
//   distance to the surface's.) For the curvature flow's L^2 steps the two halves of the risk are
//   split: the residual (what the steps do to the shape) comes from the later steps' operator
//   alone, since their smoother weights undo the damage the first step's noisy ones do to a smooth
//   shape; the divergence (how the steps respond to the noise) from the mean operator, whose first
//   share carries the weights' dependence on the noise. One more
//   Lanczos process (the movement on the later operator, with its own sketch) steps beside the
//   other two in their pass over the operator's pattern and their sketch's pass, as many steps
//   as they take, its weights formed from the mean's and the first step's: on the 1 M-face
//   torus the curvature flow's one-click estimate costs 1.8 of its steps instead of 1.2, its
//   peak 92 more bytes per vertex (26 on a 10 M-face torus; auto-gap.md, section 15). From
//   four steps the search stops only when this risk's minimizer (within 4x the mean's) has
//   settled too (auto_strength.cpp, kLaterRuleSteps): stopped on the mean's risk, the choice
//   sat at the top of its window on smooth spheres (auto-gap.md, section 31).
//
// Limits: the several-step model is an approximation (bench/results/denoise.md measures it).
// The Monte-Carlo divergence comes from one probe (a fixed one: the same mesh gives the same
// choice); where the risk is flat the choice follows that probe's error, so on unseen meshes the
// curvature flow's several-step choices spread more than the study's one draw shows
// (bench/results/issue11/auto-gap.md, section 14). The noise level's median absolute deviation
// assumes Gaussian noise: for uniform noise it runs 10-14 % high, and the choices are stronger
// than the best (the curvature flow's four L^2 steps on a 13 k-face sphere with uniform radial
// noise: 1.5-1.8x the best fixed step, 1.04-1.18x its error). A trimmed second moment (within
// three such deviations) is right for both, but made the scans' choices worse (the umbrella's
// L^2 x4 worst case 1.038 -> 1.059 of the best error; auto-gap.md, section 15): not used.
// Several first-order steps and the curvature flow's L^2 steps place the restoration's switch to
// scaling per step, with a margin for the later steps' larger losses (Sketch::step_change);
// where the steps lose evenly it stops the choice short (a 13 k-face sphere at a quarter edge,
// four first-order curvature steps: 1.12x the best error), and on a torus at 0.1 edge the
// model's risk is lowest at 1.4x the best step (1.04-1.14x its error on three noise draws;
// auto-gap.md, sections 26 and 37).
// The steps' total restores as modelled: where the model restores after the steps' total
// (restorations 1: the umbrella, the scale-dependent L^2 steps, a single step), the risk is
// lowest just before its switch to scaling when the offset gains up to there, and its volume
// loss is first order, so the steps' real change can fall past fair()'s switch while the
// model's does not. fair() then restores each component as the chosen step's model did
// (StrengthEstimate::restoration), up to twice kMaxOffsetChange for an offset (auto-gap.md,
// section 44).
// An estimate that cannot win: fair() estimates recomputed steps first and frozen ones second,
// and takes the frozen ones only where their risk is the lower by a margin
// (StrengthProblem::chosen_below). The residual RSS_n grows with lambda (each mode's share
// (1 - (1 + lambda g)^-s)^2 does; the normal projection and the restoration bend that little),
// the divergence falls and is not negative, and the restoration's gain on it steps up where a
// component switches to scaling. So between two converged grid points the risk is at least the
// lesser RSS_n plus the least gain x divergence of the two ends, and past the last converged
// point at least RSS_n there (auto_strength.cpp, excess_risk_bound). The frozen search stops at the first checkpoint where that bound, less a slack (kBoundSlack),
// lies above chosen_below. The choice is the same as the whole search's; on the 1 M-face torus
// the curvature flow's frozen estimate stops after 40 Lanczos steps instead of 109 (auto-gap.md,
// section 47).
//
// Conventions: lambda is the dimensionless time step of Options::time_step (C is scaled by the
// operator's length unit); rows at or past `data_vertices` (virtual vertices) move with the
// filter but are not data: they count neither in the risk nor in the trace. No time step at all
// (0) is chosen when the estimated noise is 0 (a flat patch, an exactly smooth mesh).
#pragma once

#include "fairing/fairing.h"
#include "fairing/half_edge.h"
#include "fairing/operators.h"

#include <functional>
#include <limits>
#include <vector>

namespace fairing {
namespace detail {

struct StrengthProblem {
    const SparseOperator* op = nullptr;       // the surface operator at the input positions
    const std::vector<char>* free = nullptr;  // the surface system's unknowns (mass > 0)
    const std::vector<double>* weight = nullptr;  // soft weights of the data vertices (w_i);
                                                  // null: all 1
    const Positions* x = nullptr;             // positions, virtual vertices after the data
    const HalfEdgeMesh* mesh = nullptr;       // the data vertices' mesh (normals, noise)
    int data_vertices = 0;
    double length_unit = 1;  // lambda_dt = lambda * length_unit
    int order = 1;
    int steps = 1;  // each of lambda (fair() gives every step the whole time step)
    bool explicit_integration = false;
    double max_time_step = 0;  // explicit: the largest time step allowed; else unused
    int threads = 1;
    // Volume restoration after each step: per data vertex the restored component's index (-1:
    // none), and per such component how: 0 rescaled, 1 offset along the normals (it has fixed
    // vertices), 2 offset while the volume changes by at most kMaxOffsetChange, else rescaled
    // (VolumeRestoration::NormalOffset; restore_measure). Empty: nothing restored.
    std::vector<int> restored;
    std::vector<char> offset;
    // How many restorations mode 2's kMaxOffsetChange applies to one by one: fair() restores
    // after every step when the steps recompute the operator, else once after the last. fair()
    // sets the steps for first-order steps and the curvature flow's L^2 steps (auto-gap.md
    // sections 26 and 37); 1: the total.
    int restorations = 1;
    // Per restored component, as offset: nonzero when fair() translates it after the steps by
    // the least-squares translation of its normal displacement (Options::cancel_drift); the
    // risk's residual loses that translation. Empty: none is.
    std::vector<char> cancel_drift;
    // The normals and the noise level when the caller has them already (strength_normals(),
    // noise_level(): fair() computes them once, for the curvature flow's offset shape too);
    // null and 0: computed here.
    const Positions* normals = nullptr;
    // Per data vertex the shape w of the normal offset (Options::shaped_offset, offset_shape.h):
    // a restored component is offset by t w_i n_i, and the residual loses that. Null: w = 1.
    const std::vector<double>* offset_shape = nullptr;
    double noise_level = 0;
    std::function<void(double)> progress;  // fraction of the estimate done, in [0, 1]
    // The operator assembled at other positions (same rows, virtual vertices included), for the
    // operators whose weights depend on the positions (eq. 11, eq. 14); empty for the umbrella,
    // whose filter is linear in the data. See "Divergence" above.
    std::function<SparseOperator(const Positions&)> assemble_at;
    // Several steps that recompute those weights (steps >= 2, not frozen): model them on the
    // steps' mean operator ("Several steps" above). Needs assemble_at.
    bool pilot = false;
    // With pilot, for L^2 steps: the residual from the later steps' operator alone, the
    // divergence from the mean ("Several steps" above). fair() sets it for the curvature flow,
    // whose cotangent weights the noise moves most.
    bool residual_on_later_steps = false;
    // With pilot: the copy the later steps' operator is assembled at is smoothed with the
    // operator's own weights (negative ones taken as 0) instead of the umbrella's. fair() sets it
    // for the scale-dependent operator, whose 1/|e| weights the umbrella's tangential drift on
    // irregular triangles changes most (auto-gap.md, section 29).
    bool pilot_on_own_weights = false;
    // Where the estimate competes (fair()'s frozen-or-recomputed choice), the excess risk it
    // must fall below to be chosen (StrengthEstimate::excess_risk). Once a checkpoint's bound on
    // the final risk lies above it the search stops: the estimate cannot be chosen, and
    // StrengthEstimate::out_of_reach says so (header, "An estimate that cannot win"). Infinite:
    // no such bound, the search runs its course.
    double chosen_below = std::numeric_limits<double>::infinity();
};

struct StrengthEstimate {
    double time_step = 0;     // dimensionless
    double noise_level = 0;   // sigma, in the mesh's units
    int lanczos_steps = 0;
    bool capped = false;  // the Lanczos processes reached their step cap before the choice settled
    double trace_fraction = 1;  // tr H / N at the chosen time step: the share of noise kept
    // The risk curve around the choice (for studies and tests, not for users): SURE is
    // rss + 2 noise_level^2 trace.
    std::vector<double> grid, rss, trace;
    double data_count = 0;
    // The risk's minimum over the grid less the noise's energy, over N sigma^2: the estimated mean
    // squared error along the normals at the best time step, in units of the noise's variance
    // (NaN where no risk curve was formed). Two filters estimated on the same data with the same
    // normals and noise level compare by it (fair()'s frozen-or-recomputed choice).
    double excess_risk = std::numeric_limits<double>::quiet_NaN();
    // Per restored component (StrengthProblem::offset's index), the restoration the risk
    // modelled at time_step when it models the steps' total (restorations 1): 1 offset, 0
    // rescaled, 2 not modelled; fair() follows it (header, "The steps' total restores as
    // modelled"). Else empty.
    std::vector<char> restoration;
    // The search stopped once it could not fall below StrengthProblem::chosen_below:
    // excess_risk is then a lower bound on it, and time_step, the grid and its curves are empty.
    bool out_of_reach = false;
};

// x moved `passes` times halfway to the mean of its one-ring (op's columns below `data`).
Positions smoothed_copy(const SparseOperator& op, const Positions& x, int data, int passes);
// The same with op's weights (negative ones taken as 0) instead of 1: a_i / 2 + the weighted
// mean of the neighbours / 2.
Positions smoothed_copy_weighted(const SparseOperator& op, const Positions& x, int data,
                                 int passes);

// Robust normals: area-weighted vertex normals averaged over the one-ring (so over two rings of
// faces), unit length, 0 where undefined. One row per vertex of `mesh`.
Positions robust_normals(const HalfEdgeMesh& mesh, const Positions& x);

// sigma (mesh units) of the noise along the normals, from the vertices with use[i] whose two-ring
// is interior (widened to all vertices when fewer than 16 qualify), each vertex type about its
// own median (above, "sigma is estimated"); 0 when none qualifies. `op` gives the one-rings (its
// weights are not used; columns at or past mesh.num_vertices() are ignored).
double estimate_noise(const SparseOperator& op, const HalfEdgeMesh& mesh, const Positions& x,
                      const Positions& normals, const std::vector<char>& use);

// The normals the estimate measures along (those of a lightly smoothed copy: the noisy mesh's
// are tilted by the noise, by ~25 degrees at half an edge, which hides part of it from the
// normal components), and the noise level along them (estimate_noise on the free data rows).
Positions strength_normals(const StrengthProblem& problem);
double noise_level(const StrengthProblem& problem, const Positions& normals);

StrengthEstimate estimate_strength(const StrengthProblem& problem);

// How far the one-standard-error rule may take the curvature flow's L^2 steps past the risk's
// minimizer (choose, `reach`). On a finely sampled smooth shape their risk is flat over a decade,
// and the rule ran to the end of the grid, 2.1-2.7x the minimizer; but strong recomputed steps
// there draw the mesh towards the discrete flow's own rest shape (on the 51 k two-density sphere at
// 0.1 edge, the top tenth of its finer half sinks by 1e-4 radii in the mean at 5x the best step),
// which the model of the steps, linear in the data, does not hold. Capped at 1.5x (three grid
// steps), the 51 k sphere's one click goes from 1.181 / 1.106 of its best fixed step's error at 0.1
// / a quarter edge to 1.086 / 1.029 (seed 2: 1.063 / 1.064 -> 1.031 / 1.001; a third draw at a
// quarter edge 1.177 -> 1.028). Of the study's 135 scan and torus cases one reached past 1.44x (b9
// in all directions, +0.4 %); the 13 k sphere's reaches of 1.6-2.1x lose up to 2.8 %, the 3 k flat
// patch's up to 4.5 %, where the infinite plane forgives any strong step (a 51 k-face patch gains
// 0.2-0.7 %). Recomputed first-order steps keep the whole rule: their mean-operator model
// overstates what strong steps cost, and the cap lost up to 17 % on the 3 k and 13 k spheres.
// With two L^2 steps it cost the 13 k sphere in all directions 12 % once (seed 2), where the
// minimizer lay far below the best step. Not reached: other 51 k spheres whose risk minimizer
// itself lies up to 6x past the best step (auto-gap.md, section 42).
constexpr double kLaterRuleReach = 1.5;

// The choice on e's risk curve (its grid, rss, trace and noise_level; sets time_step and
// trace_fraction): the minimizer of SURE on the grid, refined by a parabola in log(lambda)
// through its neighbours; or, with `strongest_within_error`, the strongest grid step up to
// `reach` times the minimizer whose risk lies within one standard error of the minimum
// (Breiman, Friedman, Olshen & Stone's one-standard-error rule, "Classification and Regression
// Trees", 1984, section 3.4.3). The standard error of the difference of two risks is taken as
// that of two nested projections' Mallows C_p, sigma^2 sqrt(2 |df_a - df_b|) (||(P_b - P_a) y||^2
// is sigma^2 chi^2 with |df_a - df_b| degrees of freedom when the signal lies in both), df being
// the divergence.
void choose(StrengthEstimate& e, bool strongest_within_error,
            double reach = std::numeric_limits<double>::infinity());

}  // namespace detail
}  // namespace fairing
