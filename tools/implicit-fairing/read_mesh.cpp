// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "read_mesh.h"

#include "common.h"

#include <vcg/complex/algorithms/clean.h>
#include <wrap/io_trimesh/import.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace implicit_fairing {
namespace {

// vcglib 2025.07's OBJ importer (import_obj.h, GoodObjIndex) compares the 0-based index with the
// number of vertices read so far using '>', so one index too many passes: with three vertices,
// "f 1 2 4" at the end of the file makes a face point one past the vertex array (and "f 0 ..."
// is read as that same index instead of being refused). Such a face is refused here, before
// anything dereferences it. (The importer of 2020.09 refused index 1, the first vertex, instead:
// it dropped every face using it, which is why this tool no longer builds on that vcglib.)
void requireFaceVerticesInside(const CMesh& m, const std::string& path)
{
    const CVertex* const first = m.vert.data();
    const CVertex* const end = first + m.vert.size();
    for (std::size_t f = 0; f < m.face.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const CVertex* v = m.face[f].cV(k);
            if (v < first || v >= end)
                throw Failure{"cannot read " + path + ": face " + std::to_string(f + 1) +
                              " refers to a vertex the file does not have (" +
                              std::to_string(m.vert.size()) + " vertices)"};
        }
}

// STL stores every triangle with its own three corners: without merging, the surface would be
// a soup of separate triangles (each with a fixed boundary: nothing would move). Exact
// duplicates are merged, as MeshLab does on STL import.
void mergeStlCorners(CMesh& m, Loaded& info)
{
    const int facesBefore = m.fn;
    info.merged = vcg::tri::Clean<CMesh>::RemoveDuplicateVertex(m);
    vcg::tri::Clean<CMesh>::RemoveUnreferencedVertex(m);
    info.degenerate = facesBefore - m.fn;
}

}  // namespace

Loaded readMesh(CMesh& m, const std::string& path)
{
    Loaded info;
    info.format = requireFormat(path, "input");
    {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw Failure{"cannot read " + path + ": " + std::strerror(errno)};
        std::fclose(f);
    }
    using Importer = vcg::tri::io::Importer<CMesh>;
    const int err = Importer::Open(m, path.c_str(), info.mask);
    if (err != 0 && Importer::ErrorCritical(err))
        throw Failure{"cannot read " + path + " as " + formatName(info.format) + ": " +
                      Importer::ErrorMsg(err)};
    if (info.format == Format::OBJ) requireFaceVerticesInside(m, path);
    info.fileVertices = m.vn;
    if (info.format == Format::STL) mergeStlCorners(m, info);
    vcg::tri::Allocator<CMesh>::CompactEveryVector(m);
    if (m.fn == 0)
        throw Failure{path + " has no faces (" + std::to_string(m.vn) +
                      " vertices): implicit fairing needs a triangle mesh"};
    return info;
}

}  // namespace implicit_fairing
