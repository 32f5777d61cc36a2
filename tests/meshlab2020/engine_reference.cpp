// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Reference for the MeshLab 2020.09 and 2025.07 integration tests: runs the engine directly on a
// PLY file, through the same vcg adapters but without MeshLab, Qt or the plugin's parameter
// handling.
//
//   engine_reference IN.ply OUT.ply umbrella|scale_dependent|curvature_flow
//                    [--select-x-gt V] [name=value ...]
//
// name=value are the plugin's parameter names (the same list the test writes into the .mlx);
// floats are parsed as float first, as MeshLab 2020.09 stores them and pymeshlab converts them.
// --select-x-gt V selects the vertices with x > V before running (what the stock "Conditional
// Vertex Selection" with "x > V" does).
// The mesh type mirrors CMeshO where it matters: coordinates, per-vertex quality and flags of
// MeshLab's scalar, float by default; built with ENGINE_REFERENCE_DOUBLE it mirrors the CMeshO of
// a double-precision MeshLab (MESHLAB_SCALAR=double, as pymeshlab is built).
#include <fairing/fairing.h>
#include <fairing_parameters/filter_parameters.h>
#include <vcg_adapters/vcg_adapters.h>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>

namespace {

class RVertex;
class RFace;
struct RUsedTypes : public vcg::UsedTypes<vcg::Use<RVertex>::AsVertexType,
                                          vcg::Use<RFace>::AsFaceType> {};
// R(Coord3) is vcg's Coord3f, or Coord3d with ENGINE_REFERENCE_DOUBLE.
#if defined(ENGINE_REFERENCE_DOUBLE)
#define R(component) component##d
#else
#define R(component) component##f
#endif
class RVertex : public vcg::Vertex<RUsedTypes, vcg::vertex::R(Coord3), vcg::vertex::R(Normal3),
                                   vcg::vertex::R(Quality), vcg::vertex::BitFlags> {};
class RFace : public vcg::Face<RUsedTypes, vcg::face::VertexRef, vcg::face::R(Normal3),
                               vcg::face::BitFlags> {};
#undef R
using RScalar = RVertex::ScalarType;
class RMesh : public vcg::tri::TriMesh<std::vector<RVertex>, std::vector<RFace>> {};

[[noreturn]] void usage(const char* msg)
{
    std::fprintf(stderr, "engine_reference: %s\n", msg);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 4) usage("usage: IN.ply OUT.ply OPERATOR [--select-x-gt V] [name=value ...]");
    const std::string in = argv[1], out = argv[2], opName = argv[3];

    fairing::Operator op;
    if (opName == "umbrella") op = fairing::Operator::Umbrella;
    else if (opName == "scale_dependent") op = fairing::Operator::ScaleDependent;
    else if (opName == "curvature_flow") op = fairing::Operator::CurvatureFlow;
    else usage("unknown operator");

    // Parameters as MeshLab stores them: floats as float, enums as indices.
    using namespace filter_parameters;
    Values v = defaults(op);
    bool select = false;
    RScalar selectX = 0;
    for (int i = 4; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--select-x-gt" && i + 1 < argc) {
            select = true;
            selectX = static_cast<RScalar>(std::stod(argv[++i]));
            continue;
        }
        const auto eq = a.find('=');
        if (eq == std::string::npos) usage(("bad argument " + a).c_str());
        const std::string name = a.substr(0, eq), value = a.substr(eq + 1);
        const auto flt = [&] { return static_cast<double>(std::stof(value)); };
        const auto boolean = [&] { return value == "true"; };
        if (name == kTimeStep) v.timeStep = flt();
        else if (name == kSteps) v.steps = std::stoi(value);
        else if (name == kOrder) v.order = std::stoi(value);
        else if (name == kIntegration) v.integration = std::stoi(value);
        else if (name == kPreserveVolume) v.preserveVolume = boolean();
        else if (name == kOpenInvariant) v.openInvariant = std::stoi(value);
        else if (name == kBoundaryMode) v.boundaryMode = std::stoi(value);
        else if (name == kQualityWeights) v.qualityWeights = boolean();
        else if (name == kInvertQuality) v.invertQuality = boolean();
        else if (name == kSelected) v.selected = boolean();
        else if (name == kTolerance) v.tolerance = flt();
        else if (name == kMaxIterations) v.maxIterations = std::stoi(value);
        else if (name == kFreezeOperator) v.freezeOperator = boolean();
        else if (name == kAcceptUnconverged) v.acceptUnconverged = boolean();
        else usage(("unknown parameter " + name).c_str());
    }

    RMesh m;
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<RMesh>::Open(m, in.c_str(), mask) != 0)
        usage(("cannot read " + in).c_str());
    if (select)
        for (auto& v : m.vert)
            if (!v.IsD() && v.P()[0] > selectX) v.SetS();

    vcg_adapters::ConstraintSettings cs;
    cs.onlySelected = v.selected;
    cs.qualityWeights = v.qualityWeights;
    cs.invertQuality = v.invertQuality;
    cs.qualityMeaningful = (mask & vcg::tri::io::Mask::IOM_VERTQUALITY) != 0;
    try {
        vcg_adapters::IndexMap map;
        const fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m, map);
        const fairing::Constraints c = vcg_adapters::makeConstraints(m, map, cs);
        const fairing::Result r = fairing::fair(tm, c, toOptions(op, v));
        vcg_adapters::writePositions(m, map, r.positions);
        vcg_adapters::updateNormalsAndBox(m);
        std::printf("engine_reference: %d vertices moved, %d fixed, %d CG iterations, "
                    "lambda_dt %g\n", r.vertices_moved, r.vertices_fixed, r.total_iterations,
                    r.lambda_dt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "engine_reference: %s\n", e.what());
        return 1;
    }
    if (vcg::tri::io::ExporterPLY<RMesh>::Save(m, out.c_str(), vcg::tri::io::Mask::IOM_VERTCOORD,
                                               true) != 0)
        usage(("cannot write " + out).c_str());
    return 0;
}
