// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The command line: every option, its help text and default, and its translation into the
// filters' parameter values (filter_parameters::Values, so an option means exactly what the
// MeshLab filter's parameter of the same name means) and then into engine options.
#pragma once

#include <fairing/fairing.h>
#include <fairing_parameters/filter_parameters.h>

#include <string>

namespace implicit_fairing {

struct CommandLine {
    std::string in, out;
    std::string operatorName = "curvature";  // umbrella | scale-dependent | curvature
    bool timeStepGiven = false;              // otherwise automatic (--time-step auto)
    double timeStep = 0;
    bool stepsGiven = false;                 // otherwise the filter's default number of steps
    int steps = 0;
    int order = 2;                           // 1 | 2
    bool explicitIntegration = false, normalized = false;
    bool noVolume = false, area = false;
    std::string boundary = "auto";           // fixed | curve | virtual | auto
    std::string volumeRestoration = "offset";  // offset | scale
    bool keepDrift = false;
    bool uniformOffset = false;
    bool qualityWeights = false, invertWeights = false;
    bool freeze = false, recompute = false;
    double tolerance = 0;
    int maxIterations = 0;
    bool acceptUnconverged = false;
    std::string preconditioner = "auto";     // auto | jacobi | factored | multigrid
    int threads = 0;
    bool json = false, ascii = false, quiet = false;
};

// Parses argv into cl (defaults: the filters'). Returns -1 when the run should go on, otherwise
// the exit status to return now: 0 after --help or --version, 2 after a usage error (printed).
int parseCommandLine(int argc, char** argv, CommandLine& cl);

fairing::Operator operatorOf(const CommandLine& cl);

// The filters' parameter values this command line sets (no selection: the tool has none).
filter_parameters::Values filterValues(const CommandLine& cl);

// filter_parameters::toOptions of those values, plus what only the tool sets (threads,
// preconditioner). Throws fairing::Error naming a value out of range.
fairing::Options engineOptions(const CommandLine& cl, const filter_parameters::Values& v);

}  // namespace implicit_fairing
