// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// implicit-fairing: the engine on a mesh file, from the command line.
//
//   implicit-fairing IN OUT [options]        implicit-fairing --help lists every option
//
// The parts, one file each: the command line and its translation into the filters' parameters
// (options), the vcg mesh type (mesh.h), reading (read_mesh) and writing (write_mesh) through
// vcglib, the output written through a temporary file (temp_file), the progress bar
// (progress_bar) and the JSON or text report (report). This file runs them in order:
// read -> vcg_adapters -> fairing::fair() -> vcg_adapters -> write.
//
// Failure (bad options, unreadable input, refusal by the engine, unwritable output) prints one
// message on stderr and exits non-zero; OUT is only ever replaced by a complete file.
#include "common.h"
#include "mesh.h"
#include "options.h"
#include "progress_bar.h"
#include "read_mesh.h"
#include "report.h"
#include "temp_file.h"
#include "write_mesh.h"

#include <fairing/fairing.h>
#include <fairing_parameters/filter_parameters.h>
#include <fairing_parameters/repair_hints.h>
#include <vcg_adapters/vcg_adapters.h>
#include <wrap/io_trimesh/io_mask.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

namespace implicit_fairing {
namespace {

using Mask = vcg::tri::io::Mask;
using Clock = std::chrono::steady_clock;

class Warnings {
public:
    explicit Warnings(bool quiet) : quiet_(quiet) {}
    void operator()(const std::string& msg) const
    {
        if (!quiet_) std::fprintf(stderr, "%s: warning: %s\n", kTool, msg.c_str());
    }

private:
    bool quiet_;
};

// The engine on m's live elements, with the progress bar on a terminal; m is not changed.
fairing::Result fairMesh(const CMesh& m, const CommandLine& cl, const Loaded& loaded,
                         const filter_parameters::Values& v, fairing::Options options,
                         vcg_adapters::IndexMap& map, vcg_adapters::ConstraintReport& crep)
{
    vcg_adapters::ConstraintSettings cs;
    cs.onlySelected = false;
    cs.qualityWeights = v.qualityWeights;
    cs.invertQuality = v.invertQuality;
    cs.qualityMeaningful = (loaded.mask & Mask::IOM_VERTQUALITY) != 0;
    if (cs.qualityWeights && !cs.qualityMeaningful)
        throw Failure{"--weights-from-quality: " + cl.in + " has no per-vertex quality (a PLY "
                      "vertex property 'quality' is needed)"};
    const fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m, map);
    const fairing::Constraints c = vcg_adapters::makeConstraints(m, map, cs, &crep);

    ProgressBar bar(!cl.quiet && isatty(STDERR_FILENO));
    options.progress = [&bar](double f) { bar.update(f); };
    bar.update(0);
    return fairing::fair(tm, c, options);  // the bar is erased when it goes out of scope
}

void warnAboutOutput(const Warnings& warn, const Loaded& loaded, Format out, int mask)
{
    if ((loaded.mask & Mask::IOM_VERTQUALITY) && !(mask & Mask::IOM_VERTQUALITY))
        warn(std::string("vertex quality is not written to ") + formatName(out));
    if (loaded.mask & (Mask::IOM_VERTTEXCOORD | Mask::IOM_WEDGTEXCOORD))
        warn("texture coordinates are not written");
}

int run(const CommandLine& cl, Clock::time_point start)
{
    const Warnings warn(cl.quiet);
    const filter_parameters::Values v = filterValues(cl);
    const fairing::Options options = engineOptions(cl, v);
    const Format outFormat = requireFormat(cl.out, "output");
    TempFile temp(cl.out);  // fails now, not after the work, when OUT's folder is unwritable

    CMesh m;
    const Loaded loaded = readMesh(m, cl.in);
    if (loaded.merged > 0 && !cl.quiet && !cl.json)
        std::fprintf(stderr, "%s: STL: merged %d duplicate vertices (%d -> %d), removed %d "
                     "degenerate faces\n", kTool, loaded.merged, loaded.fileVertices, m.vn,
                     loaded.degenerate);

    vcg_adapters::IndexMap map;
    vcg_adapters::ConstraintReport crep;
    const fairing::Result r = fairMesh(m, cl, loaded, v, options, map, crep);
    vcg_adapters::writePositions(m, map, r.positions);
    vcg_adapters::updateNormalsAndBox(m);
    vcg::tri::UpdateNormal<CMesh>::NormalizePerVertex(m);  // unit normals in the file
    const int mask = saveMask(outFormat, loaded);
    writeMesh(m, temp.path(), outFormat, mask, cl.ascii);
    temp.commit();

    for (const auto& w : r.warnings) warn(w);
    if (crep.qualityClamped > 0)
        warn(std::to_string(crep.qualityClamped) + " quality values outside [0, 1] were clamped");
    warnAboutOutput(warn, loaded, outFormat, mask);

    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const RunFacts facts{cl, options, r, loaded, static_cast<long>(map.rowToVertex.size()),
                         static_cast<long>(map.liveFaces), seconds};
    if (cl.json)
        std::printf("%s\n", jsonReport(facts).c_str());
    else if (!cl.quiet)
        std::printf("%s\n", summaryLine(facts).c_str());
    return 0;
}

}  // namespace
}  // namespace implicit_fairing

int main(int argc, char** argv)
{
    using namespace implicit_fairing;
    const auto start = Clock::now();
    CommandLine cl;
    const int status = parseCommandLine(argc, argv, cl);
    if (status >= 0) return status;
    try {
        return run(cl, start);
    } catch (const Failure& e) {
        std::fprintf(stderr, "%s: error: %s\n", kTool, e.message.c_str());
    } catch (const fairing::Error& e) {
        const std::string message = filter_parameters::render(e, filter_parameters::Host::CommandLine);
        std::fprintf(stderr, "%s: error: %s\n", kTool, message.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", kTool, e.what());
    }
    std::fprintf(stderr, "%s: %s was not written\n", kTool, cl.out.c_str());
    return 1;
}
