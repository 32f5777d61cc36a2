// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Writing the result with vcglib's exporters.
#pragma once

#include "formats.h"
#include "mesh.h"
#include "read_mesh.h"

#include <string>

namespace implicit_fairing {

// What the output gets: positions and faces always; what the input had and the format can hold
// (a vcg::tri::io::Mask).
int saveMask(Format out, const Loaded& in);

// Writes m to path in format f; ascii: PLY and STL as text. Throws Failure.
void writeMesh(CMesh& m, const std::string& path, Format f, int mask, bool ascii);

}  // namespace implicit_fairing
