// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Implicit fairing of irregular meshes (Desbrun, Meyer, Schroeder, Barr, SIGGRAPH 1999):
// the one entry point every host (MeshLab filters, the command-line tool, tests) calls.
//
//   fairing::Options options;                 // documented defaults below
//   options.op = fairing::Operator::CurvatureFlow;
//   fairing::Result r = fairing::fair(mesh, constraints, options);
//   // r.positions holds the new positions; the input is never modified.
//
// Conventions:
// - Every operator is L = M^-1 K with M diagonal positive and K symmetric, zero row sums,
//   negative semi-definite. Implicit steps solve the symmetric positive definite system
//   (M/w - lambda_dt K) X' = (M/w) X (eq. 9 multiplied by M; w = soft-constraint weights), or
//   for the second order (M/w + lambda_dt K M^-1 K) X' = (M/w) X (section 2.6), and for the
//   order p (M/w + lambda_dt (-K) (M^-1 (-K))^(p-1)) X' = (M/w) X.
// - The time step given by the user is dimensionless. For the scale-dependent umbrella and the
//   curvature flow (L in 1/length^2, L^2 in 1/length^4) the absolute lambda_dt is
//   time_step * (mean edge length)^(2 order), so the same settings work whatever the mesh's
//   units; for the umbrella and the normalized operators (L dimensionless) lambda_dt =
//   time_step. The boundary curve (eq. 11 on the loop) is scaled like the scale-dependent
//   operator. Result::lambda_dt reports the value used.
// - Automatic strength (Options::time_step left empty, the default): the time step minimizing
//   Stein's unbiased estimate of the error along the normals, from the input alone
//   (src/auto_strength.h). Result::time_step, noise_level and the other strength fields report
//   the choice. A given time step is used as is.
// - fair() throws fairing::Error on refusal (bad input, failed solve, non-finite values); the
//   caller's data is untouched because it only ever receives positions from a finished run.
#pragma once

#include "fairing/types.h"

#include <functional>
#include <string>
#include <vector>

namespace fairing {

enum class Operator {
    Umbrella,        // eq. 7: uniform weights, valence mass.
    ScaleDependent,  // eq. 11 (Fujiwara): weights 1/|e_ij|, mass E/2.
    CurvatureFlow,   // eq. 14: weights cot(alpha)+cot(beta), mass 4A (one-ring area).
};

enum class Integration {
    Implicit,  // backward Euler, eq. 9: unconditionally stable.
    Explicit,  // forward Euler, eq. 8: stable only for small lambda_dt (a warning says when not).
};

enum class BoundaryMode {
    Fixed,          // boundary vertices do not move.
    SmoothCurve,    // section 5.3: boundary loops follow eq. 11 restricted to their two boundary
                    // neighbours, solved first; the interior then follows with the new curve.
                    // The loops keep their first step's weights (section 4.3) in every step.
    VirtualVertex,  // section 5.3: a hidden vertex at the barycentre of each loop, fanned to it.
};

// What is restored after each step on components that are not closed (they enclose no volume).
enum class OpenInvariant {
    None,  // nothing: the component may shrink.
    Area,  // surface area (section 3.2's "preserve the surface area if the mesh is non-closed").
};

// How a closed component's volume (or, with OpenInvariant::Area, an open one's area) is brought
// back after a step.
enum class VolumeRestoration {
    // Every free vertex moves along its area-weighted unit normal by one common distance t,
    // solved to machine precision: to first order the smallest correction (area-weighted
    // L2) that restores the volume. On a sphere it is the paper's scaling; on thin parts and
    // tori it is not: scaling about the centroid moves far parts most whatever shrank (README,
    // "Volume by the smallest correction"). A loss above kMaxOffsetChange (invariants.h) is
    // scaled: an offset surface that large would fold over itself. With the automatic time
    // step of the umbrella, the scale-dependent L^2 steps or a single step, each component is
    // restored as the estimate modelled the chosen step (src/auto_strength.h), an offset up to
    // twice that.
    NormalOffset,
    // Section 3.2: scale about the centroid by beta = (V0/Vn)^(1/3). A component with fixed
    // vertices still gets the normal offset, so fixed vertices stay where they are.
    Scale,
};

enum class ResidualNorm { L2, LInfinity };  // Appendix A.2.

// How the conjugate gradients are preconditioned (see solver.h).
enum class Preconditioner {
    Automatic,  // L^2 without soft weights: one complex solve (solver.h), preconditioned by
                // complex Jacobi, block symmetric Gauss-Seidel or the V-cycle as the step's
                // stiffness grows; else Factored for L^2 steps strong enough to profit, Jacobi
                // otherwise; Multigrid in place of Jacobi for strong steps on meshes of 50,000
                // vertices or more, and for the rest of a complex solve not finished in half of
                // max_iterations
    Jacobi,     // the diagonal of the system: cheap, iterations grow as sqrt(lambda_dt)
    Factored,   // L^2 only: two first-order solves per iteration, iterations grow as lambda_dt^1/4
    Multigrid,  // smoothed-aggregation multigrid V-cycle (src/multigrid.h): first order, and L^2
                // without soft weights (complex solve); L^2 with soft weights falls back to
                // Automatic's choice. Set-up costs about a few iterations; iterations stay
                // nearly flat as lambda_dt grows
};

// A double or nothing: std::optional<double> for the C++14 callers of this header (MeshLab
// 2020.09 plugins are built as gnu++14, which has no <optional>). Same member names.
class OptionalDouble {
public:
    OptionalDouble() = default;                       // empty
    OptionalDouble(double value) : has_(true), value_(value) {}  // NOLINT: assign a number
    bool has_value() const { return has_; }
    explicit operator bool() const { return has_; }
    double operator*() const { return value_; }
    double value() const {
        if (!has_) throw Error("no value: the time step is automatic");
        return value_;
    }
    double value_or(double fallback) const { return has_ ? value_ : fallback; }
    void reset() { *this = OptionalDouble(); }

private:
    bool has_ = false;
    double value_ = 0;
};

struct Options {
    Operator op = Operator::CurvatureFlow;
    Integration integration = Integration::Implicit;
    // 1: diffusion with L (eq. 6). 2: with L^2, (I + lambda_dt L^2) X' = X (section 2.6), the
    // paper's recommendation and the better denoiser. 3, 4: (I + lambda_dt (-L)^p) X' = X, the
    // higher powers of Figure 3a, closer still to a low-pass filter. Without soft weights a step
    // is a function of the first-order operator, by partial fractions over the p-th roots of
    // -1/lambda_dt (src/frozen_steps.h, src/power_solve.h); with them Jacobi CG on the L^p system
    // (slow for strong steps).
    int order = 2;
    // Dimensionless; see the conventions above. Must be finite and >= 0. Empty (the default):
    // chosen from the mesh (automatic strength, see the conventions above).
    OptionalDouble time_step;
    int steps = 1;
    // Section 4.3: keep the coefficients of the first step for all steps (smoothing "relative to
    // the initial mesh"). Off: coefficients are recomputed from the current mesh at each step;
    // a recomputed L^3 or L^4 step whose system cannot be solved (its vertex stars shrunk) is
    // taken on the last operator that solved, frozen from there, with a warning.
    // The umbrella's never change. Implicit steps on a frozen operator are one linear filter and
    // are taken at once where measured cheaper (the defaults' L^2 steps; src/frozen_steps.h):
    // the same result to the tolerance, one SolveReport for all of them. The curvature flow's
    // recomputed vertex areas follow a scan's thin parts as they shrink, and keep a noisy sphere
    // round: on scans frozen steps erred 0.88x the recomputed ones (120 cases), on the study's
    // spheres 2.0x (bench/results/issue11/auto-gap.md, section 41); off lets freeze_when_better
    // decide.
    bool freeze_operator = false;
    // With the automatic time step and freeze_operator off, the curvature flow's and the
    // scale-dependent operator's several implicit steps estimate the risk of frozen steps as
    // well as of recomputed ones, and freeze when that estimated error is the lower by a margin
    // (Result::operator_frozen; src/fairing.cpp, kFreezeMargin). Off, or with a given time step:
    // recomputed, as the paper's flow (section 4).
    bool freeze_when_better = true;
    // Explicit integration only: use the normalized operators of section 5.5 (eigenvalues of L
    // in [-2, 0], so time_step is dimensionless and up to 1 is stable).
    bool normalized = false;
    BoundaryMode boundary = BoundaryMode::Fixed;
    // Sections 3.1-3.2: after each step restore the volume of every closed component, by
    // `restoration`. Steps on a frozen operator (freeze_operator, the umbrella) are one linear
    // filter, and NormalOffset restores once, after the last: offsets after each step would add
    // up to it but for the small change of the normals between steps, and the steps can then be
    // taken at once (src/frozen_steps.h).
    bool preserve_volume = true;
    VolumeRestoration restoration = VolumeRestoration::NormalOffset;
    // Curvature flow with preserve_volume: after the last step, translate every closed component
    // without fixed vertices by the translation that best explains its displacement from the
    // input along the normals (least squares over its faces, by area). A step of eq. 14 keeps
    // sum M_i x_i with M_i = 4 A_i, the one-ring areas, and noise inflates them unevenly where the
    // sampling density varies: on the sphere sampled at two densities with half an edge of noise
    // in all directions that weighted centroid lies 1.6 edges off the clean one, and strong steps
    // drift the sphere towards it. Zero-mean noise has no such translation, and a thin part that
    // shrinks is none either (moving the solid's centroid back instead, as CGAL's smooth_shape
    // does, cost the camel up to 19 %). The study's spheres: the automatic curvature flow's error
    // 19 % lower in the median, 16 % on a second draw (bench/results/issue11/auto-gap.md,
    // section 21). Steps are translation-equivariant, so one translation after the last step is
    // the same as one after each. The other operators keep the valence- or edge-weighted mean of
    // the vertices: no effect.
    bool cancel_drift = true;
    // Curvature flow with preserve_volume and VolumeRestoration::NormalOffset: a closed
    // component's volume goes back by the offset t w_i n_i instead of t n_i, w the smoothed mean
    // curvature of the input after one first-order curvature step, pulled towards uniform by the
    // share of its variation that a second draw of noise shows to be noise (src/offset_shape.h).
    // The flow takes the volume from the convex, strongly curved parts (a torus's outer rim, a
    // thin limb), and a uniform offset puts it back everywhere. Where noise or sampling explains
    // most of the curvature's variation (a sphere) the offset stays uniform, bit for bit. The
    // automatic strength models this offset for first-order steps (whose loss is the mean
    // curvature the shape follows) and chooses as for the uniform offset for L^2 steps:
    // modelling it there let the choice run away on tori, where the shaped offset makes strong
    // steps nearly harmless to the model but not to the shape (bench/results/issue11/
    // auto-gap.md, sections 24-25). Costs two first-order steps and three assemblies of the
    // operator (+11 % on the 1.2 M-face bunny's one-click run).
    bool shaped_offset = true;
    OpenInvariant open_invariant = OpenInvariant::None;
    // Solver (Appendix A): stop when ||A X - b|| < tolerance ||b|| for x, y and z. b is the
    // mass-weighted position of the centred mesh, so 1e-8 leaves an error far below an edge.
    double tolerance = 1e-8;
    ResidualNorm norm = ResidualNorm::L2;
    int max_iterations = 2000;
    Preconditioner preconditioner = Preconditioner::Automatic;
    // An implicit surface solve that does not converge (stalls, or reaches max_iterations) on at
    // most 100,000 free vertices (L and L^2; L^3 50,000, L^4 25,000: the factor couples p rings)
    // is solved again by a sparse LDL^T (SolveReport::direct), unless accept_unconverged asks for
    // the last iterate. Its residual is rounding's, amplified by the decades M^-1 spans, p - 1
    // times in L^p; a result whose residual exceeds 1e-3 (and the tolerance) is not kept.
    // Needles that the curvature flow's later steps make can stall CG short of the tolerance on
    // real scans. false: such a solve is refused as below.
    bool direct_fallback = true;
    // When the iteration cap is hit and no direct solve took over: false refuses (the input stays
    // as it was); true accepts the last iterate and records a warning with the residual reached.
    bool accept_unconverged = false;
    // Threads for the solver's loops on meshes of 50,000 vertices or more (smaller ones always
    // use one): 0 = as many as OpenMP offers (OMP_NUM_THREADS, else the cores), 1 = one.
    int threads = 0;
    // Called now and then with the fraction of the work done, in [0, 1], never decreasing.
    std::function<void(double)> progress;
};

// Per-vertex constraints (section 2.7). Empty vectors mean "none".
struct Constraints {
    std::vector<char> fixed;      // nonzero: hard constraint, the position stays bit-identical.
    std::vector<double> weights;  // soft constraint in [0, 1], scales lambda at the vertex;
                                  // 0 is a hard constraint. Values outside are an error.
};

struct TriangleMesh {
    Positions positions;
    std::vector<Triangle> triangles;
};

// One linear solve (per step there is one, plus one for the boundary curve in SmoothCurve mode).
struct SolveReport {
    int step = 0;
    std::string system;    // "surface" or "boundary curve"
    int iterations = 0;
    // Factored preconditioner: iterations of the inner first-order solves (each one product with
    // K, against two for an iteration of an L^2 system).
    int inner_iterations = 0;
    bool factored = false;  // the Factored preconditioner was used
    // Solved by a sparse LDL^T: the boundary loops always, the surface when its iterative solve
    // did not converge (Options::direct_fallback; `iterations` then counts that solve's).
    bool direct = false;
    double residual = 0;   // max over x, y, z of ||A X - b|| / ||b|| in the chosen norm
    bool converged = true;
    // > 0: this one report covers that many steps with a frozen operator, taken at once as a
    // matrix function (src/frozen_steps.h); `iterations` then counts its products with the
    // system (both Lanczos passes) and `residual` is the estimated error of the result relative
    // to the positions (D-norm), which the steps' tolerance bounds.
    int frozen_steps = 0;
};

enum class Restoration {
    None,            // nothing restored (switched off, or open component with OpenInvariant::None)
    Scale,           // rescaled about the component's centroid (eq. 10 and section 3.2)
    NormalOffset,    // free vertices offset along their normals (VolumeRestoration::NormalOffset,
                     // or the component has fixed vertices)
    Unchanged,       // every vertex of the component is fixed
    // Left as given: the steps flattened the component (a tetrahedron, a thin plate), so that its
    // measure became zero or negative, or restoring it would have enlarged the component more
    // than twofold (Run::restore in fairing.cpp).
    Collapsed,
};

struct ComponentReport {
    int faces = 0;
    bool closed = false;       // no boundary, consistently oriented: encloses a volume
    bool has_fixed = false;
    Restoration restoration = Restoration::None;
    // The invariant measured: volume for closed components, area for open ones.
    double measure_before = 0;
    double measure_after = 0;
};

struct Result {
    Positions positions;            // the new positions, one row per input vertex
    double lambda_dt = 0;           // absolute lambda*dt used per step
    double time_step = 0;           // the dimensionless time step used (chosen or given)
    bool automatic_time_step = false;  // chosen from the mesh (Options::time_step empty)
    // BoundaryMode::SmoothCurve: the boundary curve's dimensionless time step (scaled like the
    // scale-dependent operator's). A given time step serves both systems; the automatic strength
    // chooses the curve's on its own, since a loop of eq. 11 wants a far other strength than the
    // surface (0 without a smoothed curve).
    double boundary_time_step = 0;
    double mean_edge_length = 0;    // of the input, in its units (the time step's length unit)
    // Automatic strength only (0 otherwise): the estimated standard deviation of the noise
    // along the normals, in the mesh's units and in mean edge lengths of the input (which normal
    // noise lengthens: by 6-8 % at a quarter edge of noise, 21-25 % at half an edge).
    double noise_level = 0;
    double noise_level_edges = 0;
    // Automatic strength only: tr H / N of the chosen filter H on the free vertices (its
    // effective degrees of freedom per vertex: 1 keeps everything, 0 smooths everything away),
    // the Lanczos steps spent and the seconds spent choosing (included in `seconds`).
    double trace_fraction = 0;
    int strength_iterations = 0;
    double strength_seconds = 0;
    // Whether the steps kept the first step's operator, by Options::freeze_operator or by
    // Options::freeze_when_better's choice (false for the umbrella, whose operator never changes).
    bool operator_frozen = false;
    // Options::freeze_when_better's comparison, where it was made (operator_compared): the
    // estimated error of recomputed and of frozen steps at their best time steps, the mean
    // squared error along the normals over the noise's variance (estimates: may be negative).
    bool operator_compared = false;
    double recomputed_risk = 0;
    double frozen_risk = 0;
    // The frozen estimate stopped as soon as it could no longer win (the recomputed steps ran):
    // frozen_risk is then a lower bound on its risk, not its value.
    bool frozen_risk_is_bound = false;
    int steps = 0;
    std::vector<SolveReport> solves;
    int total_iterations = 0;
    int total_inner_iterations = 0;  // of the Factored preconditioner's first-order solves
    double max_residual = 0;
    double volume_before = 0;       // sum over closed components
    double volume_after = 0;
    std::vector<ComponentReport> components;
    int vertices_moved = 0;         // vertices whose position changed
    int vertices_fixed = 0;         // hard constraints (user, weight 0, fixed boundary, frozen)
    int isolated_vertices = 0;      // referenced by no face: left out
    int zero_area_faces = 0;        // contribute nothing to the operators
    int dropped_faces = 0;          // faces repeating a vertex index: left out
    int inconsistent_edges = 0;     // edges whose two faces disagree on orientation
    int boundary_loops = 0;
    bool explicit_unstable = false;  // an explicit step exceeded its stability bound
    std::vector<std::string> warnings;
    double seconds = 0;             // the whole of fair(): validation, assembly, solves
};

// Runs options.steps steps of implicit (or explicit) fairing. Throws fairing::Error.
Result fair(const TriangleMesh& mesh, const Constraints& constraints, const Options& options);

const char* to_string(Operator op);
const char* to_string(BoundaryMode mode);
const char* to_string(Restoration restoration);

}  // namespace fairing
