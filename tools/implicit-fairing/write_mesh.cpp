// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "write_mesh.h"

#include "common.h"

#include <wrap/io_trimesh/export_obj.h>
#include <wrap/io_trimesh/export_off.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/export_stl.h>

namespace implicit_fairing {

using Mask = vcg::tri::io::Mask;

int saveMask(Format out, const Loaded& in)
{
    int mask = Mask::IOM_VERTCOORD | Mask::IOM_FACEINDEX;
    const int had = in.mask;
    switch (out) {
    case Format::PLY:
        mask |= had & (Mask::IOM_VERTQUALITY | Mask::IOM_VERTCOLOR | Mask::IOM_VERTNORMAL |
                       Mask::IOM_FACECOLOR);
        break;
    case Format::OFF:
        mask |= had & (Mask::IOM_VERTCOLOR | Mask::IOM_FACECOLOR);
        break;
    case Format::OBJ:  // face colours would need a .mtl file named after the temporary file
        mask |= had & (Mask::IOM_VERTCOLOR | Mask::IOM_VERTNORMAL);
        break;
    default: break;
    }
    return mask;
}

namespace {

// Saves with one exporter; returns its error message, or nullptr on success.
template <class Exporter, class... Args>
const char* save(Args&&... args)
{
    const int err = Exporter::Save(std::forward<Args>(args)...);
    return err == 0 ? nullptr : Exporter::ErrorMsg(err);
}

}  // namespace

void writeMesh(CMesh& m, const std::string& path, Format f, int mask, bool ascii)
{
    using namespace vcg::tri::io;
    const char* file = path.c_str();
    const char* error = "unsupported format";
    switch (f) {
    case Format::PLY: error = save<ExporterPLY<CMesh>>(m, file, mask, !ascii); break;
    case Format::OBJ: error = save<ExporterOBJ<CMesh>>(m, file, mask); break;
    case Format::OFF: error = save<ExporterOFF<CMesh>>(m, file, mask); break;
    case Format::STL: error = save<ExporterSTL<CMesh>>(m, file, !ascii); break;
    default: break;
    }
    if (error != nullptr)
        throw Failure{std::string("cannot write ") + formatName(f) + ": " + error};
}

}  // namespace implicit_fairing
