// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The filters' parameters, host-neutral: their internal names (what .mlx scripts and, lower-
// cased, pymeshlab use), enum labels, defaults, and the one translation into fairing::Options.
// The MeshLab plugin, the tests' reference tools and the command-line tool all go through here,
// so a parameter means the same thing everywhere. No Qt, no vcg.
#pragma once

#include <fairing/fairing.h>

#include <string>
#include <vector>

namespace filter_parameters {

// Internal names. Never "lambda" (pymeshlab would turn it into "lambda_").
constexpr const char* kTimeStep = "timeStep";
constexpr const char* kSteps = "stepSmoothNum";
constexpr const char* kOrder = "order";
constexpr const char* kIntegration = "integration";
constexpr const char* kPreserveVolume = "preserveVolume";
constexpr const char* kOpenInvariant = "openInvariant";
constexpr const char* kBoundaryMode = "boundaryMode";
constexpr const char* kQualityWeights = "qualityWeights";
constexpr const char* kInvertQuality = "invertQuality";
constexpr const char* kSelected = "Selected";
constexpr const char* kTolerance = "tolerance";
constexpr const char* kMaxIterations = "maxIterations";
constexpr const char* kFreezeOperator = "freezeOperator";
constexpr const char* kAcceptUnconverged = "acceptUnconverged";

// Enum labels, in index order. Plain ASCII, because pymeshlab users type them: pymeshlab
// matches a string argument to a label exactly (QStringList::indexOf) and also takes the index.
// .mlx scripts store the index, so a label may change its words but never its position: the
// second order was labelled "L\xc2\xb2 (second order, recommended)" until 0.1.0, and scripts
// saved then still run.
inline const std::vector<std::string>& orderLabels() {
    static const std::vector<std::string> v = {"L (first order)", "L2 (second order)",
                                               "L3 (third order)", "L4 (fourth order)"};
    return v;
}
inline const std::vector<std::string>& integrationLabels() {
    static const std::vector<std::string> v = {"Implicit", "Explicit",
                                               "Explicit, normalized operator (section 5.5)"};
    return v;
}
inline const std::vector<std::string>& openInvariantLabels() {
    static const std::vector<std::string> v = {"None", "Area"};
    return v;
}
inline const std::vector<std::string>& boundaryModeLabels() {
    static const std::vector<std::string> v = {"Fixed", "Smooth boundary curve", "Virtual vertex",
                                               "Automatic"};
    return v;
}
// The default boundary: the loops smoothed as curves with their own automatic time step when the
// time step is automatic (a fixed boundary keeps their noise: smoothed, the one-click error is
// 0.54-0.98 of the fixed boundary's on libcgal-demo's blade and mech-holes-shark, auto-gap.md
// section 30), and fixed with an explicit time step, which so does exactly what it did before
// the automatic strength. Last, so that scripts saved before it keep their indices.
constexpr int kAutomaticBoundary = 3;

// The time step's default: 0 = automatic (the engine chooses it from the mesh, issue 11;
// fairing::Options::time_step left empty). 0 was a no-op before the automatic strength existed;
// any other value is passed on as is, so scripts with an explicit time step run exactly as before.
constexpr double kAutomaticTimeStep = 0.0;

// Reference strengths for an explicit time step: with L^2 the three operators damp a mode of
// wavelength k (in edges) by 1/(1 + t c (2 pi / k)^4) on a regular mesh, c = 1/16 (umbrella),
// 1/4 (scale-dependent), 1/36 (curvature flow); these steps give all three the same filter, which
// removes noise of wavelength up to about four edges and keeps features over about sixteen.
inline double referenceTimeStep(fairing::Operator op) {
    switch (op) {
    case fairing::Operator::Umbrella: return 10.0;
    case fairing::Operator::ScaleDependent: return 2.5;
    case fairing::Operator::CurvatureFlow: return 22.5;
    }
    return 10.0;
}

// Parameter values as a host reads them (enums as indices).
struct Values {
    double timeStep = kAutomaticTimeStep;
    int steps = 1;
    int order = 1;        // index into orderLabels(): L^2
    int integration = 0;  // index into integrationLabels()
    bool preserveVolume = true;
    // Not a filter parameter: MeshLab 2020.09's meshlabserver asserts that a script lists every
    // parameter of the filter, so a new one would break every saved script. The filters use the
    // engine's default (the normal offset); the command-line tool and the engine offer both.
    // cancelDrift and shapedOffset likewise (Options::cancel_drift, Options::shaped_offset).
    fairing::VolumeRestoration volumeRestoration = fairing::VolumeRestoration::NormalOffset;
    bool cancelDrift = fairing::Options().cancel_drift;
    bool shapedOffset = fairing::Options().shaped_offset;
    int openInvariant = 0;
    int boundaryMode = kAutomaticBoundary;
    bool qualityWeights = false;
    bool invertQuality = false;
    bool selected = false;
    double tolerance = fairing::Options().tolerance;
    int maxIterations = fairing::Options().max_iterations;
    bool freezeOperator = false;
    // Not a filter parameter either (see volumeRestoration): with freezeOperator off and the
    // automatic time step, the engine freezes where its risk estimate says so
    // (Options::freeze_when_better); the command-line tool's --recompute turns that off.
    bool freezeWhenBetter = fairing::Options().freeze_when_better;
    bool acceptUnconverged = false;
};

// One-click settings per filter: L^2, the automatic strength, and the number of steps that gave
// the lowest error over scans and shapes with a known surface in bench/denoise (issue 11;
// figures in bench/results/denoise.md): the curvature flow with 4 steps, the scale-dependent
// umbrella with 2 (it degrades with more steps on scans), the umbrella with 8: its steps share
// one operator and run as one matrix function, so 8 cost what 4 do, and their sharper filter
// gave lower automatic errors on scans (bench/results/issue11/auto-gap.md, section 38).
inline int defaultSteps(fairing::Operator op) {
    switch (op) {
    case fairing::Operator::Umbrella: return 8;
    case fairing::Operator::ScaleDependent: return 2;
    default: return 4;
    }
}

inline Values defaults(fairing::Operator op) {
    Values v;
    v.steps = defaultSteps(op);
    return v;
}

// Throws fairing::Error naming the parameter when a value is out of its range.
inline fairing::Options toOptions(fairing::Operator op, const Values& v) {
    auto index = [](int i, const std::vector<std::string>& labels, const char* name) {
        if (i < 0 || i >= static_cast<int>(labels.size()))
            throw fairing::Error(std::string("parameter ") + name + ": index " +
                                 std::to_string(i) + " is out of range");
        return i;
    };
    fairing::Options o;
    o.op = op;
    if (v.timeStep != kAutomaticTimeStep) o.time_step = v.timeStep;
    o.steps = v.steps;
    o.order = index(v.order, orderLabels(), kOrder) + 1;
    const int integration = index(v.integration, integrationLabels(), kIntegration);
    o.integration = integration == 0 ? fairing::Integration::Implicit
                                     : fairing::Integration::Explicit;
    o.normalized = integration == 2;
    o.preserve_volume = v.preserveVolume;
    o.restoration = v.volumeRestoration;
    o.cancel_drift = v.cancelDrift;
    o.shaped_offset = v.shapedOffset;
    o.open_invariant = index(v.openInvariant, openInvariantLabels(), kOpenInvariant) == 1
                           ? fairing::OpenInvariant::Area
                           : fairing::OpenInvariant::None;
    switch (index(v.boundaryMode, boundaryModeLabels(), kBoundaryMode)) {
    case 1: o.boundary = fairing::BoundaryMode::SmoothCurve; break;
    case 2: o.boundary = fairing::BoundaryMode::VirtualVertex; break;
    case kAutomaticBoundary:
        o.boundary = o.time_step.has_value() ? fairing::BoundaryMode::Fixed
                                             : fairing::BoundaryMode::SmoothCurve;
        break;
    default: o.boundary = fairing::BoundaryMode::Fixed; break;
    }
    o.tolerance = v.tolerance;
    o.max_iterations = v.maxIterations;
    o.freeze_operator = v.freezeOperator;
    o.freeze_when_better = v.freezeWhenBetter;
    o.accept_unconverged = v.acceptUnconverged;
    return o;
}

}  // namespace filter_parameters
