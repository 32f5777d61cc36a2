// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Filter logic of the implicit fairing plugin. No numerics here (the engine in fairing/ does
// them) and no MeshLab API differences (meshlab_api.h maps them): this file builds the parameter
// list, translates parameters into fairing::Options, runs the adapters and the engine, and logs.
#include "filter_implicit_fairing.h"

#include <fairing/fairing.h>
#include <fairing_parameters/filter_parameters.h>
#include <vcg_adapters/vcg_adapters.h>

#include <QElapsedTimer>
#include <QStringList>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <thread>

namespace {

using namespace filter_parameters;

QStringList labels(const std::vector<std::string>& v)
{
    QStringList out;
    for (const std::string& s : v) out << QString::fromStdString(s);
    return out;
}

fairing::Operator operatorOf(fairing_plugin::FilterId id)
{
    switch (id) {
    case FilterImplicitFairing::FP_UMBRELLA: return fairing::Operator::Umbrella;
    case FilterImplicitFairing::FP_SCALE_DEPENDENT: return fairing::Operator::ScaleDependent;
    default: return fairing::Operator::CurvatureFlow;
    }
}

QString num(double x) { return QString::number(x, 'g', 6); }

}  // namespace

FilterImplicitFairing::FilterImplicitFairing()
{
    registerFilters({FP_UMBRELLA, FP_SCALE_DEPENDENT, FP_CURVATURE_FLOW});
}

QString FilterImplicitFairing::pluginName() const { return "FilterImplicitFairing"; }

QString FilterImplicitFairing::filterName(fairing_plugin::FilterId id) const
{
    switch (id) {
    case FP_UMBRELLA: return QStringLiteral("Implicit Fairing: Umbrella Diffusion");
    case FP_SCALE_DEPENDENT: return QStringLiteral("Implicit Fairing: Scale-Dependent Diffusion");
    case FP_CURVATURE_FLOW: return QStringLiteral("Implicit Fairing: Curvature Flow");
    }
    return QString();
}

QString FilterImplicitFairing::pythonNameOf(fairing_plugin::FilterId id) const
{
    switch (id) {
    case FP_UMBRELLA: return QStringLiteral("apply_coord_implicit_fairing_umbrella");
    case FP_SCALE_DEPENDENT: return QStringLiteral("apply_coord_implicit_fairing_scale_dependent");
    case FP_CURVATURE_FLOW: return QStringLiteral("apply_coord_implicit_fairing_curvature_flow");
    }
    return QString();
}

QString FilterImplicitFairing::filterInfo(fairing_plugin::FilterId id) const
{
    QString what;
    switch (id) {
    case FP_UMBRELLA:
        what = tr("Diffusion with the <b>umbrella operator</b> (eq. 7): each vertex moves towards "
                  "the average of its neighbours. Strong fairing changes the shape most, as "
                  "triangles drift and even out in size: it also regularizes the triangulation. "
                  "<b>Pick it for noisy scans</b>: with its defaults it had the lowest error of "
                  "the three on every scan of the denoising study (e.g. the fandisk at noise 0.25 "
                  "edge: 0.108 edge, against 0.115 scale-dependent and 0.117 curvature flow; "
                  "MeshLab's Taubin Smooth at its best iteration count 0.107), and on a torus it "
                  "beat every other smoother at its best (0.033 edge against 0.039 or more).");
        break;
    case FP_SCALE_DEPENDENT:
        what = tr("Diffusion with the <b>scale-dependent umbrella operator</b> (Fujiwara, eq. 11; "
                  "neighbours weighted by 1/edge length): stays closer to the original shape and "
                  "almost keeps the triangle sizes. For irregular meshes whose sampling should "
                  "stay as it is (with the defaults, 0.038 edge on a two-density sphere at noise "
                  "0.25, between the umbrella's 0.071 and the curvature flow's 0.017).");
        break;
    case FP_CURVATURE_FLOW:
        what = tr("<b>Curvature flow</b> (eq. 14, cotangent weights): vertices move along the "
                  "normal by the mean curvature, so they do not slide over the surface and "
                  "spheres stay spheres and flat regions stay flat; the volume the flow takes "
                  "from convex, strongly curved parts goes back there. <b>Pick it when only the "
                  "shape should change</b>, and for smooth shapes: with its defaults, on the "
                  "two-density sphere at noise 0.25 edge it reached 0.017 edge (CGAL's "
                  "smooth_shape at its best: 0.027), on a torus 0.033 (0.037 with a uniform "
                  "volume offset).");
        break;
    }
    // Short on purpose: MeshLab puts this text above the parameters, and at full length it
    // made the dialog 1138 pixels tall, past the top of a 1200-pixel screen. Each parameter's
    // own tooltip explains it.
    return what + tr(
        "<br>Implicit steps (I - &lambda;dt L) X' = X, or (I + &lambda;dt L&sup2;) X' = X, solved in "
        "symmetric form: stable for any time step. On failure the mesh is left untouched.<br>"
        "<b>Time step</b> 0 (the default) chooses the strength from the mesh: it estimates the "
        "noise along the normals and takes the step minimizing Stein's unbiased estimate of the "
        "error; the choice and the noise level are logged. Fine detail counts as noise too: on "
        "clean detailed scans give a small time step. Each parameter's tooltip says more.<br>"
        "See: <i>M. Desbrun, M. Meyer, P. Schr&ouml;der, A. H. Barr</i>, <b>\"Implicit Fairing "
        "of Irregular Meshes using Diffusion and Curvature Flow\"</b>, SIGGRAPH 99, 317-324.");
}

FilterImplicitFairing::FilterClass FilterImplicitFairing::classOf(fairing_plugin::FilterId) const
{
    return Interface::Smoothing;
}

int FilterImplicitFairing::preConditionsOf(fairing_plugin::FilterId) const
{
    return MeshModel::MM_FACENUMBER;
}

int FilterImplicitFairing::postConditionOf(fairing_plugin::FilterId) const
{
    return MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL;
}

void FilterImplicitFairing::initParameters(fairing_plugin::FilterId id, const MeshModel* current,
                                           RichParameterList& par)
{
    const bool selection = current != nullptr && vcg_adapters::hasSelection(current->cm);
    const Values d = defaults(operatorOf(id));
    par.addParam(RichFloat(kTimeStep, static_cast<float>(d.timeStep),
        tr("Time step (0 = automatic)"),
        tr("Strength of each step (the paper's lambda*dt). 0, the default, chooses it from the "
           "mesh itself: the noise along the normals is estimated and the step that minimizes "
           "the expected error (Stein's unbiased risk estimate) is taken; the choice and the "
           "noise level are logged. Any other value is dimensionless, independent of the mesh's "
           "units: the scale-dependent and curvature operators multiply it by the power of the "
           "mean edge length their units need, so the same value works in millimetres and "
           "metres; larger values smooth more.")));
    par.addParam(RichInt(kSteps, d.steps, tr("Smoothing steps"),
        tr("Number of implicit steps; each one applies the time step again. The defaults "
           "(umbrella 8, scale-dependent 2, curvature flow 4) gave the lowest errors in the "
           "denoising study; the umbrella's steps share one operator and run as one solve, so "
           "its 8 cost what 4 would.")));
    par.addParam(RichEnum(kOrder, d.order, labels(orderLabels()), tr("Operator order"),
        tr("L: diffusion/flow with the operator itself. L²: with the squared operator "
           "(section 2.6), a much sharper low-pass filter: removes noise, keeps shape. "
           "L³, L⁴: the higher powers of the paper's Figure 3a, closer still to a low-pass "
           "filter (each step a first-order and a complex solve, or two complex ones). With "
           "the umbrella, two L³ steps beat four L² ones on smooth, finely sampled scans (a "
           "Loop-subdivided elephant: 1.8-2.6 % lower error) and lose on detailed ones (a "
           "dragon: up to 5 % higher); a strong step costs about three L² steps.")));
    par.addParam(RichEnum(kIntegration, d.integration, labels(integrationLabels()),
        tr("Integration"),
        tr("Implicit (backward Euler) is stable for any time step. Explicit (forward Euler) is "
           "for comparison and unstable for large time steps (a warning says when); its "
           "normalized variant uses the operators of section 5.5, stable up to a time step of "
           "about 1.")));
    par.addParam(RichBool(kPreserveVolume, d.preserveVolume, tr("Preserve volume"),
        tr("After each step, restore the initial volume of every closed component (sections "
           "3.1-3.2) by offsetting its free vertices along their normals, the smallest "
           "correction (a loss above 10 % is scaled about the centroid, as in the paper; with "
           "the automatic time step, except for several first-order or curvature flow steps, "
           "as the strength's estimate modelled the chosen step). The curvature flow's offset "
           "follows the smoothed mean curvature, where the flow took the volume.")));
    par.addParam(RichEnum(kOpenInvariant, d.openInvariant, labels(openInvariantLabels()), tr("Open components"),
        tr("Components with a boundary enclose no volume: keep nothing, or keep their surface "
           "area.")));
    par.addParam(RichEnum(kBoundaryMode, d.boundaryMode, labels(boundaryModeLabels()), tr("Boundary"),
        tr("Fixed: boundary vertices do not move. Smooth boundary curve: each boundary loop is "
           "faired as a curve first, then the interior; with the automatic time step the loops "
           "get one chosen for them on their own (in the log), which takes the noise off the "
           "border of an open scan that Fixed keeps. Virtual vertex: a hidden vertex at the "
           "centre of each hole lets the boundary move with the surface. Automatic (default): "
           "Smooth boundary curve with the automatic time step, Fixed with one you give: on "
           "open CAD parts with holes (libcgal-demo's turbine blade and mech-holes-shark) it "
           "took 2-46 % off the fixed boundary's error.")));
    par.addParam(RichBool(kQualityWeights, d.qualityWeights, tr("Use vertex quality as smoothing weight"),
        tr("Per-vertex quality, clamped to [0,1], scales the smoothing at each vertex; 0 keeps "
           "the vertex fixed, 1 smooths fully. Needs a mesh with vertex quality.")));
    par.addParam(RichBool(kInvertQuality, d.invertQuality, tr("Invert quality weight"),
        tr("Use 1 - quality as the weight: high quality means little smoothing.")));
    par.addParam(RichBool(kSelected, selection, tr("Affect only selection"),
        tr("If checked, only the selected vertices move (for a face selection: vertices whose "
           "faces are all selected); every other vertex stays exactly where it is.")));
    par.addParam(RichFloat(kTolerance, static_cast<float>(d.tolerance), tr("Solver tolerance"),
        tr("The conjugate gradient stops when the relative residual |AX-b|/|b| is below this.")));
    par.addParam(RichInt(kMaxIterations, d.maxIterations, tr("Max solver iterations"),
        tr("Iteration cap of each conjugate-gradient solve. A solve that stops short of the "
           "tolerance (at the cap, or stalled by needle triangles) on a mesh of up to 100,000 "
           "free vertices (L or L²; L³ 50,000, L⁴ 25,000) is solved again directly (sparse "
           "LDLᵀ).")));
    par.addParam(RichBool(kFreezeOperator, d.freezeOperator, tr("Freeze operator"),
        tr("Keep the operator's weights of the first step for all steps (smoothing relative to "
           "the initial mesh, section 4.3) instead of recomputing them at each step. Off "
           "(default): recomputed, except that with the automatic time step the curvature flow "
           "and the scale-dependent filter estimate the error of frozen steps too and freeze "
           "where it is the lower (the log says which ran): over the denoising study's 120 scan "
           "cases their one-click error fell by 11 % and 4 %, and noisy spheres, which "
           "recomputed steps keep round, stay recomputed. Tick it to freeze always.")));
    par.addParam(RichBool(kAcceptUnconverged, d.acceptUnconverged, tr("Accept unconverged solves"),
        tr("When a solve hits the iteration cap, keep its last iterate with a warning instead "
           "of solving it again directly or failing and leaving the mesh unchanged.")));
}

namespace {

Values readValues(const RichParameterList& par)
{
    Values v;
    v.timeStep = static_cast<double>(par.getFloat(kTimeStep));
    v.steps = par.getInt(kSteps);
    v.order = par.getEnum(kOrder);
    v.integration = par.getEnum(kIntegration);
    v.preserveVolume = par.getBool(kPreserveVolume);
    v.openInvariant = par.getEnum(kOpenInvariant);
    v.boundaryMode = par.getEnum(kBoundaryMode);
    v.qualityWeights = par.getBool(kQualityWeights);
    v.invertQuality = par.getBool(kInvertQuality);
    v.selected = par.getBool(kSelected);
    v.tolerance = static_cast<double>(par.getFloat(kTolerance));
    v.maxIterations = par.getInt(kMaxIterations);
    v.freezeOperator = par.getBool(kFreezeOperator);
    v.acceptUnconverged = par.getBool(kAcceptUnconverged);
    return v;
}

// Progress: only from the thread that called applyFilter, only when the percentage changes.
std::function<void(double)> progressTo(vcg::CallBackPos* cb, int& lastPercent)
{
    if (cb == nullptr) return nullptr;
    const std::thread::id caller = std::this_thread::get_id();
    return [cb, caller, &lastPercent](double f) {
        if (std::this_thread::get_id() != caller) return;
        const int p = std::max(0, std::min(100, static_cast<int>(f * 100.0)));
        if (p == lastPercent) return;
        lastPercent = p;
        cb(p, "Implicit fairing");
    };
}

int unconvergedSolves(const fairing::Result& r)
{
    return static_cast<int>(std::count_if(r.solves.begin(), r.solves.end(),
                                          [](const fairing::SolveReport& s) { return !s.converged; }));
}

// The run's figures, which pymeshlab returns as a dict. Warnings that change the result reach
// a non-verbose pymeshlab user only here (its log and stderr are silenced), and as numbers and
// flags: pymeshlab 2025.7's toPyDict drops strings.
fairing_plugin::RunFigures figuresOf(const fairing::Result& r, double seconds)
{
    fairing_plugin::RunFigures figures;
    figures.counts = {{"steps", r.steps},
                      {"iterations", r.total_iterations},
                      {"inner_iterations", r.total_inner_iterations},
                      {"vertices_moved", r.vertices_moved},
                      {"vertices_fixed", r.vertices_fixed},
                      {"warnings", static_cast<int>(r.warnings.size())},
                      {"unconverged_solves", unconvergedSolves(r)}};
    figures.values = {{"residual", r.max_residual},
                      {"volume_before", r.volume_before},
                      {"volume_after", r.volume_after},
                      {"lambda_dt", r.lambda_dt},
                      {"time_step", r.time_step},
                      {"boundary_time_step", r.boundary_time_step},
                      {"noise_level", r.noise_level},
                      {"noise_level_edges", r.noise_level_edges},
                      {"mean_edge_length", r.mean_edge_length},
                      {"strength_seconds", r.strength_seconds},
                      {"engine_seconds", r.seconds},
                      {"seconds", seconds}};
    figures.flags = {{"explicit_unstable", r.explicit_unstable},
                     {"automatic_time_step", r.automatic_time_step},
                     {"operator_frozen", r.operator_frozen}};
    return figures;
}

}  // namespace

fairing_plugin::RunFigures FilterImplicitFairing::apply(fairing_plugin::FilterId id, MeshModel& m,
                                                        const RichParameterList& par,
                                                        vcg::CallBackPos* cb)
{
    try {
        return run(id, m, par, cb);
    } catch (const fairing::Error& e) {
        throw std::runtime_error(render(e, fairing_plugin::kMessageHost));
    }
}

fairing_plugin::RunFigures FilterImplicitFairing::run(fairing_plugin::FilterId id, MeshModel& m,
                                                      const RichParameterList& par,
                                                      vcg::CallBackPos* cb)
{
    QElapsedTimer timer;
    timer.start();
    const Values v = readValues(par);
    fairing::Options o = toOptions(operatorOf(id), v);
    int lastPercent = -1;
    o.progress = progressTo(cb, lastPercent);

    vcg_adapters::ConstraintSettings cs;
    cs.onlySelected = v.selected;
    cs.qualityWeights = v.qualityWeights;
    cs.invertQuality = v.invertQuality;
    cs.qualityMeaningful = m.hasDataMask(MeshModel::MM_VERTQUALITY);

    // Everything that can fail runs before the mesh is written.
    vcg_adapters::IndexMap map;
    const fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m.cm, map);
    vcg_adapters::ConstraintReport crep;
    const fairing::Constraints constraints = vcg_adapters::makeConstraints(m.cm, map, cs, &crep);
    const fairing::Result r = fairing::fair(tm, constraints, o);
    vcg_adapters::writePositions(m.cm, map, r.positions);   // checks first, then writes
    updateBoxAndNormals(m);
    if (cb != nullptr) cb(100, "Implicit fairing done");

    const double seconds = timer.elapsed() / 1000.0;
    logRun(id, v, o, cs, crep, r, static_cast<long>(tm.positions.rows()), seconds);
    return figuresOf(r, seconds);
}

void FilterImplicitFairing::logRun(fairing_plugin::FilterId id, const Values& v,
                                   const fairing::Options& o,
                                   const vcg_adapters::ConstraintSettings& cs,
                                   const vcg_adapters::ConstraintReport& crep,
                                   const fairing::Result& r, long vertices, double seconds)
{
    logLine(QString("%1: %2 operator, %3, %4 integration")
                .arg(filterName(id))
                .arg(fairing::to_string(o.op))
                .arg(o.order == 2 ? QString::fromUtf8("L²") : QString("L"))
                .arg(QString::fromStdString(integrationLabels()[v.integration]).toLower()));
    logLine(QString("Vertices moved: %1 of %2; fixed: %3")
                .arg(r.vertices_moved).arg(vertices).arg(r.vertices_fixed));
    if (cs.onlySelected)
        logLine(QString("Affect only selection: %1 vertices free from the %2, %3 fixed")
                    .arg(crep.movable).arg(QString::fromStdString(crep.selectionSource))
                    .arg(crep.fixedBySelection));
    if (cs.qualityWeights)
        logLine(QString("Quality weights%1: %2 vertices with weight 0, %3 quality values "
                        "clamped to [0,1]")
                    .arg(cs.invertQuality ? " (inverted)" : "")
                    .arg(crep.zeroWeights).arg(crep.qualityClamped));
    logSolves(r);
    logComponents(o, r);
    logWarnings(r);
    logLine(QString("Time: %1 s in the engine, %2 s in total")
                .arg(num(r.seconds)).arg(num(seconds)));
}

void FilterImplicitFairing::logSolves(const fairing::Result& r)
{
    if (r.automatic_time_step)
        logLine(QString("Time step: automatic, %1 (estimated noise along the normals: %2 = %3 "
                        "mean edge lengths; chosen in %4 s, %5 Lanczos steps)")
                    .arg(num(r.time_step)).arg(num(r.noise_level)).arg(num(r.noise_level_edges))
                    .arg(num(r.strength_seconds)).arg(r.strength_iterations));
    else
        logLine(QString("Time step: %1 (given)").arg(num(r.time_step)));
    if (r.operator_compared)  // Options::freeze_when_better
        logLine(QString("Operator: %1 (estimated risk, squared error along the normals over the "
                        "noise's variance: %2 frozen, %3 recomputed)")
                    .arg(r.operator_frozen ? "the first step's for all steps, frozen"
                                           : "recomputed at each step")
                    .arg((r.frozen_risk_is_bound ? "at least " : "") + num(r.frozen_risk))
                    .arg(num(r.recomputed_risk)));
    else if (r.operator_frozen)
        logLine("Operator: the first step's for all steps (Freeze operator)");
    if (r.boundary_time_step > 0)
        logLine(QString("Boundary curve time step: %1 (%2)")
                    .arg(num(r.boundary_time_step))
                    .arg(r.automatic_time_step ? "automatic, chosen for the loops on their own"
                                               : "the given time step"));
    logLine(QString::fromUtf8("Steps: %1; absolute λdt per step: %2 (time step %3)")
                .arg(r.steps).arg(num(r.lambda_dt)).arg(num(r.time_step)));
    for (const fairing::SolveReport& s : r.solves) {
        if (s.frozen_steps > 0) {  // one report for all the steps (the engine's frozen_steps.h)
            logLine(QString("  steps 1-%1 at once (frozen operator), %2: %3 products with the "
                            "system (two Lanczos passes), estimated error %4")
                        .arg(s.frozen_steps).arg(QString::fromStdString(s.system))
                        .arg(s.iterations).arg(num(s.residual)));
            continue;
        }
        if (s.direct) {  // the loops, or a stalled surface solve (the engine's direct_solve.h)
            logLine(QString("  step %1, %2: solved directly (sparse LDL^T)%3, residual %4")
                        .arg(s.step).arg(QString::fromStdString(s.system))
                        .arg(s.iterations > 0 ? QString(" after %1 CG iterations stopped short")
                                                    .arg(s.iterations)
                                              : QString())
                        .arg(num(s.residual)));
            continue;
        }
        logLine(QString("  step %1, %2: %3 CG iterations%4, residual %5%6")
                    .arg(s.step).arg(QString::fromStdString(s.system)).arg(s.iterations)
                    .arg(s.factored ? QString(" (factored L² preconditioner: %1 inner "
                                              "first-order iterations)")
                                          .arg(s.inner_iterations)
                                    : QString())
                    .arg(num(s.residual)).arg(s.converged ? "" : " (NOT converged)"));
    }
    logLine(QString("CG iterations in total: %1; largest final residual: %2")
                .arg(r.total_iterations).arg(num(r.max_residual)));
}

void FilterImplicitFairing::logComponents(const fairing::Options& o, const fairing::Result& r)
{
    logLine(QString("Volume of closed components: before %1, after %2")
                .arg(num(r.volume_before)).arg(num(r.volume_after)));
    logLine(QString("Boundary: %1 (%2 boundary loops); volume preservation %3")
                .arg(fairing::to_string(o.boundary)).arg(r.boundary_loops)
                .arg(o.preserve_volume ? "on" : "off"));
    const std::size_t shown = std::min<std::size_t>(r.components.size(), 20);
    for (std::size_t i = 0; i < shown; ++i) {
        const fairing::ComponentReport& c = r.components[i];
        logLine(QString("  component %1: %2 faces, %3%4; %5; %6 %7 -> %8")
                    .arg(i).arg(c.faces).arg(c.closed ? "closed" : "open")
                    .arg(c.has_fixed ? ", has fixed vertices" : "")
                    .arg(fairing::to_string(c.restoration))
                    .arg(c.closed ? "volume" : "area")
                    .arg(num(c.measure_before)).arg(num(c.measure_after)));
    }
    if (r.components.size() > shown)
        logLine(QString("  ... and %1 more components").arg(r.components.size() - shown));
}

void FilterImplicitFairing::logWarnings(const fairing::Result& r)
{
    if (r.isolated_vertices > 0)
        logLine(QString("Warning: %1 isolated vertices left out").arg(r.isolated_vertices));
    if (r.zero_area_faces > 0)
        logLine(QString("Warning: %1 zero-area faces contribute nothing").arg(r.zero_area_faces));
    if (r.dropped_faces > 0)
        logLine(QString("Warning: %1 faces repeating a vertex left out").arg(r.dropped_faces));
    if (r.inconsistent_edges > 0)
        logLine(QString("Warning: %1 edges with inconsistent face orientation")
                    .arg(r.inconsistent_edges));
    for (const std::string& w : r.warnings)
        logLine(QString("Warning: %1").arg(QString::fromStdString(w)));
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterImplicitFairing)
