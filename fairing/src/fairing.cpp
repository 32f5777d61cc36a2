// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "fairing/fairing.h"

#include "fairing/half_edge.h"
#include "fairing/invariants.h"
#include "fairing/operators.h"
#include "fairing/solver.h"
#include "auto_strength.h"
#include "complex_factor.h"
#include "direct_solve.h"
#include "frozen_steps.h"
#include "geometry.h"
#include "kernels.h"
#include "loop_strength.h"
#include "offset_shape.h"
#include "vertex_order.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace fairing {

const char* to_string(Operator op) {
    switch (op) {
    case Operator::Umbrella: return "umbrella (eq. 7)";
    case Operator::ScaleDependent: return "scale-dependent umbrella (eq. 11)";
    case Operator::CurvatureFlow: return "curvature flow (eq. 14)";
    }
    return "?";
}

const char* to_string(BoundaryMode mode) {
    switch (mode) {
    case BoundaryMode::Fixed: return "fixed";
    case BoundaryMode::SmoothCurve: return "smooth boundary curve";
    case BoundaryMode::VirtualVertex: return "virtual vertex";
    }
    return "?";
}

const char* to_string(Restoration restoration) {
    switch (restoration) {
    case Restoration::None: return "none";
    case Restoration::Scale: return "scaled about the centroid";
    case Restoration::NormalOffset: return "normal offset of the free vertices";
    case Restoration::Unchanged: return "unchanged (all vertices fixed)";
    case Restoration::Collapsed: return "left as given (the steps flattened it)";
    }
    return "?";
}

namespace {

// The most free rows a surface system may have to be factored when its iterative solve stops
// short (Run::integrate), by order. Measured on noisy tori, curvature L^2 at 22.5, one thread,
// every step factored (--max-iterations 1): per step 0.7 s and 96 MB at 25 k vertices, 10.7 s and
// 455 MB at 100 k, 39 s and 838 MB at 200 k, against 0.07, 0.3 and 0.6 s for CG (auto-gap.md
// section 32). L^p couples p rings, and the factor's fill grows with them: on the 25.6 k-vertex
// two-density sphere one factored curvature step took 1.8 s and 87 MB (L^2), 6.8 s and 148 MB
// (L^3), 18 s and 239 MB (L^4); on the 37.7 k-vertex bunny 1.3, 4.8 and 13 s.
std::ptrdiff_t max_direct_fallback_rows(int order) {
    return order <= 2 ? 100000 : order == 3 ? 50000 : 25000;
}

// The largest relative residual of a factored step that is kept (Run::integrate). A
// factorization is backward stable, but when M^-1 spans many decades the residual of an L^p
// system is rounding amplified by them, and so is the error: one L^4 curvature step (no volume
// restored) on a noisy 642-vertex sphere with one vertex star shrunk by 1e-2 or 1e-3, against the
// matrix-function step (error bounded to 1e-8), differed by 2.4e-5 of the radius at a residual
// of 1.2e-5, by 1.3e-3 at 1.2e-3 and by 1.0 at 0.22, each time at the shrunk star's centre. So
// the error stays at the vertex that caused it, and up to 1e-3 it stays within a tenth of an
// edge of a mesh of ten thousand vertices: the femur's one-click curvature flow without the
// volume kept (half an edge of noise) factors its fourth step at a residual of 4.1e-4. The
// loops' factored L^2 steps reach 4e-6 (the dragon's sliver holes).
constexpr double kDirectResidual = 1e-3;

// Options::freeze_when_better's margins (Run::estimate_frozen_or_recomputed), in the noise's
// variance per vertex: about twice the most the recomputed estimate exceeded the frozen one by
// on the study's spheres and torus, where frozen steps err up to 3.6x (curvature flow; 0.0175,
// the torus in all directions) and 1.4x (scale-dependent; 0.0051) the recomputed ones. A margin
// of 0.002 would have frozen the scale-dependent steps on 102 scan cases instead of 76 (one-click
// error 0.985x), but also on spheres within 0.0005 of it and on an open CAD part (libcgal-demo's
// blade at half an edge, 1.07x and, with four steps, 1.54x the recomputed steps' error).
constexpr double kFreezeMargin = 0.03;
constexpr double kFreezeMarginScaleDependent = 0.01;

// A step whose solve did not converge (Run::record): recomputed L^3 and L^4 steps retake it on
// the last operator that solved (Run::take_steps).
class UnsolvedStep : public Error {
public:
    using Error::Error;
};

// The smallest mass of a free row with mass, relative to their mean (1: none).
double smallest_mass_ratio(const SparseOperator& op, const std::vector<char>& free) {
    double sum = 0, least = 0;
    int rows = 0;
    for (int i = 0; i < op.size(); ++i) {
        if (!free[i] || !(op.mass[i] > 0)) continue;
        sum += op.mass[i];
        least = rows++ == 0 ? op.mass[i] : std::min(least, op.mass[i]);
    }
    return rows == 0 ? 1.0 : least / (sum / rows);
}

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// A factor to two significant digits ("23", "3.8").
std::string fold(double v) {
    std::ostringstream s;
    s << std::setprecision(2) << v;
    return s.str();
}

void validate(const TriangleMesh& mesh, const Constraints& constraints, const Options& options) {
    const std::size_t n = static_cast<std::size_t>(mesh.positions.rows());
    if (!constraints.fixed.empty() && constraints.fixed.size() != n)
        throw Error("the fixed-vertex mask has size " + std::to_string(constraints.fixed.size()) +
                    " but the mesh has " + std::to_string(n) + " vertices");
    if (!constraints.weights.empty() && constraints.weights.size() != n)
        throw Error("the vertex weights have size " + std::to_string(constraints.weights.size()) +
                    " but the mesh has " + std::to_string(n) + " vertices");
    long long bad_weights = 0;
    for (double w : constraints.weights)
        if (!(w >= 0.0 && w <= 1.0)) ++bad_weights;
    if (bad_weights > 0)
        throw Error(detail::count_of(bad_weights, "vertex weight is", "vertex weights are") +
                    " outside [0, 1] or not a number; a weight scales the smoothing at its "
                    "vertex (section 2.7), 0 keeps it fixed");
    if (options.time_step.has_value() &&
        !(std::isfinite(*options.time_step) && *options.time_step >= 0))
        throw Error("the time step must be a finite number >= 0, or left automatic (got " +
                    number(*options.time_step) + ")");
    if (options.steps < 0)
        throw Error("the number of steps must be >= 0 (got " + std::to_string(options.steps) + ")");
    if (options.order < 1 || options.order > 4)
        throw Error("the operator order must be 1 (L), 2 (L squared), 3 or 4 (the higher powers "
                    "of section 2.6), got " + std::to_string(options.order));
    if (!(std::isfinite(options.tolerance) && options.tolerance > 0))
        throw Error("the solver tolerance must be a finite number > 0 (got " +
                    number(options.tolerance) + ")");
    if (options.threads < 0)
        throw Error("the thread count must be >= 0, 0 meaning all cores (got " +
                    std::to_string(options.threads) + ")");
    if (options.max_iterations < 1)
        throw Error("the iteration cap must be at least 1 (got " +
                    std::to_string(options.max_iterations) + ")");
    if (options.normalized && options.integration == Integration::Implicit)
        throw Error("the normalized operators (section 5.5) are meant for explicit integration; "
                    "switch them off for implicit integration");
}

// Hands the pages of freed blocks back to the system between the phases of a run. glibc serves
// blocks below its mmap threshold from the heap, and raises that threshold to the size of any
// large block freed (up to 32 MB), so after the first phase most vectors of a large mesh live on
// the heap, whose freed holes stay resident: measured on the 1.2 M-face bunny (curvature L^2,
// automatic time step) 564 bytes per vertex of peak RSS against 507 with a fixed threshold,
// whatever the phase freed before the solve. A no-op elsewhere.
void release_free_memory() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

// Appends the virtual vertex of each boundary loop (section 5.3) at the loop's barycentre and
// the fan of faces joining it to the loop, each fan face running opposite to its boundary edge.
void add_virtual_vertices(const HalfEdgeMesh& mesh, Positions& x, std::vector<Triangle>& faces) {
    const int n = mesh.num_vertices();
    const auto& loops = mesh.boundary_loops();
    x.conservativeResize(n + static_cast<int>(loops.size()), 3);
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const int v = n + static_cast<int>(l);
        Vec3 sum = Vec3::Zero();
        for (int b : loops[l]) sum += detail::row(x, b);
        x.row(v) = (sum / static_cast<double>(loops[l].size())).transpose();
        for (int h : mesh.boundary_loop_edges()[l]) faces.push_back({mesh.to(h), mesh.from(h), v});
    }
}

// Explicit stability bound from Gershgorin's theorem on L = M^-1 K: its eigenvalues lie in
// [-mu, 0] with mu = max_i 2 sum_j |w_ij| / M_i, and forward Euler is stable while
// lambda_dt mu^p <= 2 for order p (mu^p bounds the spectrum of (-L)^p). For the umbrella mu = 2,
// which gives the paper's lambda_dt < 1 (section 2.2).
double explicit_bound(const SparseOperator& op, const std::vector<char>& free, int order) {
    double mu = 0;
    for (int i = 0; i < op.size(); ++i) {
        if (!free[i] || !(op.mass[i] > 0)) continue;
        double sum = 0;
        for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k) sum += std::abs(op.weight[k]);
        mu = std::max(mu, 2 * sum / op.mass[i]);
    }
    if (mu == 0) return INFINITY;
    return order == 1 ? 2 / mu : order == 2 ? 2 / (mu * mu) : 2 / std::pow(mu, order);
}

// One run of fair() on `mesh`, the caller's mesh or its renumbering by `order` (vertex_order.h:
// order[i] is the caller's row of vertex i, empty for the caller's own numbering). `mesh` is read
// by the constructor only (it may be freed afterwards: a renumbered copy would otherwise stay
// alive through the solves); later the run reads the caller's positions, `input`, through
// `order`, and returns the result in the caller's numbering.
class Run {
public:
    Run(const TriangleMesh& mesh, const Positions& input, const std::vector<int>& order,
        const Constraints& constraints, const Options& options)
        : input_(input),
          order_(order),
          input_triangles_(static_cast<long long>(mesh.triangles.size())),
          options_(options),
          he_(HalfEdgeMesh::build(mesh.positions, mesh.triangles, options.threads)) {
        n_ = static_cast<int>(mesh.positions.rows());
        // No soft weights: weight_ stays empty (all 1) rather than 8 bytes per vertex of ones.
        if (!constraints.weights.empty()) weight_ = constraints.weights;
        frozen_ = options_.freeze_operator;
        hard_.assign(n_, 0);
        for (int i = 0; i < n_; ++i)
            hard_[i] = (!constraints.fixed.empty() && constraints.fixed[i]) || weight(i) == 0.0;
    }

    Result run();

private:
    void check_input();
    Eigen::RowVector3d centre();
    void set_free_masks();
    void add_virtual_mode();
    void set_targets();
    void assemble_surface();
    bool assembles_again() const;
    void release_pairing();
    std::vector<char> surface_free() const;
    void choose_time_step();
    bool compares_freezing() const;
    detail::StrengthEstimate estimate_frozen_or_recomputed(detail::StrengthProblem& problem,
                                                           double share);
    int choose_curve_time_step(const detail::StrengthProblem& surface, double noise_level);
    bool smooths_curve() const;
    void take_steps();
    bool smooth_loops(double lambda_dt, int step, int steps);
    bool take_frozen_steps(double lambda_dt, int steps);
    bool lanczos_power_step(const LinearSystem& linear, int step, const char* system,
                            const std::function<void(double)>& progress);
    detail::FrozenProblem frozen_problem(const LinearSystem& system, int steps) const;
    void record_frozen(const detail::FrozenOutcome& outcome, int step, const char* system,
                       int steps);
    LinearSystem system_for(const SparseOperator& op, const std::vector<char>& free,
                            double lambda_dt) const;
    void finish(const Eigen::RowVector3d& origin);
    void warn_about_input();
    void integrate(const SparseOperator& op, const std::vector<char>& free, double lambda_dt,
                   int step, const char* system);
    void explicit_step(const SparseOperator& op, const std::vector<char>& free,
                       double lambda_dt, const char* system);
    void record(const SolveStats& stats, int step, const char* system,
                const std::string& cause = std::string());
    std::string ill_conditioning(const SparseOperator& op, const std::vector<char>& free) const;
    double farthest_flight(const Positions& from) const;
    void restore();
    double size_of(const Component& component, const Positions& x) const;
    void leave_as_given(std::size_t c);
    void leave_if_grown(std::size_t c);
    void check_collapses();
    std::string flattening() const;
    Restoration restore_component(std::size_t c, Positions& x,
                                  const std::vector<double>* shape) const;
    void shape_offset();
    bool cancels_drift(std::size_t component) const;
    void cancel_drift(const Eigen::RowVector3d& origin);  // Options::cancel_drift
    void warn(const std::string& w) { result_.warnings.push_back(w); }
    // Soft weight of row i; virtual vertices (i >= n_) have none.
    double weight(int i) const { return i < n_ && !weight_.empty() ? weight_[i] : 1.0; }
    // The caller's input position of vertex i.
    Eigen::Ref<const Eigen::RowVector3d> input_row(int i) const {
        return input_.row(order_.empty() ? i : order_[i]);
    }
    // The CG-based estimate may go back when the residual rises; the user sees it only advance.
    // The automatic strength takes the first `progress_offset_` of the range.
    void report_progress(double fraction) {
        fraction = progress_offset_ + (1 - progress_offset_) * fraction;
        if (options_.progress && fraction > progress_) {
            progress_ = fraction;
            options_.progress(fraction);
        }
    }

    const Positions& input_;
    const std::vector<int>& order_;
    long long input_triangles_ = 0;
    const Options& options_;
    HalfEdgeMesh he_;
    HalfEdgeMesh work_;  // he_ plus virtual vertices and their fans, in VirtualVertex mode
    bool virtual_mode_ = false;
    int n_ = 0;
    std::vector<double> weight_;    // soft weights; empty: all 1
    std::vector<char> hard_;        // user constraints and weight 0
    std::vector<char> restorable_;  // may be moved by the volume/area restoration
    std::vector<char> free_surface_, free_curve_;  // unknowns of the two systems
    std::vector<char> ever_free_;   // moved by some step
    std::vector<double> target_;    // per component: volume (closed) or area (open), or 0
    // Per restored component its input's size (root mean square distance of its vertices from
    // their mean), and per vertex whether its component was left as given (Run::restore; empty
    // while none is).
    std::vector<double> input_size_;
    std::vector<char> left_as_given_;
    double largest_growth_ = 0;  // of the components left as given for growing (0: none did)
    const char* grown_measure_ = "volume";  // what restoring would have enlarged that one by
    Eigen::RowVector3d origin_ = Eigen::RowVector3d::Zero();  // x_ = input - origin_
    std::vector<double> offset_shape_;  // Options::shaped_offset, per data vertex; empty: uniform
    // Per component, the restoration the automatic time step's risk modelled (StrengthEstimate::
    // restoration: 1 offset, 0 rescaled, 2 restore_measure's own rule); empty: none modelled.
    std::vector<char> modelled_restoration_;
    // The steps keep the first step's operator: Options::freeze_operator, or chosen by the
    // automatic strength (Options::freeze_when_better, choose_time_step).
    bool frozen_ = false;
    // The automatic strength's normals and noise level, computed once for the offset shape and
    // the estimate (empty and 0: not yet).
    Positions strength_normals_;
    double noise_level_ = 0;
    Positions x_;                   // centred working positions (plus virtual vertices)
    SolveStats previous_surface_solve_;  // the last step's (solver.h, SolveSettings::previous)
    SparseOperator surface_, curve_;
    AssemblyReport worst_;          // most of each finding over the assemblies
    double mean_edge_ = 0;
    double length_unit_ = 1;        // (mean edge)^(2 order): lambda_dt per unit time step
    double time_step_ = 0;
    double curve_time_step_ = 0;    // the boundary curve's (Result::boundary_time_step)
    Result result_;
    bool warned_stability_ = false;
    int needle_faces_ = 0;  // most needles seen by an assembly so far
    double progress_ = 0;
    double progress_offset_ = 0;
};

const HalfEdgeMesh& work_mesh(const HalfEdgeMesh& he, const HalfEdgeMesh& work, bool virtual_mode) {
    return virtual_mode ? work : he;
}

void Run::explicit_step(const SparseOperator& op, const std::vector<char>& free,
                        double lambda_dt, const char* system) {
    const int n = op.size();
    if (!warned_stability_) {
        const double bound = explicit_bound(op, free, options_.order);
        if (lambda_dt > bound) {
            warn("explicit integration: lambda*dt = " + number(lambda_dt) +
                 " exceeds the stability bound " + number(bound) + " of this mesh (" + system +
                 "); expect growing oscillations, or use implicit integration");
            warned_stability_ = true;
            result_.explicit_unstable = true;
        }
    }
    // X' = X - lambda_dt (-L P)^(p-1) (-L) X (order 2: X - lambda_dt L P L X), L = 0 at fixed
    // vertices.
    Positions lx, llx;
    op.apply_l(x_, lx);
    for (int power = 2; power <= options_.order; ++power) {
        for (int i = 0; i < n; ++i)
            if (!free[i]) lx.row(i).setZero();
        op.apply_l(lx, llx);
        lx.swap(llx);
    }
    const double sign = options_.order % 2 ? 1 : -1;
    for (int i = 0; i < n; ++i)
        if (free[i]) x_.row(i) += sign * lambda_dt * weight(i) * lx.row(i);
}

void Run::record(const SolveStats& stats, int step, const char* system,
                 const std::string& cause) {
    SolveReport report;
    report.step = step;
    report.system = system;
    report.iterations = stats.iterations;
    report.inner_iterations = stats.inner_iterations;
    report.factored = stats.factored;
    report.direct = stats.direct;
    report.residual = stats.residual;
    report.converged = stats.converged;
    result_.solves.push_back(report);
    result_.total_iterations += stats.iterations;
    result_.total_inner_iterations += stats.inner_iterations;
    result_.max_residual = std::max(result_.max_residual, stats.residual);
    if (stats.converged) return;
    const std::string what =
        "the linear solve (" + std::string(system) + ", step " + std::to_string(step + 1) +
        ") did not converge in " + std::to_string(stats.iterations) + " iterations: residual " +
        number(stats.residual) + ", tolerance " + number(options_.tolerance) +
        (!cause.empty() ? cause
         : needle_faces_ > 0
             ? " (" + detail::count_of(needle_faces_, "face is a needle", "faces are needles") +
                   ", with an angle below 0.01 rad: their cotangent weights, even capped at " +
                   number(kCotangentCap) +
                   ", make the system ill-conditioned; MeshLab's 'Remove T-Vertices by Edge "
                   "Flip' or 'Merge Close Vertices' repairs them)"
             : std::string());
    if (!options_.accept_unconverged)
        throw UnsolvedStep(what +
                    (cause.empty() ? ". Raise the iteration cap or the tolerance, or use a "
                                     "smaller time step; the mesh was left unchanged"
                                   : ". Use a lower order or a smaller time step, or freeze "
                                     "the operator; the mesh was left unchanged"));
    warn(what + "; the unconverged result was kept as asked");
}

// Why an L^p system (p >= 2) may be out of reach, or empty: M^-1 enters it p - 1 times, so a
// vertex mass r times the mean raises its condition by about r^-(p-1). The curvature flow's
// recomputed L^3 and L^4 steps shrink some vertex stars that far: on libcgal-demo's femur at
// half an edge of noise (one click, order 3) to 1e-9 of the mean area by the third step, where
// the iterative solves diverged and a factorization left a residual of 0.08.
std::string Run::ill_conditioning(const SparseOperator& op, const std::vector<char>& free) const {
    const double ratio = smallest_mass_ratio(op, free);
    if (options_.order < 2 || std::pow(ratio, options_.order - 1) >= 1e-6) return std::string();
    return " (the smallest vertex mass, its area for the curvature flow, is " + number(ratio) +
           " of the mean, and an order-" + std::to_string(options_.order) +
           " system's condition grows with its inverse to the power " +
           std::to_string(options_.order - 1) +
           (options_.op == Operator::Umbrella || frozen_
                ? std::string(")")
                : std::string("; recomputed steps shrink vertex stars, a frozen operator does "
                              "not)"));
}

// How far the step from `from` to x_ moved a vertex, in sizes (size_of, at `from`) of its
// component; 0 for components of one point. A smoothing step pulls a part in on itself, moving
// a vertex about its distance from the part's centre (up to 3.8 radii on 16-vertex patches with
// a cell of noise, whose loops a step of 100 drew in first), so past kBlownUp it has blown up: a
// vertex whose star a recomputed L^3 or L^4 step shrank to almost no area is held to its data
// with that area only, and the order-p term places it by extrapolation. On libcgal-demo's
// b9_mesh at a quarter edge of noise (curvature flow, order 4, its loops smoothed) the fourth
// step's solves converged to 1e-9 and threw vertices of a 1,703-vertex part up to 1,540 mean
// edges (auto-gap.md, section 41).
constexpr double kBlownUp = 10;
double Run::farthest_flight(const Positions& from) const {
    double farthest = 0;
    for (const Component& part : he_.components()) {
        const double size = size_of(part, from);
        if (!(size > 0)) continue;
        for (int v : part.vertices)
            farthest = std::max(farthest, (x_.row(v) - from.row(v)).norm() / size);
    }
    return farthest;
}

void Run::integrate(const SparseOperator& op, const std::vector<char>& free, double lambda_dt,
                    int step, const char* system) {
    if (options_.integration == Integration::Explicit) {
        explicit_step(op, free, lambda_dt, system);
        SolveReport report;
        report.step = step;
        report.system = system;
        result_.solves.push_back(report);
        return;
    }
    const LinearSystem linear = system_for(op, free, lambda_dt);
    SolveSettings settings;
    settings.tolerance = options_.tolerance;
    settings.norm = options_.norm;
    settings.max_iterations = options_.max_iterations;
    settings.preconditioner = options_.preconditioner;
    if (options_.progress) {
        const double steps = std::max(1, options_.steps);
        settings.progress = [this, step, steps](double f) {
            report_progress(std::min(1.0, (step + std::min(1.0, f)) / steps));
        };
    }
    const bool surface = &op == &surface_;
    const double trusted = std::max(options_.tolerance, kDirectResidual);
    if (!surface) {  // the loops' cyclic bands: solved directly
        const SolveStats direct = detail::solve_directly(linear, x_, trusted);
        if (direct.converged) {
            record(direct, step, system);
            return;
        }
    }
    if (surface && lanczos_power_step(linear, step, system, settings.progress)) return;
    if (surface && step > 0) settings.previous = &previous_surface_solve_;
    // A solve that stalls on a mesh small enough to factor is solved directly instead
    // (direct_solve.h). Needles that the curvature flow's later steps make can keep CG from the
    // tolerance: on libcgal-demo's femur with half an edge of noise the one-click run's fourth
    // step stalled at a residual of 2.8e-7 after 1242 iterations (84 needles) and was refused.
    const bool may_factor = surface && options_.direct_fallback &&
                            !options_.accept_unconverged &&
                            std::count(free.begin(), free.end(), char(1)) <=
                                max_direct_fallback_rows(options_.order);
    Positions before;
    if (may_factor) before = x_;
    SolveStats stats = solve(linear, x_, settings);
    if (surface) previous_surface_solve_ = stats;
    if (!stats.converged && may_factor) {
        SolveStats direct = detail::solve_directly(linear, before, trusted);
        if (direct.converged) {
            x_.swap(before);
            direct.iterations = stats.iterations;  // what the stalled solve cost
            stats = direct;
        }
    }
    record(stats, step, system, stats.converged ? std::string() : ill_conditioning(op, free));
}

// One L^3 or L^4 step without soft weights as the frozen steps' matrix function of the
// first-order operator (frozen_steps.h, one step). Its stopping rule bounds the error of the
// result; the partial-fraction solve (power_solve.h) must bring the L^p residual itself down,
// which its parts' rounding keeps up by up to (c g)^(p-1) at strong steps: the curvature flow's
// automatic L^3 x4 on the 51 k-face two-density sphere at half an edge of noise was refused at
// the 2,000-iteration cap (residual 0.16) and the 1 M-face torus's umbrella step at 7.9e6 took
// four refinement rounds (auto-gap.md section 28). false: not taken (x_ untouched).
bool Run::lanczos_power_step(const LinearSystem& linear, int step, const char* system,
                             const std::function<void(double)>& progress) {
    if (options_.order < 3 || options_.norm != ResidualNorm::L2 ||
        options_.preconditioner != Preconditioner::Automatic ||
        !detail::powers_first_order(linear))
        return false;
    detail::FrozenProblem problem = frozen_problem(linear, 1);
    problem.progress = progress;
    // Its error bound is relative to the positions before the step. A step that all but
    // collapses the mesh (time steps far past any smoothing: 1e12 on a small sphere) leaves a
    // result whose own relative error exceeds the tolerance, and the volume restoration would
    // magnify it into a distorted shape; such a step goes to the solve (x_ as it was), which
    // brings the residual down or refuses it.
    const Positions before = x_;
    const detail::FrozenOutcome outcome = detail::take_frozen_steps(problem, x_);
    if (!outcome.taken) return false;
    double shrink = 1;  // the smallest ratio of a column's size after the step to before
    for (int c = 0; c < 3; ++c) {
        double after = 0, ahead = 0;
        for (int i = 0; i < n_; ++i) {
            if (!linear.free[i]) continue;
            after += x_(i, c) * x_(i, c);
            ahead += before(i, c) * before(i, c);
        }
        if (ahead > 0) shrink = std::min(shrink, std::sqrt(after / ahead));
    }
    if (outcome.error > options_.tolerance * shrink) {
        x_ = before;
        return false;
    }
    record_frozen(outcome, step, system, 1);
    return true;
}

detail::FrozenProblem Run::frozen_problem(const LinearSystem& system, int steps) const {
    detail::FrozenProblem problem;
    problem.system = &system;
    problem.steps = steps;
    problem.tolerance = options_.tolerance;
    problem.max_iterations = options_.max_iterations;
    problem.mesh = &he_;
    return problem;
}

// One report for `steps` steps taken at once as the frozen steps' matrix function.
void Run::record_frozen(const detail::FrozenOutcome& outcome, int step, const char* system,
                        int steps) {
    SolveReport report;
    report.step = step;
    report.system = system;
    report.iterations = outcome.products;
    report.residual = outcome.error;
    report.frozen_steps = steps;
    result_.solves.push_back(report);
    result_.total_iterations += outcome.products;
    result_.max_residual = std::max(result_.max_residual, outcome.error);
}

LinearSystem Run::system_for(const SparseOperator& op, const std::vector<char>& free,
                             double lambda_dt) const {
    const int n = op.size();
    LinearSystem linear;
    linear.op = &op;
    linear.free = free;
    linear.lambda_dt = lambda_dt;
    linear.order = options_.order;
    linear.diagonal.assign(n, 1.0);
    for (int i = 0; i < n; ++i)
        if (free[i]) linear.diagonal[i] = op.mass[i] / weight(i);
    return linear;
}

// Steps with a frozen operator taken at once (src/frozen_steps.h), where measured cheaper than
// the steps one by one with fairing-bench-tool, one thread, process CPU seconds, 10 frozen steps
// (bench/results/issue12/frozen.md):
// - L^2 without soft weights, automatic preconditioner (the filters' defaults; the Krylov space
//   is that of the first-order operator): curvature L^2 at 22.5, 11.0 s against 38.3 s on the
//   1.2 M-face bunny and 7.6 s against 25.7 s on a 1 M-face torus (one step: 5.0 s, 5.5 s);
//   umbrella L^2 at 10, 2.6 s against 7.5 s and 1.8 s against 5.1 s.
// - First order when no component is rescaled (open components, volume off): curvature L at
//   4.74, 7.3 s against 8.5 s (bunny) and 4.7 s against 8.2 s (torus). With rescaling, 10 steps
//   of lambda need about as many Lanczos steps as one of 10 lambda and the intermediate results
//   the rescaling needs make the second pass dearer: 9.0 s against 8.0 s on the bunny (7.0 s
//   against 10.5 s on the torus), so those stay one by one.
// - L^2 with soft weights: the Krylov space would be the L^2 operator's, unpreconditioned; not
//   measured, expected slower than the steps' preconditioned solves: one by one.
// The process is the same filter as the steps one by one only with implicit steps on one system
// (no boundary curve first), the L2 stopping rule, and, with VolumeRestoration::Scale, every
// restored component either rescaled whole (all its vertices free: the filter then keeps
// constants on it and the rescaling commutes with it up to a translation the process replays) or
// not moving; a normal offset after each step (fixed vertices) is not linear. With
// VolumeRestoration::NormalOffset the volume is restored once, after the last step. Anywhere
// else, or when the Lanczos process gives up, the steps are taken one by one as before (false,
// x_ untouched). A rescaled run keeps the intermediate
// results, 12 bytes per vertex and step (24 when single precision is not enough), hence the cap.
bool Run::take_frozen_steps(double lambda_dt, int steps) {
    constexpr int kMaxRescaledSteps = 17;
    if (options_.integration != Integration::Implicit || options_.norm != ResidualNorm::L2 ||
        options_.preconditioner != Preconditioner::Automatic)
        return false;
    const std::vector<char> free = surface_free();
    std::vector<int> rescaled;  // components rescaled after every step, and their measures
    std::vector<double> target;
    std::vector<int> unchanged;
    const auto& components = he_.components();
    // A normal offset is restored once, after the last step (Options::preserve_volume).
    const bool offset = options_.restoration == VolumeRestoration::NormalOffset;
    for (std::size_t c = 0; c < components.size() && !offset; ++c) {
        if (target_[c] == 0) continue;
        std::size_t movable = 0, moving = 0;
        for (int v : components[c].vertices) {
            movable += restorable_[v] ? 1 : 0;
            moving += restorable_[v] && free[v] ? 1 : 0;
        }
        if (movable == 0) {
            unchanged.push_back(static_cast<int>(c));
            continue;
        }
        // In virtual-vertex mode a loop's hidden vertex would not be rescaled with the loop.
        if (moving != components[c].vertices.size() || (virtual_mode_ && !components[c].closed()))
            return false;
        rescaled.push_back(static_cast<int>(c));
        target.push_back(target_[c]);
    }
    if (!rescaled.empty() && steps > kMaxRescaledSteps) return false;
    const LinearSystem system = system_for(surface_, free, lambda_dt);
    const bool first_order_unscaled = options_.order == 1 && rescaled.empty();
    if (!first_order_unscaled && !detail::powers_first_order(system)) return false;
    detail::FrozenProblem run = frozen_problem(system, steps);
    run.rescaled = std::move(rescaled);
    run.target = std::move(target);
    if (options_.progress) run.progress = [this](double f) { report_progress(f); };
    const detail::FrozenOutcome outcome = detail::take_frozen_steps(run, x_);
    if (!outcome.taken) return false;
    record_frozen(outcome, 0, "surface", steps);
    for (int c : run.rescaled) {
        result_.components[c].restoration = Restoration::Scale;
        leave_if_grown(c);
    }
    for (int c : unchanged) result_.components[c].restoration = Restoration::Unchanged;
    if (offset) restore();
    else check_collapses();
    for (int i = 0; i < n_; ++i) ever_free_[i] |= free[i];
    result_.steps = steps;
    report_progress(1.0);
    return true;
}

// Restores every component's measure (sections 3.1-3.2). A step can flatten a small or thin
// closed component (a tetrahedron, a plate) into something with almost no volume: scaling it
// back up then blows it up. On libcgal-demo's b9_mesh, a CAD part of 47 components, the
// curvature flow's one-click run at a quarter edge of noise moved a four-vertex component by 400
// mean edges and the rest of the mesh by at most three. Such a component (no fixed vertex,
// measure zero or negative after the step, or more than twice its input's size once restored) is
// left as given; a mesh with nothing else to smooth is refused, as before.
void Run::restore() {
    const std::vector<double>* shape = offset_shape_.empty() ? nullptr : &offset_shape_;
    for (std::size_t c = 0; c < target_.size(); ++c) {
        if (target_[c] == 0) continue;
        ComponentReport& report = result_.components[c];
        if (report.restoration == Restoration::Collapsed) {
            leave_as_given(c);  // the later steps smoothed it again
            continue;
        }
        if (report.has_fixed) {  // its offset keeps the fixed vertices; failures are reported
            report.restoration = restore_component(c, x_, shape);
            continue;
        }
        try {
            report.restoration = restore_component(c, x_, shape);
        } catch (const Error&) {  // no fixed vertex: the measure itself collapsed
            leave_as_given(c);
            continue;
        }
        leave_if_grown(c);
    }
    check_collapses();
}

void Run::leave_if_grown(std::size_t c) {
    constexpr double kMaxGrowth = 2;
    const double growth = size_of(he_.components()[c], x_) / input_size_[c];
    if (!(growth > kMaxGrowth)) return;
    if (growth > largest_growth_) grown_measure_ = result_.components[c].closed ? "volume" : "area";
    largest_growth_ = std::max(largest_growth_, growth);
    leave_as_given(c);
}

// Root mean square distance of the component's vertices from their mean.
double Run::size_of(const Component& component, const Positions& x) const {
    Vec3 mean = Vec3::Zero();
    for (int v : component.vertices) mean += detail::row(x, v);
    mean /= static_cast<double>(component.vertices.size());
    double sum = 0;
    for (int v : component.vertices) sum += (detail::row(x, v) - mean).squaredNorm();
    return std::sqrt(sum / static_cast<double>(component.vertices.size()));
}

void Run::leave_as_given(std::size_t c) {
    if (left_as_given_.empty()) left_as_given_.assign(n_, 0);
    result_.components[c].restoration = Restoration::Collapsed;
    for (int v : he_.components()[c].vertices) {
        left_as_given_[v] = 1;
        x_.row(v) = input_row(v) - origin_;
    }
}

// Refuses the run when every vertex that could move lies in a component left as given.
void Run::check_collapses() {
    if (left_as_given_.empty()) return;
    for (int i = 0; i < n_; ++i)
        if (restorable_[i] && !he_.is_isolated(i) && !left_as_given_[i]) return;
    // An automatic step is named, so that the user knows where "smaller" starts.
    throw Error("the steps flattened every component that could move: " + flattening() +
                ", so the mesh was left unchanged; use a smaller time step" +
                (result_.automatic_time_step
                     ? " than the automatic one (" + number(time_step_) + ")"
                     : std::string()));
}

// What the steps did to the components left as given (for the warning and the refusal).
std::string Run::flattening() const {
    return largest_growth_ > 0 ? std::string("restoring its ") + grown_measure_ +
                                     " would have enlarged it " + fold(largest_growth_) + "-fold"
                               : std::string("its volume or area became zero or negative");
}

// x may hold virtual vertices after the first n_ rows; they are not part of any component and
// restore_measure only touches the component's own rows.
// With an automatic time step, a component restored as the estimate modelled it: its choice
// weighed that restoration's risk, and the model's volume loss is first order. On libcgal-demo's
// sponge (walls thinner than an edge; a tenth of an edge of noise, the umbrella's L^2 x8) the
// risk fell up to where the model switches to scaling, at a modelled change of 10 %, and the
// choice sat there; the steps' real change was 10.5 %, restore_measure rescaled, and the error
// was 1.84x the best fixed step's (auto-gap.md section 44). An offset is still bounded, by
// kModelledOffsetChange: past it, the model was too far off to be followed.
Restoration Run::restore_component(std::size_t c, Positions& x,
                                   const std::vector<double>* shape) const {
    constexpr double kModelledOffsetChange = 2 * kMaxOffsetChange;
    VolumeRestoration how = options_.restoration;
    double max_offset_change = kMaxOffsetChange;
    if (c < modelled_restoration_.size() && how == VolumeRestoration::NormalOffset) {
        if (modelled_restoration_[c] == 0) how = VolumeRestoration::Scale;
        if (modelled_restoration_[c] == 1) max_offset_change = kModelledOffsetChange;
    }
    return restore_measure(he_, he_.components()[c], restorable_, target_[c], x, how,
                           options_.threads, shape, max_offset_change);
}

// Options::shaped_offset (src/offset_shape.h): the shape of the curvature flow's volume offset,
// from the input, before the estimate (which models it) and the steps.
void Run::shape_offset() {
    if (!options_.shaped_offset || options_.op != Operator::CurvatureFlow ||
        !options_.preserve_volume || options_.restoration != VolumeRestoration::NormalOffset)
        return;
    detail::OffsetShapeProblem problem;
    const auto& components = he_.components();
    problem.component_of.assign(n_, -1);
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (target_[c] == 0 || !result_.components[c].closed) continue;
        for (int v : components[c].vertices) problem.component_of[v] = problem.components;
        ++problem.components;
    }
    if (problem.components == 0) return;
    const std::vector<char> free = surface_free();
    detail::StrengthProblem measured;  // what the automatic strength measures the noise on
    measured.op = &surface_;
    measured.free = &free;
    measured.x = &x_;
    measured.mesh = &he_;
    measured.data_vertices = n_;
    strength_normals_ = detail::strength_normals(measured);
    noise_level_ = detail::noise_level(measured, strength_normals_);
    if (options_.time_step.has_value()) Positions().swap(strength_normals_);  // no estimate
    problem.mesh = &he_;
    problem.op = &surface_;
    problem.x = &x_;
    problem.free = &free;
    problem.weight = weight_.empty() ? nullptr : &weight_;
    problem.data_vertices = n_;
    problem.mean_edge = mean_edge_;
    problem.noise_level = noise_level_;
    problem.max_iterations = options_.max_iterations;
    // Two first-order solves: a tenth of the progress range, before the estimate's share.
    constexpr double kShare = 0.1;
    if (options_.progress) problem.progress = [this](double f) { report_progress(kShare * f); };
    problem.assemble_at = [this](const Positions& at) {
        return assemble(options_.op, work_mesh(he_, work_, virtual_mode_), at, options_.normalized,
                        nullptr, options_.threads);
    };
    problem.restore = [this](Positions& x) {
        try {
            for (std::size_t c = 0; c < target_.size(); ++c)
                if (target_[c] != 0) restore_component(c, x, nullptr);
        } catch (const Error&) {  // the run itself says so if its own restoration fails
            return false;
        }
        return true;
    };
    try {
        offset_shape_ = detail::curvature_offset_shape(problem).weight;
    } catch (const Error&) {  // a pilot that fails leaves the offset uniform; the run goes on
        offset_shape_.clear();
    }
}

bool Run::cancels_drift(std::size_t c) const {
    return options_.cancel_drift && options_.preserve_volume &&
           options_.op == Operator::CurvatureFlow && result_.components[c].closed &&
           !result_.components[c].has_fixed;
}

// The translation t minimizing sum_f A_f (n_f . (d_f - t))^2 over the component's faces, d_f the
// mean displacement of the face's vertices from the input, A_f n_f the face's area vector:
// (sum A_f n_f n_f^T) t = sum A_f n_f (n_f . d_f).
void Run::cancel_drift(const Eigen::RowVector3d& origin) {
    if (result_.steps == 0) return;
    const auto& components = he_.components();
    const std::vector<Triangle>& faces = he_.faces();
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (!cancels_drift(c) || result_.components[c].restoration == Restoration::Collapsed)
            continue;
        Eigen::Matrix3d normal_moment = Eigen::Matrix3d::Zero();
        Vec3 along_normals = Vec3::Zero();
        for (int f : components[c].faces) {
            const Triangle& t = faces[f];
            const Vec3 a = detail::row(x_, t[0]);
            const Vec3 area_vector =
                0.5 * (detail::row(x_, t[1]) - a).cross(detail::row(x_, t[2]) - a);
            const double area = area_vector.norm();
            if (!(area > 0)) continue;
            Vec3 d = Vec3::Zero();
            for (int k = 0; k < 3; ++k)
                d += (input_row(t[k]) - origin).transpose() - detail::row(x_, t[k]);
            const Vec3 n = area_vector / area;
            normal_moment += area * n * n.transpose();
            along_normals += area * n * n.dot(d / 3);
        }
        const Eigen::LDLT<Eigen::Matrix3d> solve(normal_moment);
        const Vec3 shift = solve.solve(along_normals);
        // A flat or degenerate component has no well-posed translation normal to it.
        if (solve.info() != Eigen::Success || !std::isfinite(shift.squaredNorm()) ||
            !(solve.vectorD().minCoeff() > 1e-9 * solve.vectorD().maxCoeff()))
            continue;
        for (int v : components[c].vertices) x_.row(v) += shift.transpose();
    }
}

void Run::check_input() {
    const ValidationReport& report = he_.report();
    result_.isolated_vertices = report.isolated_vertices;
    result_.zero_area_faces = report.zero_area_faces;
    result_.dropped_faces = report.dropped_faces;
    result_.inconsistent_edges = report.inconsistent_edges;
    result_.boundary_loops = static_cast<int>(he_.boundary_loops().size());
    if (he_.num_faces() == 0)
        throw Error("the mesh has no faces (" +
                    detail::count_of(n_, "vertex", "vertices") + ", " +
                    detail::count_of(input_triangles_, "face", "faces") +
                    " given): there is nothing to smooth");
    virtual_mode_ =
        options_.boundary == BoundaryMode::VirtualVertex && !he_.boundary_loops().empty();
    if (virtual_mode_ && report.nonmanifold_vertices > 0)
        throw Error(detail::count_of(report.nonmanifold_vertices, "boundary vertex is",
                                     "boundary vertices are") +
                    " non-manifold (several boundary loops meet there), so the virtual-vertex "
                    "boundary mode cannot close the holes",
                    Repair::NonManifoldVertices, "choose another boundary mode");
}

// Work on coordinates centred on the bounding box: the stopping rule and the volume are then as
// accurate far from the origin as near it.
Eigen::RowVector3d Run::centre() {
    Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(INFINITY), hi = -lo;
    for (int i = 0; i < n_; ++i)
        if (!he_.is_isolated(i)) {
            lo = lo.cwiseMin(input_row(i));
            hi = hi.cwiseMax(input_row(i));
        }
    const Eigen::RowVector3d origin = 0.5 * (lo + hi);
    x_.resize(n_, 3);
    for (int i = 0; i < n_; ++i) x_.row(i) = input_row(i) - origin;
    return origin;
}

// Who may move, in the surface system, the boundary curve's and in the restoration.
void Run::set_free_masks() {
    const BoundaryMode boundary = options_.boundary;
    free_surface_.assign(n_, 1);
    free_curve_.assign(n_, 0);
    restorable_.assign(n_, 1);
    for (int i = 0; i < n_; ++i) {
        const bool pinned = hard_[i] || he_.is_isolated(i) ||
                            (boundary == BoundaryMode::Fixed && he_.is_boundary_vertex(i));
        restorable_[i] = !pinned;
        free_surface_[i] = !pinned && !(boundary == BoundaryMode::SmoothCurve &&
                                         he_.is_boundary_vertex(i));
        free_curve_[i] = !pinned && boundary == BoundaryMode::SmoothCurve &&
                         he_.is_boundary_vertex(i);
    }
    for (int v : he_.nonmanifold_vertices()) free_curve_[v] = 0;
}

void Run::add_virtual_mode() {
    if (!virtual_mode_) return;
    std::vector<Triangle> work_faces = he_.faces();
    add_virtual_vertices(he_, x_, work_faces);
    work_ = HalfEdgeMesh::build(x_, work_faces, options_.threads);
    free_surface_.resize(x_.rows(), 1);
}

// Invariants to keep, per component (sections 3.1-3.2).
void Run::set_targets() {
    const auto& components = he_.components();
    target_.assign(components.size(), 0.0);
    input_size_.assign(components.size(), 0.0);
    result_.components.resize(components.size());
    int open_unrestored = 0;
    for (std::size_t c = 0; c < components.size(); ++c) {
        ComponentReport& cr = result_.components[c];
        const Component& comp = components[c];
        cr.faces = static_cast<int>(comp.faces.size());
        cr.closed = comp.closed();
        for (int v : comp.vertices) cr.has_fixed = cr.has_fixed || !restorable_[v];
        cr.measure_before = cr.closed ? component_volume(he_, comp, x_, options_.threads)
                                      : component_area(he_, comp, x_, options_.threads);
        if (!options_.preserve_volume) continue;
        if (cr.closed) target_[c] = cr.measure_before;
        else if (options_.open_invariant == OpenInvariant::Area) target_[c] = cr.measure_before;
        else ++open_unrestored;
        if (target_[c] != 0) input_size_[c] = size_of(comp, x_);
    }
    if (open_unrestored > 0)
        warn(detail::count_of(open_unrestored, "open component encloses",
                              "open components enclose") +
             " no volume: nothing was restored there (choose Area for open components to keep "
             "their surface area)");
}

void Run::assemble_surface() {
    AssemblyReport assembly;
    surface_ = assemble(options_.op, work_mesh(he_, work_, virtual_mode_), x_,
                        options_.normalized, &assembly, options_.threads);
    worst_.zero_area_faces = std::max(worst_.zero_area_faces, assembly.zero_area_faces);
    worst_.floored_edges = std::max(worst_.floored_edges, assembly.floored_edges);
    worst_.massless_vertices = std::max(worst_.massless_vertices, assembly.massless_vertices);
    worst_.negligible_vertices =
        std::max(worst_.negligible_vertices, assembly.negligible_vertices);
    needle_faces_ = std::max(needle_faces_, assembly.needle_faces);
    // The loops keep their first step's operator: the automatic strength models them so, and
    // reassembled at every step the curvature flow's four L^2 steps on libcgal-demo's
    // mech-holes-shark erred 1.11-1.16x the fixed boundary's error (auto-gap.md, section 30).
    if (options_.boundary == BoundaryMode::SmoothCurve && curve_.size() == 0)
        curve_ = assemble_boundary_curve(he_, x_, options_.threads);
    surface_.threads = detail::threads_for(surface_.size(), options_.threads);
    curve_.threads = detail::threads_for(curve_.size(), options_.threads);
}

// Whether the boundary loops are smoothed as a curve of their own (section 5.3): some vertex of
// a loop is free.
bool Run::smooths_curve() const {
    if (options_.boundary != BoundaryMode::SmoothCurve || he_.boundary_loops().empty())
        return false;
    for (char f : free_curve_)
        if (f) return true;
    return false;
}

// Whether an operator is assembled after the first step's (and the automatic strength's
// perturbed one): the steps' own operators, recomputed at every step.
bool Run::assembles_again() const {
    return options_.op != Operator::Umbrella && !frozen_ && options_.steps > 1;
}

// Assembly is the only user of the half-edge pairing: once it is done for good the pairing is
// freed, so that the solves do not hold it (HalfEdgeMesh::release_pairing).
void Run::release_pairing() {
    he_.release_pairing();
    work_.release_pairing();
}

// The surface system's unknowns: free and with mass.
std::vector<char> Run::surface_free() const {
    std::vector<char> free = free_surface_;
    for (int i = 0; i < surface_.size(); ++i)
        if (!(surface_.mass[i] > 0)) free[i] = 0;
    return free;
}

// The given time step, or the automatic one, estimated on the first step's surface system.
void Run::choose_time_step() {
    result_.automatic_time_step = !options_.time_step.has_value();
    if (!result_.automatic_time_step) {
        time_step_ = *options_.time_step;
        curve_time_step_ = time_step_;
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const bool has_units = options_.op != Operator::Umbrella && !options_.normalized;
    const std::vector<char> free = surface_free();
    detail::StrengthProblem problem;
    problem.op = &surface_;
    problem.free = &free;
    problem.weight = weight_.empty() ? nullptr : &weight_;
    problem.x = &x_;
    problem.mesh = &he_;
    problem.data_vertices = n_;
    problem.length_unit = has_units ? length_unit_ : 1.0;
    problem.order = options_.order;
    problem.steps = std::max(1, options_.steps);
    problem.pilot = assembles_again();  // the steps recompute the weights of the positions
    // Each recomputed step is restored on its own (take_steps), and each decides offset or
    // scaling: so modelled for first-order steps and the curvature flow's L^2 steps. On a sphere
    // the curvature flow's best L^2 step lies just before fair()'s own switch (a step losing more
    // than kMaxOffsetChange is rescaled, and the error jumps 8 %); modelled on the steps' total,
    // the switch came four times too early for four steps and held the choice back. Per step,
    // over eight probes of each two-density sphere case of the study's three draws, its default
    // missed its best step by more than 10 % in 41 of 224 runs instead of 79, and on a thin plate
    // 1.36-1.42x -> 1.00-1.01x; the scale-dependent L^2 steps got worse on the plate (1.24-1.28x
    // -> 1.33-1.38x) and kept their choices elsewhere, so they keep the total (auto-gap.md,
    // sections 26 and 37).
    if (problem.pilot && (options_.order == 1 || options_.op == Operator::CurvatureFlow))
        problem.restorations = problem.steps;
    problem.residual_on_later_steps = options_.op == Operator::CurvatureFlow;
    // The curvature flow's later steps keep the umbrella's pilot: its own clamped cotangent
    // weights moved the study's sphere rows away from their best steps (auto-gap.md, 29).
    problem.pilot_on_own_weights = options_.op == Operator::ScaleDependent;
    problem.explicit_integration = options_.integration == Integration::Explicit;
    // Explicit: at most half the first step's stability bound. At the bound the highest mode
    // flips sign undamped, and later steps on recomputed operators have lower bounds.
    if (problem.explicit_integration)
        problem.max_time_step =
            0.5 * explicit_bound(surface_, free, options_.order) / problem.length_unit;
    // The estimate costs about as much as one solve: a third of the progress range.
    constexpr double kShare = 1.0 / 3;
    const auto& components = he_.components();
    problem.restored.assign(n_, -1);
    std::vector<int> modelled;  // the components problem.offset lists
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (target_[c] == 0 || !result_.components[c].closed) continue;  // volume only
        modelled.push_back(static_cast<int>(c));
        for (int v : components[c].vertices) problem.restored[v] = static_cast<int>(problem.offset.size());
        problem.offset.push_back(result_.components[c].has_fixed                             ? 1
                                 : options_.restoration == VolumeRestoration::NormalOffset ? 2
                                                                                           : 0);
        problem.cancel_drift.push_back(cancels_drift(c) ? 1 : 0);
    }
    const bool estimates_curve = smooths_curve();  // its estimate assembles loops: the pairing
    if (estimates_curve && strength_normals_.rows() == 0)  // the curve's estimate needs them too
        strength_normals_ = detail::strength_normals(problem);
    problem.normals = strength_normals_.rows() > 0 ? &strength_normals_ : nullptr;
    // The first-order curvature flow's loss is its mean curvature, which the shape follows, so
    // the model restores as fair() will; the L^2 flow's loss follows the shape less well, and
    // modelling it let the choice run away on tori (auto-gap.md sections 24-25).
    problem.offset_shape =
        options_.order == 1 && !offset_shape_.empty() ? &offset_shape_ : nullptr;
    problem.noise_level = noise_level_;
    if (options_.progress) problem.progress = [this](double f) { report_progress(kShare * f); };
    if (options_.op == Operator::Umbrella && !estimates_curve) release_pairing();
    if (options_.op != Operator::Umbrella)  // weights of the positions: Monte-Carlo divergence
        problem.assemble_at = [this, estimates_curve](const Positions& at) {
            SparseOperator op = assemble(options_.op, work_mesh(he_, work_, virtual_mode_), at,
                                         options_.normalized, nullptr, options_.threads);
            if (!assembles_again() && !estimates_curve) release_pairing();  // the last one
            return op;
        };
    const detail::StrengthEstimate e = compares_freezing()
                                           ? estimate_frozen_or_recomputed(problem, kShare)
                                           : detail::estimate_strength(problem);
    time_step_ = e.time_step;
    if (!e.restoration.empty()) {
        modelled_restoration_.assign(components.size(), 2);
        for (std::size_t k = 0; k < modelled.size() && k < e.restoration.size(); ++k)
            modelled_restoration_[modelled[k]] = e.restoration[k];
    }
    curve_time_step_ = time_step_;
    int curve_lanczos_steps = 0;
    if (estimates_curve && e.noise_level > 0)
        curve_lanczos_steps = choose_curve_time_step(problem, e.noise_level);
    Positions().swap(strength_normals_);
    progress_offset_ = std::max(progress_, kShare);
    result_.noise_level = e.noise_level;
    result_.noise_level_edges = mean_edge_ > 0 ? e.noise_level / mean_edge_ : 0.0;
    result_.trace_fraction = e.trace_fraction;
    result_.strength_iterations = e.lanczos_steps + curve_lanczos_steps;
    result_.strength_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Options::freeze_when_better: recomputed steps follow the shape as it smooths, which keeps a
// noisy sphere round and shrinks a scan's thin parts (their vertex areas fall, so the flow there
// speeds up); frozen ones hold the first step's weights and areas (auto-gap.md, section 41).
// Neither wins everywhere, and no statistic of the input told spheres from scans through the
// noise; the risk each would run at does (Ramani et al.'s Monte-Carlo SURE compares any two
// filters of the same data). Both are estimated with the same normals and noise level, and the
// frozen steps are taken where their estimated error at its best time step is the lower by
// more than a margin (kFreezeMargin). The recomputed model is the rougher one (the mean operator,
// header of auto_strength.h), so the margin bounds its error on the shapes where recomputing
// wins. Measured on the seven sets' 188 cases, one click recomputed and frozen (auto-gap.md,
// section 45): the recomputed estimate less the frozen one reached at most 0.0035 (curvature
// flow) and 0.0051 (scale-dependent) of the noise's variance on the spheres and 0.0175 and
// 0.0040 on the torus, and exceeded 0.033 on nine in ten scans (curvature flow) and 0.0063 on
// three in four (scale-dependent). The estimate is the error along the normals, and on scans the
// frozen steps gain more in the distance to the surface than it shows: the curvature flow
// 0.80-0.85x where it reads 0.07-0.08 lower.
bool Run::compares_freezing() const {
    return options_.freeze_when_better && !frozen_ && options_.op != Operator::Umbrella &&
           options_.steps > 1 && options_.integration == Integration::Implicit;
}

detail::StrengthEstimate Run::estimate_frozen_or_recomputed(detail::StrengthProblem& problem,
                                                            double share) {
    const double margin = options_.op == Operator::CurvatureFlow ? kFreezeMargin
                                                                 : kFreezeMarginScaleDependent;
    if (strength_normals_.rows() == 0) strength_normals_ = detail::strength_normals(problem);
    problem.normals = &strength_normals_;
    if (!(noise_level_ > 0)) noise_level_ = detail::noise_level(problem, strength_normals_);
    problem.noise_level = noise_level_;
    if (!(noise_level_ > 0)) return detail::estimate_strength(problem);  // no time step at all
    detail::StrengthProblem frozen = problem;
    frozen.pilot = false;  // as choose_time_step builds it for frozen steps
    frozen.restorations = 1;
    if (options_.progress) {
        problem.progress = [this, share](double f) { report_progress(0.5 * share * f); };
        frozen.progress = [this, share](double f) { report_progress(share * (0.5 + 0.5 * f)); };
    }
    detail::StrengthEstimate recomputed = detail::estimate_strength(problem);
    if (std::isfinite(recomputed.excess_risk))  // the frozen search stops once it cannot win
        frozen.chosen_below = recomputed.excess_risk - margin;
    detail::StrengthEstimate kept = detail::estimate_strength(frozen);
    kept.lanczos_steps += recomputed.lanczos_steps;
    recomputed.lanczos_steps = kept.lanczos_steps;
    if (!std::isfinite(recomputed.excess_risk) || !std::isfinite(kept.excess_risk))
        return recomputed;
    result_.operator_compared = true;
    result_.recomputed_risk = recomputed.excess_risk;
    result_.frozen_risk = kept.excess_risk;
    result_.frozen_risk_is_bound = kept.out_of_reach;
    if (kept.out_of_reach || !(recomputed.excess_risk - kept.excess_risk > margin))
        return recomputed;
    frozen_ = true;
    return kept;
}

// The boundary loops (section 5.3) as a problem of their own: eq. 11 on a loop is a 1-D operator
// whose best strength follows the loop's sampling and corners, not the surface's (on
// libcgal-demo's open turbine blade the best loop step moved from 0.01 to 100 between a tenth and
// half an edge of noise while the surface's stayed near 200-270; auto-gap.md, section 29). The
// noise level and normals are the surface's: a loop's few vertices would estimate them poorly.
// Nothing is restored on a loop, and it keeps its first step's operator. Implicit steps of every
// order are measured exactly by direct solves (loop_strength.h); explicit ones by the surface's
// Lanczos model, which sees only the normals' channel: at orders 3 and 4 it rounded a noisy
// square's outline by 1.2 cells and drew a hole's loop 0.44 cells in (auto-gap.md, section 41).
// Returns the Lanczos steps taken; on failure the loops keep the surface's time step.
int Run::choose_curve_time_step(const detail::StrengthProblem& surface, double noise_level) {
    // The loop's weights 1/|e| come from the noisy data and, on a loop sampled finer than the
    // noise, depend on it: the risk takes the Monte-Carlo divergence (auto-gap.md, section 30).
    const auto assemble_at = [this](const Positions& at) {
        return assemble_boundary_curve(he_, at, options_.threads);
    };
    try {
        if (!surface.explicit_integration) {
            detail::LoopStrengthProblem loop;
            loop.op = &curve_;
            loop.free = &free_curve_;
            loop.weight = surface.weight;
            loop.x = &x_;
            loop.normals = surface.normals;
            loop.mesh = &he_;
            loop.noise_level = noise_level;
            loop.length_unit = length_unit_;
            loop.order = surface.order;
            loop.steps = surface.steps;
            loop.assemble_at = assemble_at;
            const double chosen = detail::loop_time_step(loop);
            if (chosen > 0) curve_time_step_ = chosen;
            return 0;
        }
        detail::StrengthProblem loop;
        loop.op = &curve_;
        loop.free = &free_curve_;
        loop.weight = surface.weight;
        loop.x = &x_;
        loop.mesh = &he_;
        loop.data_vertices = n_;
        loop.length_unit = length_unit_;
        loop.order = surface.order;
        loop.steps = surface.steps;
        loop.explicit_integration = surface.explicit_integration;
        loop.normals = surface.normals;
        loop.noise_level = noise_level;
        loop.assemble_at = assemble_at;
        if (loop.explicit_integration)
            loop.max_time_step =
                0.5 * explicit_bound(curve_, free_curve_, options_.order) / loop.length_unit;
        const detail::StrengthEstimate c = detail::estimate_strength(loop);
        if (c.time_step > 0) curve_time_step_ = c.time_step;
        return c.lanczos_steps;
    } catch (const Error&) {  // the run goes on
    }
    return 0;
}

void Run::take_steps() {
    const bool has_units = options_.op != Operator::Umbrella && !options_.normalized;
    const double lambda_dt = time_step_ * (has_units ? length_unit_ : 1.0);
    const double curve_lambda_dt = curve_time_step_ * length_unit_;
    result_.lambda_dt = lambda_dt;
    result_.time_step = time_step_;
    result_.boundary_time_step = smooths_curve() ? curve_time_step_ : 0.0;
    const int steps = lambda_dt > 0 ? options_.steps : 0;
    const bool recompute = options_.op != Operator::Umbrella && !frozen_;
    result_.operator_frozen = options_.op != Operator::Umbrella && frozen_;
    const bool curve = options_.boundary == BoundaryMode::SmoothCurve && !he_.boundary_loops().empty();
    ever_free_.assign(n_, 0);
    if (!assembles_again()) release_pairing();
    if (steps >= 2 && !recompute && !curve && take_frozen_steps(lambda_dt, steps)) return;
    // On a frozen operator the steps are one linear filter, and a normal offset follows it once
    // (Options::preserve_volume), as take_frozen_steps does.
    const bool restore_at_end = !recompute && options_.restoration == VolumeRestoration::NormalOffset;
    // Recomputed L^3 and L^4 curvature steps can shrink vertex stars until their systems are out
    // of reach (Run::ill_conditioning): one click at order 4 was refused on libcgal-demo's bull,
    // camel, cheese, femur and homer, at order 3 on the cheese and the femur. From the step that
    // fails, the steps keep the last operator that solved, frozen as section 4.3 allows; on the
    // femur at half an edge of noise (order 3, steps 3-4 kept step 2's) that errs 0.232 mean
    // edges from the clean surface, where solving every recomputed step (at 50 times the iteration
    // cap, 90 times the time) errs 0.223 and a frozen operator from the start 0.220.
    const bool may_freeze_later = recompute && options_.order >= 3 && steps > 1 &&
                                  options_.integration == Integration::Implicit;
    SparseOperator solved;  // may_freeze_later: the operator of the last step that solved
    Positions before;       // and the positions its failed successor started from
    int frozen_from = -1;   // the step from which the operator was kept
    bool loops_held = false;  // the loops' system could not be solved: they stay in place
    for (int step = 0; step < steps; ++step) {
        if (step > 0 && recompute && frozen_from < 0) {
            if (may_freeze_later) solved = std::move(surface_);
            assemble_surface();
        }
        if (step + 1 == steps) release_pairing();
        if (curve && !loops_held) {
            for (int i = 0; i < n_; ++i) ever_free_[i] |= free_curve_[i];
            loops_held = !smooth_loops(curve_lambda_dt, step, steps);
        }
        std::vector<char> free = surface_free();
        for (int i = 0; i < n_; ++i) ever_free_[i] |= free[i];
        release_free_memory();  // before the solve's vectors: the peak
        const bool may_retake = may_freeze_later && step > 0 && frozen_from < 0;
        if (may_retake) before = x_;
        const std::size_t reports = result_.solves.size();
        const double max_residual = result_.max_residual;
        double flight = 0;  // may_retake: how far the step threw a vertex (farthest_flight)
        try {
            integrate(surface_, free, lambda_dt, step, "surface");
            if (may_retake && (flight = farthest_flight(before)) > kBlownUp)
                throw UnsolvedStep("blown up");
        } catch (const UnsolvedStep&) {
            if (!may_retake) throw;
            const double ratio = smallest_mass_ratio(surface_, free);
            x_.swap(before);
            result_.solves.resize(reports);  // its iterations stay counted: they were spent
            result_.max_residual = max_residual;
            surface_ = std::move(solved);
            free = surface_free();
            for (int i = 0; i < n_; ++i) ever_free_[i] |= free[i];
            integrate(surface_, free, lambda_dt, step, "surface");
            frozen_from = step;
            const std::string order = "its order-" + std::to_string(options_.order);
            const std::string why =
                flight > kBlownUp ? order + " step threw a vertex " + number(flight) +
                                        " times its part's RMS radius"
                                  : order + " system could not be solved";
            warn(std::string(step + 1 < steps ? "steps " : "step ") + std::to_string(step + 1) +
                 (step + 1 < steps ? "-" + std::to_string(steps) : std::string()) +
                 " kept the operator of step " + std::to_string(step) +
                 " (frozen, section 4.3): assembled again, its smallest vertex " +
                 (options_.op == Operator::CurvatureFlow ? "area" : "mass") + " was " +
                 number(ratio) + " of the mean, and " + why +
                 ". Recomputed steps of order 3 and 4 shrink vertex stars; a lower order or a "
                 "frozen operator does not");
        }
        if (!x_.allFinite())
            throw Error("step " + std::to_string(step + 1) +
                        " produced non-finite positions; the mesh was left unchanged (with "
                        "explicit integration, use a smaller time step)");
        if (!restore_at_end || step + 1 == steps) restore();
        ++result_.steps;
        report_progress(static_cast<double>(step + 1) / steps);
    }
}

// One step of the boundary loops (section 5.3). A loop far finer than the mean edge and far from
// the origin (the three-vertex sliver holes of libcgal-demo's dragon, 0.02 edges around) makes
// its L^4 system stiffer than even a factorization about the loop's centroid can carry; then the
// loops stay where they are from this step on, as with a fixed boundary, and the run says so.
// false: held.
bool Run::smooth_loops(double lambda_dt, int step, int steps) {
    std::vector<int> loop_rows;
    for (int i = 0; i < n_; ++i)
        if (free_curve_[i]) loop_rows.push_back(i);
    Positions kept(static_cast<Eigen::Index>(loop_rows.size()), 3);
    for (std::size_t k = 0; k < loop_rows.size(); ++k) kept.row(k) = x_.row(loop_rows[k]);
    const std::size_t reports = result_.solves.size();
    const double max_residual = result_.max_residual;
    try {
        integrate(curve_, free_curve_, lambda_dt, step, "boundary curve");
        return true;
    } catch (const UnsolvedStep&) {
        for (std::size_t k = 0; k < loop_rows.size(); ++k) x_.row(loop_rows[k]) = kept.row(k);
        result_.solves.resize(reports);
        result_.max_residual = max_residual;
        warn("the boundary loops stayed in place " +
             (step + 1 < steps ? "from step " + std::to_string(step + 1) + " on"
                               : "in step " + std::to_string(step + 1)) +
             ": their order-" + std::to_string(options_.order) +
             " system could not be solved, which a loop far finer than the mean edge (a sliver "
             "hole) causes; MeshLab's 'Close Holes' fills such holes, or choose a lower order");
        return false;
    }
}

// Vertices that may not move keep their input coordinates bit for bit. The copy is made only
// now, when the solver's vectors are gone, to keep the peak memory down, and straight in the
// caller's numbering.
void Run::finish(const Eigen::RowVector3d& origin) {
    result_.positions = input_;
    int fixed = 0;
    for (int i = 0; i < n_; ++i) {
        if (he_.is_isolated(i)) continue;
        if (!ever_free_[i]) ++fixed;
        // No step taken (time step 0), or a component left as given (Run::restore): keep the
        // input bits, not (p - origin) + origin.
        if (restorable_[i] && result_.steps > 0 && (left_as_given_.empty() || !left_as_given_[i]))
            result_.positions.row(order_.empty() ? i : order_[i]) = x_.row(i) + origin;
    }
    if (!result_.positions.allFinite())
        throw Error("the result holds non-finite positions; the mesh was left unchanged");
    result_.vertices_fixed = fixed;
    for (int i = 0; i < n_; ++i)
        if (result_.positions.row(i) != input_.row(i)) ++result_.vertices_moved;
    const auto& components = he_.components();
    for (std::size_t c = 0; c < components.size(); ++c) {
        ComponentReport& cr = result_.components[c];
        cr.measure_after = cr.closed ? component_volume(he_, components[c], x_, options_.threads)
                                     : component_area(he_, components[c], x_, options_.threads);
        if (cr.closed) {
            result_.volume_before += cr.measure_before;
            result_.volume_after += cr.measure_after;
        }
    }
    if (result_.steps > 0 &&
        std::none_of(ever_free_.begin(), ever_free_.end(), [](char f) { return f != 0; }))
        warn("no vertex was free to move: all " +
             detail::count_of(n_ - he_.report().isolated_vertices, "vertex", "vertices") +
             " in faces are fixed (on a fixed boundary, unselected, of weight 0, or with only "
             "degenerate faces around them); the mesh is unchanged");
}

// Duplicated vertices split the surface into open pieces whose boundaries coincide, so boundary
// vertices at exactly the position of another one give them away (checking the boundary only
// keeps this off the cost of closed meshes).
// p holds the positions in the caller's numbering, `renumbering` maps he's vertices to its rows
// (empty: the same numbering).
int coincident_boundary_vertices(const HalfEdgeMesh& he, const Positions& p,
                                 const std::vector<int>& renumbering) {
    std::vector<int> order;
    for (int i = 0; i < he.num_vertices(); ++i)
        if (he.is_boundary_vertex(i)) order.push_back(renumbering.empty() ? i : renumbering[i]);
    const auto less = [&](int a, int b) {
        for (int k = 0; k < 3; ++k)
            if (p(a, k) != p(b, k)) return p(a, k) < p(b, k);
        return false;
    };
    std::sort(order.begin(), order.end(), less);
    int coincident = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
        if ((k > 0 && !less(order[k - 1], order[k])) ||
            (k + 1 < order.size() && !less(order[k], order[k + 1])))
            ++coincident;
    return coincident;
}

void Run::warn_about_input() {
    const ValidationReport& report = he_.report();
    const int coincident = coincident_boundary_vertices(he_, input_, order_);
    if (coincident > 0)
        warn(detail::count_of(coincident, "vertex shares its position",
                              "vertices share their position") +
             " with another vertex (duplicated vertices split the surface into open pieces; "
             "MeshLab's 'Remove Duplicate Vertices' merges them)");
    if (report.dropped_faces > 0)
        warn(detail::count_of(report.dropped_faces, "face repeats", "faces repeat") +
             " a vertex and was left out (MeshLab's 'Remove Zero Area Faces' deletes them)");
    if (report.isolated_vertices > 0)
        warn(detail::count_of(report.isolated_vertices, "isolated vertex", "isolated vertices") +
             " (in no face) left out (MeshLab's 'Remove Unreferenced Vertices' deletes them)");
    if (report.zero_area_faces > 0)
        warn(detail::count_of(report.zero_area_faces, "face has", "faces have") +
             " zero area and contribute nothing to the curvature operator (MeshLab's 'Remove "
             "Zero Area Faces' deletes them)");
    if (report.inconsistent_edges > 0)
        warn(detail::count_of(report.inconsistent_edges, "edge joins", "edges join") +
             " faces of opposite orientation; their components are treated as open (run "
             "MeshLab's 'Re-Orient all faces coherentely')");
    if (report.nonmanifold_vertices > 0 && options_.boundary == BoundaryMode::SmoothCurve)
        warn(detail::count_of(report.nonmanifold_vertices, "non-manifold boundary vertex was",
                              "non-manifold boundary vertices were") +
             " kept out of the boundary-curve smoothing");
    if (worst_.floored_edges > 0)
        warn(detail::count_of(worst_.floored_edges, "edge is", "edges are") +
             " shorter than " + number(100 * kDuplicateEdge) +
             " % of the mean edge (duplicated vertices?); their weight was bounded as that of "
             "any edge under " + number(100 * kShortEdge) +
             " % of the mean (MeshLab's 'Merge Close Vertices' repairs this)");
    int flattened = 0, flattened_vertices = 0;
    for (std::size_t c = 0; c < result_.components.size(); ++c)
        if (result_.components[c].restoration == Restoration::Collapsed) {
            ++flattened;
            flattened_vertices += static_cast<int>(he_.components()[c].vertices.size());
        }
    if (flattened > 0)
        warn(detail::count_of(flattened, "component", "components") + " (" +
             detail::count_of(flattened_vertices, "vertex", "vertices") + ") " +
             (flattened == 1 ? "was" : "were") +
             " left as given: the steps flattened it, so that " + flattening() +
             "; a smaller time step smooths it too");
    if (worst_.massless_vertices > 0)
        warn(detail::count_of(worst_.massless_vertices, "vertex has", "vertices have") +
             (worst_.massless_vertices == 1 ? " only degenerate faces around it and was"
                                            : " only degenerate faces around them and were") +
             " kept in place");
    if (worst_.negligible_vertices > 0)
        warn(detail::count_of(worst_.negligible_vertices, "vertex was", "vertices were") +
             " kept in place once the steps had shrunk the faces around " +
             (worst_.negligible_vertices == 1 ? "it" : "them") + " below " +
             number(kNegligibleArea) +
             " of the mean vertex area: the flow shrinks small closed parts to a point when the "
             "volume is not preserved (preserve it, or take a smaller time step)");
    if (needle_faces_ > 0)
        warn(detail::count_of(needle_faces_, "face was a needle", "faces were needles") +
             " (an angle below 0.01 rad) in some step; their cotangent weights were capped at " +
             number(kCotangentCap) +
             ", as every sliver's (MeshLab's 'Remove T-Vertices by Edge Flip' or 'Merge Close "
             "Vertices' repairs them)");
}

Result Run::run() {
    check_input();
    const Eigen::RowVector3d origin = centre();
    origin_ = origin;
    mean_edge_ = mean_edge_length(he_, x_, options_.threads);
    result_.mean_edge_length = mean_edge_;
    // L is in 1/length^2 (L^2 in 1/length^4) for all but the dimensionless operators.
    length_unit_ = std::pow(mean_edge_, 2 * options_.order);
    set_free_masks();
    add_virtual_mode();
    set_targets();
    // The first step's operators (also what the automatic strength is estimated on).
    const bool may_step = options_.steps > 0 && !(options_.time_step.has_value() &&
                                                  *options_.time_step == 0);
    if (may_step) assemble_surface();
    if (may_step) shape_offset();
    if (may_step) choose_time_step();
    if (result_.automatic_time_step) release_free_memory();  // the estimate's vectors
    else time_step_ = options_.time_step.value_or(0);
    take_steps();
    cancel_drift(origin);
    finish(origin);
    warn_about_input();
    return std::move(result_);
}

}  // namespace

Result fair(const TriangleMesh& mesh, const Constraints& constraints, const Options& options) {
    const auto start = std::chrono::steady_clock::now();
    validate(mesh, constraints, options);
    const std::vector<int> order = detail::locality_order(mesh);
    std::unique_ptr<Run> run;
    if (order.empty()) {
        run = std::make_unique<Run>(mesh, mesh.positions, order, constraints, options);
    } else {
        // The same run on a cache-friendly numbering (vertex_order.h). The renumbered copy
        // (48 bytes per vertex) only builds the run's half-edge view: it is freed before the
        // solves, and the run writes its result in the caller's numbering.
        const TriangleMesh local = detail::renumbered(mesh, order);
        run = std::make_unique<Run>(local, mesh.positions, order,
                                    detail::renumbered(constraints, order), options);
    }
    Result result = run->run();
    run.reset();
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace fairing
