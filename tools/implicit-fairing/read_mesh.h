// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Reading a mesh file with vcglib's importers (the vcglib of MeshLab 2025.07, so a file reads
// as MeshLab 2025.07 reads it).
#pragma once

#include "formats.h"
#include "mesh.h"

#include <string>

namespace implicit_fairing {

struct Loaded {
    Format format = Format::Unknown;
    int mask = 0;           // what vcglib loaded (vcg::tri::io::Mask::IOM_*)
    int fileVertices = 0;   // before merging (STL)
    int merged = 0;         // duplicate vertices merged (STL)
    int degenerate = 0;     // faces removed by the merge (STL)
};

// Reads path into the empty mesh m (compacted, at least one face); throws Failure.
Loaded readMesh(CMesh& m, const std::string& path);

}  // namespace implicit_fairing
