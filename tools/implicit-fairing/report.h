// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// What the tool prints after a successful run on stdout: one line of JSON (--json) or a
// one-line summary.
#pragma once

#include "options.h"
#include "read_mesh.h"

#include <fairing/fairing.h>

#include <string>

namespace implicit_fairing {

struct RunFacts {
    const CommandLine& cl;
    const fairing::Options& options;
    const fairing::Result& result;
    const Loaded& loaded;
    long vertices;          // live vertices given to the engine
    long faces;
    double secondsTotal;    // from start-up to the written file
};

// One line of JSON: every figure of the run, warnings as an array of strings; non-finite
// numbers as null.
std::string jsonReport(const RunFacts& f);

// "implicit-fairing: OUT: 642 vertices (642 moved), 1280 faces; curvature, order 2, ..."
std::string summaryLine(const RunFacts& f);

}  // namespace implicit_fairing
