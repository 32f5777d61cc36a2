// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "options.h"

#include "common.h"

#include <CLI/CLI.hpp>

#include <climits>
#include <exception>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#ifndef IMPLICIT_FAIRING_VERSION
#define IMPLICIT_FAIRING_VERSION "unknown"
#endif

namespace implicit_fairing {
namespace {

using filter_parameters::Values;

const std::map<std::string, fairing::Operator>& operatorNames()
{
    static const std::map<std::string, fairing::Operator> m = {
        {"umbrella", fairing::Operator::Umbrella},
        {"scale-dependent", fairing::Operator::ScaleDependent},
        {"curvature", fairing::Operator::CurvatureFlow}};
    return m;
}

// Word-wraps text at width columns (CLI11 2.1 does not wrap; it indents after '\n').
std::string wrap(const std::string& text, std::size_t width)
{
    std::istringstream words(text);
    std::string word, out;
    std::size_t column = 0;
    while (words >> word) {
        if (column > 0 && column + 1 + word.size() > width) {
            out += '\n';
            column = 0;
        } else if (column > 0) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
    }
    return out;
}

// An option whose value is one of a few names.
void addChoice(CLI::App& app, const std::string& option, std::string& value,
               const std::string& help, const std::vector<std::string>& names,
               const char* typeName)
{
    app.add_option(option, value, help)->check(CLI::IsMember(names))->type_name(typeName);
}

void addFiles(CLI::App& app, CommandLine& cl)
{
    app.add_option("IN", cl.in,
                   "Input mesh: .ply .obj .off .stl (by extension, any case). Polygons are "
                   "triangulated; duplicate vertices of STL input are merged (STL stores every "
                   "triangle separately).")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("OUT", cl.out,
                   "Output mesh: .ply .obj .off .stl. Written only after success, through a "
                   "temporary file in the same folder renamed over OUT (on failure an existing "
                   "OUT is left untouched). May equal IN. Keeps what the input had and the format "
                   "holds: PLY vertex quality, colours, normals (recomputed).")
        ->required();
}

// The options that mirror a filter parameter: its .mlx name in brackets.
void addFilterParameters(CLI::App& app, CommandLine& cl, const Values& d)
{
    addChoice(app, "--operator", cl.operatorName,
              "umbrella (eq. 7, uniform weights), scale-dependent (eq. 11, Fujiwara's 1/|edge| "
              "weights) or curvature (eq. 14, the cotangent curvature flow). Default: curvature",
              {"umbrella", "scale-dependent", "curvature"}, "NAME");
    app.add_option_function<std::string>(
           "--time-step",
           [&cl](const std::string& t) {
               cl.timeStepGiven = t != "auto";
               if (cl.timeStepGiven) cl.timeStep = std::stod(t);
           },
           "[timeStep] auto (or 0): chosen from the mesh, by the noise it estimates along the "
           "normals (Stein's unbiased risk estimate; --json reports time_step and "
           "noise_level; a scan's finest detail counts as noise too, so clean or barely noisy "
           "detailed scans come out smoother than needed: give T there). Or a dimensionless "
           "time step T > 0: lambda*dt = T * (mean edge)^(2*order) for scale-dependent and "
           "curvature, T for umbrella and --normalized "
           "(with L^2, 10, 2.5 and 22.5 remove noise of about one edge length). Default: auto")
        ->type_name("auto|T")
        ->check(CLI::Validator(
            [](std::string& t) -> std::string {
                if (t == "auto") return std::string();
                std::size_t used = 0;
                try {
                    std::stod(t, &used);
                } catch (const std::exception&) {
                    used = 0;
                }
                return used == t.size() && used > 0 ? std::string()
                                                    : "expected 'auto' or a number, got '" + t + "'";
            },
            ""));
    app.add_option_function<int>(
           "--steps",
           [&cl](int n) {
               cl.stepsGiven = true;
               cl.steps = n;
           },
           "[stepSmoothNum] Number of time steps, each of the whole time step. Default: the "
           "filter's: " +
               std::to_string(filter_parameters::defaultSteps(fairing::Operator::Umbrella)) +
               " (umbrella), " +
               std::to_string(filter_parameters::defaultSteps(fairing::Operator::ScaleDependent)) +
               " (scale-dependent), " +
               std::to_string(filter_parameters::defaultSteps(fairing::Operator::CurvatureFlow)) +
               " (curvature)")
        ->type_name("N");
    app.add_option("--order", cl.order,
                   "[order] 1: diffusion with L; 2: with L^2 (section 2.6, recommended); 3, 4: "
                   "with L^3, L^4 (Figure 3a: closer to a low-pass filter). Default: " +
                       std::to_string(d.order + 1))
        ->check(CLI::IsMember({1, 2, 3, 4}))
        ->type_name("1|2|3|4");
    app.add_flag("--explicit", cl.explicitIntegration,
                 "[integration=Explicit] Forward Euler (eq. 8) instead of the implicit backward "
                 "Euler (eq. 9); stable only for small time steps (a warning says when not). "
                 "Default: implicit");
    app.add_flag("--normalized", cl.normalized,
                 "[integration=Explicit, normalized operator] Explicit integration with the "
                 "normalized operator of section 5.5 (time step dimensionless, stable up to 1); "
                 "implies --explicit. Default: off");
    app.add_flag("--no-volume", cl.noVolume,
                 "[preserveVolume=false] Do not restore the volume of closed components after "
                 "each step (sections 3.1-3.2). Default: volume preserved");
    addChoice(app, "--volume-restoration", cl.volumeRestoration,
              "How the volume is restored: offset (every free vertex moves one distance along "
              "its normal, the smallest correction; a loss above 10 % is scaled, or with the "
              "automatic time step, except for several first-order or curvature flow steps, "
              "as the estimate modelled the chosen step; what the filters do) or scale "
              "(section 3.2: about the centroid). Default: offset",
              {"offset", "scale"}, "HOW");
    app.add_flag("--keep-drift", cl.keepDrift,
                 "Curvature flow: do not translate closed components back by the least-squares "
                 "translation of their displacement along the normals (the paper's flow as is: "
                 "strong steps on unevenly sampled noisy meshes drift). Default: translated back");
    app.add_flag("--uniform-offset", cl.uniformOffset,
                 "Curvature flow, --volume-restoration offset: every free vertex moves the same "
                 "distance along its normal, instead of a distance shaped like the input's "
                 "smoothed mean curvature (the volume goes back where the flow took it; uniform "
                 "anyway where noise explains most of that curvature's variation, as on a "
                 "sphere). Default: shaped");
    app.add_flag("--area", cl.area,
                 "[openInvariant=Area] Restore the surface area of open components (which "
                 "enclose no volume) after each step. Default: open components are not restored");
    addChoice(app, "--boundary", cl.boundary,
              "[boundaryMode] fixed (boundary vertices stay), curve (section 5.3: boundary loops "
              "smoothed as curves first; with the automatic time step the loops get their own, "
              "reported as boundary_time_step), virtual (a hidden vertex at each loop's "
              "barycentre) or auto (curve with the automatic time step, fixed with a given "
              "one). Default: auto",
              {"fixed", "curve", "virtual", "auto"}, "MODE");
    auto* weights = app.add_flag("--weights-from-quality", cl.qualityWeights,
                                 "[qualityWeights] Per-vertex quality (PLY 'quality' property) as "
                                 "smoothing weight (section 2.7), clamped to [0, 1]; 0 = the "
                                 "vertex stays bit-identical. Default: off");
    app.add_flag("--invert-weights", cl.invertWeights,
                 "[invertQuality] Weight = 1 - clamped quality. Needs --weights-from-quality. "
                 "Default: off")
        ->needs(weights);
    auto* freeze = app.add_flag(
        "--freeze", cl.freeze,
        "[freezeOperator] Keep the first step's coefficients for all steps (section 4.3). "
        "Default: recomputed at each step, except that with the automatic time step the "
        "curvature flow's and the scale-dependent operator's several steps are frozen where the "
        "estimated error of frozen steps is the lower (scans: over the denoising study's 120 "
        "scan cases the curvature flow's one-click error fell by 11 %, the scale-dependent "
        "filter's by 4 %; spheres keep the recomputed steps). The JSON report's "
        "operator_frozen says which ran");
    app.add_flag("--recompute", cl.recompute,
                 "Recompute the coefficients at each step also with the automatic time step "
                 "(the paper's flow). Default: off, frozen where the estimated error is the "
                 "lower (see --freeze)")
        ->excludes(freeze);
    app.add_option("--tolerance", cl.tolerance,
                   "[tolerance] Conjugate-gradient stopping rule: ||A X - b|| < E ||b|| for x, y "
                   "and z (> 0). Default: " + formatNumber(d.tolerance))
        ->type_name("E");
    app.add_option("--max-iterations", cl.maxIterations,
                   "[maxIterations] Conjugate-gradient iteration cap per solve (>= 1). A solve that "
                   "stops short of the tolerance (at the cap, or stalled by needle triangles) on "
                   "a mesh of up to 100,000 free vertices (L or L^2; L^3 50,000, L^4 25,000) is "
                   "solved again directly (sparse LDL^T). Default: " +
                       std::to_string(d.maxIterations))
        ->type_name("N");
    app.add_flag("--accept-unconverged", cl.acceptUnconverged,
                 "[acceptUnconverged] When the iteration cap is hit, keep the last iterate with "
                 "a warning instead of solving it again directly or failing. Default: fail");
}

// The options only the tool has.
void addToolOptions(CLI::App& app, CommandLine& cl)
{
    addChoice(app, "--preconditioner", cl.preconditioner,
              "auto, jacobi, factored or multigrid. factored (order 2 only) preconditions the "
              "L^2 system with two first-order solves per iteration: its cost grows as the 4th "
              "root of the time step instead of the square root. multigrid uses a smoothed-"
              "aggregation V-cycle, whose iterations barely grow with the time step (first order, "
              "and L^2 without vertex weights). auto solves an L^2 step without vertex weights as "
              "one complex first-order solve, Re (M + i sqrt(dt) K)^-1 b (preconditioned by "
              "symmetric Gauss-Seidel, the umbrella by its complex diagonal); with weights it "
              "starts with jacobi and switches when the solve turns out heavy; on meshes of 50,000 "
              "vertices or more it takes multigrid for strong steps. Default: auto",
              {"auto", "jacobi", "factored", "multigrid"}, "NAME");
    app.add_option("--threads", cl.threads,
                   "Threads for the solver on meshes of 50,000 vertices or more (smaller ones "
                   "always use one): 0 = all cores (or OMP_NUM_THREADS). Default: 0")
        ->check(CLI::Range(0, INT_MAX))
        ->type_name("N");
    app.add_flag("--json", cl.json,
                 "Print one line of JSON on stdout (and nothing else there): vertices, faces, "
                 "operator, steps, lambda_dt (absolute), cg_iterations, residual, volume_before, "
                 "volume_after, seconds_engine (assembly + solve), seconds_total, and more. "
                 "Default: a one-line summary");
    app.add_flag("--ascii", cl.ascii, "Write PLY and STL as ASCII. Default: binary");
    app.add_flag("-q,--quiet", cl.quiet,
                 "No progress bar, summary or warnings (errors are still reported; --json still "
                 "prints). Default: off");
}

}  // namespace

int parseCommandLine(int argc, char** argv, CommandLine& cl)
{
    const Values d = filter_parameters::defaults(fairing::Operator::CurvatureFlow);
    cl.order = d.order + 1;
    cl.tolerance = d.tolerance;
    cl.maxIterations = d.maxIterations;
    cl.threads = fairing::Options().threads;

    CLI::App app{"Implicit fairing (Desbrun, Meyer, Schroeder, Barr, SIGGRAPH 1999) of a "
                 "triangle mesh: reads IN, smooths it, writes OUT. The options mirror the MeshLab "
                 "filters \"Implicit Fairing: Umbrella Diffusion / Scale-Dependent Diffusion / "
                 "Curvature Flow\" (their parameter names in brackets) and mean the same.",
                 kTool};
    app.set_version_flag("--version", std::string(kTool) + " " + IMPLICIT_FAIRING_VERSION);
    app.get_formatter()->column_width(34);
    addFiles(app, cl);
    addFilterParameters(app, cl, d);
    addToolOptions(app, cl);
    for (CLI::Option* o : app.get_options()) o->description(wrap(o->get_description(), 64));
    app.description(wrap(app.get_description(), 98));
    app.footer(wrap("Coordinates are read into floats, as in MeshLab, so a run gives the "
                    "positions the MeshLab filter gives. vcglib writes OBJ with 6 decimals and "
                    "OFF with 7 significant digits; PLY and STL keep floats exactly. A progress "
                    "bar is drawn on stderr when it is a terminal. Exit status: 0 on success, 1 "
                    "when the run fails, 2 for a usage error; OUT is written only on success.",
                    98));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "%s: %s\nRun '%s --help' for the options.\n", kTool, e.what(),
                     kTool);
        return 2;
    }
    return -1;
}

fairing::Operator operatorOf(const CommandLine& cl) { return operatorNames().at(cl.operatorName); }

Values filterValues(const CommandLine& cl)
{
    Values v = filter_parameters::defaults(operatorOf(cl));
    if (cl.timeStepGiven) v.timeStep = cl.timeStep;
    if (cl.stepsGiven) v.steps = cl.steps;
    v.order = cl.order - 1;
    v.integration = cl.normalized ? 2 : cl.explicitIntegration ? 1 : 0;
    v.preserveVolume = !cl.noVolume;
    v.volumeRestoration = cl.volumeRestoration == "scale" ? fairing::VolumeRestoration::Scale
                                                          : fairing::VolumeRestoration::NormalOffset;
    v.cancelDrift = !cl.keepDrift;
    v.shapedOffset = !cl.uniformOffset;
    v.openInvariant = cl.area ? 1 : 0;
    v.boundaryMode = cl.boundary == "curve"     ? 1
                     : cl.boundary == "virtual" ? 2
                     : cl.boundary == "auto"    ? filter_parameters::kAutomaticBoundary
                                                : 0;
    v.qualityWeights = cl.qualityWeights;
    v.invertQuality = cl.invertWeights;
    v.selected = false;
    v.tolerance = cl.tolerance;
    v.maxIterations = cl.maxIterations;
    v.freezeOperator = cl.freeze;
    v.freezeWhenBetter = !cl.recompute;
    v.acceptUnconverged = cl.acceptUnconverged;
    return v;
}

fairing::Options engineOptions(const CommandLine& cl, const Values& v)
{
    fairing::Options options = filter_parameters::toOptions(operatorOf(cl), v);
    options.threads = cl.threads;
    options.preconditioner = cl.preconditioner == "jacobi"      ? fairing::Preconditioner::Jacobi
                             : cl.preconditioner == "factored"  ? fairing::Preconditioner::Factored
                             : cl.preconditioner == "multigrid" ? fairing::Preconditioner::Multigrid
                                                                : fairing::Preconditioner::Automatic;
    return options;
}

}  // namespace implicit_fairing
