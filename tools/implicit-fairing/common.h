// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// What every part of the command-line tool shares: its name in messages, the one exception a
// failed run throws, and the number format of the help text and the summary.
#pragma once

#include <cstdio>
#include <string>

namespace implicit_fairing {

constexpr const char* kTool = "implicit-fairing";

// A failed run: main() prints the message and exits with status 1, leaving OUT untouched.
struct Failure {
    std::string message;
};

inline std::string formatNumber(double x)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

}  // namespace implicit_fairing
