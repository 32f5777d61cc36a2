// implicit-fairing: the engine on a mesh file, from the command line (issue 5).
//
//   implicit-fairing IN OUT [options]        implicit-fairing --help lists every option
//
// Reads and writes PLY, OBJ, OFF and STL through vcglib's importers and exporters (the vcglib of
// MeshLab 2020.09), runs fairing::fair() through vcg_adapters, and translates its options through
// filter_parameters::Values / toOptions, so that a setting means exactly what the MeshLab filter
// of the same name does (the filters' parameters are named in the --help text).
//
// The mesh type mirrors MeshLab's CMeshO where it matters (float coordinates, per-vertex quality
// and flags), so a run gives the positions the filter gives in MeshLab.
//
// Failure (bad options, unreadable input, refusal by the engine, unwritable output) prints one
// message on stderr and exits non-zero; OUT is only ever replaced by a complete file: the result
// is written to a temporary file next to OUT and renamed over it.
#include <fairing/fairing.h>
#include <filter_parameters.h>
#include <vcg_adapters/vcg_adapters.h>

#include <vcg/complex/algorithms/clean.h>
#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export_obj.h>
#include <wrap/io_trimesh/export_off.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/export_stl.h>
#include <wrap/io_trimesh/import.h>  // PLY, OFF, STL (OBJ: readObj below)

#include <CLI/CLI.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#ifndef IMPLICIT_FAIRING_VERSION
#define IMPLICIT_FAIRING_VERSION "unknown"
#endif

namespace {

class CVertex;
class CFace;
struct CUsedTypes : public vcg::UsedTypes<vcg::Use<CVertex>::AsVertexType,
                                          vcg::Use<CFace>::AsFaceType> {};
class CVertex : public vcg::Vertex<CUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                   vcg::vertex::Color4b, vcg::vertex::Qualityf,
                                   vcg::vertex::BitFlags> {};
class CFace : public vcg::Face<CUsedTypes, vcg::face::VertexRef, vcg::face::Normal3f,
                               vcg::face::Color4b, vcg::face::BitFlags> {};
class CMesh : public vcg::tri::TriMesh<std::vector<CVertex>, std::vector<CFace>> {};

using Mask = vcg::tri::io::Mask;

const char* const kTool = "implicit-fairing";

struct Failure {
    std::string message;
};

// ---------------------------------------------------------------------------------------------
// formats

enum class Format { Unknown, PLY, OBJ, OFF, STL };

std::string lowerExtension(const std::string& path)
{
    const auto slash = path.find_last_of('/');
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Format formatOf(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == "ply") return Format::PLY;
    if (ext == "obj") return Format::OBJ;
    if (ext == "off") return Format::OFF;
    if (ext == "stl") return Format::STL;
    return Format::Unknown;
}

Format requireFormat(const std::string& path, const char* role)
{
    const Format f = formatOf(path);
    if (f == Format::Unknown) {
        const std::string ext = lowerExtension(path);
        throw Failure{std::string(role) + " " + path + ": " +
                      (ext.empty() ? std::string("no file extension")
                                   : "unsupported file extension '." + ext + "'") +
                      "; supported: .ply .obj .off .stl"};
    }
    return f;
}

const char* formatName(Format f)
{
    switch (f) {
    case Format::PLY: return "PLY";
    case Format::OBJ: return "OBJ";
    case Format::OFF: return "OFF";
    case Format::STL: return "STL";
    default: return "?";
    }
}

// ---------------------------------------------------------------------------------------------
// the temporary output: a private folder created next to OUT before the work starts (so an
// unwritable folder fails early), holding a file with OUT's own name (the OBJ exporter writes
// the name into the file). After success the file is renamed over OUT; on failure, SIGINT,
// SIGTERM or SIGHUP the file and the folder are removed.

char g_tempFile[PATH_MAX + 64] = {0};
char g_tempDir[PATH_MAX + 64] = {0};

extern "C" void removeTempAndReraise(int sig)
{
    if (g_tempFile[0]) unlink(g_tempFile);
    if (g_tempDir[0]) rmdir(g_tempDir);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

class TempFile {
public:
    explicit TempFile(const std::string& out) : out_(out)
    {
        const auto slash = out.find_last_of('/');
        const std::string dir = slash == std::string::npos ? "" : out.substr(0, slash + 1);
        const std::string base = slash == std::string::npos ? out : out.substr(slash + 1);
        if (base.empty()) throw Failure{"output " + out + ": no file name"};
        std::string templ = dir + "." + base + ".tmp-XXXXXX";
        if (templ.size() + base.size() + 2 >= sizeof(g_tempFile))
            throw Failure{"output path too long: " + out};
        std::vector<char> buf(templ.begin(), templ.end());
        buf.push_back('\0');
        if (!mkdtemp(buf.data()))
            throw Failure{"cannot create a file in " + (dir.empty() ? std::string(".") : dir) +
                          " (for " + out + "): " + std::strerror(errno)};
        dir_ = buf.data();
        path_ = dir_ + "/" + base;
        std::memcpy(g_tempDir, dir_.c_str(), dir_.size() + 1);
        std::memcpy(g_tempFile, path_.c_str(), path_.size() + 1);
        std::signal(SIGINT, removeTempAndReraise);
        std::signal(SIGTERM, removeTempAndReraise);
        std::signal(SIGHUP, removeTempAndReraise);
    }
    ~TempFile()
    {
        if (!path_.empty()) unlink(path_.c_str());
        if (!dir_.empty()) rmdir(dir_.c_str());
        g_tempFile[0] = g_tempDir[0] = '\0';
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const std::string& path() const { return path_; }

    void commit()
    {
        struct stat st;
        if (stat(out_.c_str(), &st) == 0) chmod(path_.c_str(), st.st_mode & 07777);
        if (std::rename(path_.c_str(), out_.c_str()) != 0)
            throw Failure{"cannot rename " + path_ + " to " + out_ + ": " + std::strerror(errno)};
        path_.clear();
        g_tempFile[0] = '\0';
    }

private:
    std::string out_, dir_, path_;
};

// ---------------------------------------------------------------------------------------------
// reading and writing

struct Loaded {
    Format format = Format::Unknown;
    int mask = 0;           // what vcglib loaded (Mask::IOM_*)
    int fileVertices = 0;   // before merging (STL)
    int merged = 0;         // duplicate vertices merged (STL)
    int degenerate = 0;     // faces removed by the merge (STL)
};

// vcglib 2020.09's ImporterOBJ drops, without a word, every face that uses the file's first
// vertex: its GoodObjIndex() rejects index 0 after the index has been made 0-based (vcglib commit
// feea7d6, August 2020, which MeshLab 2020.09 ships). So OBJ is read here, as that importer
// reads it otherwise: "v x y z [w]" or "v x y z r g b" (colours in [0, 1]); "f" with v, v/vt,
// v//vn or v/vt/vn, negative (relative) indices, polygons fan-triangulated. Texture
// coordinates, groups and materials are ignored. Throws Failure with the line on bad input.
int readObj(CMesh& m, const std::string& path)
{
    std::ifstream file(path);
    if (!file) throw Failure{"cannot read " + path + ": " + std::strerror(errno)};
    std::vector<vcg::Point3f> positions;
    std::vector<vcg::Color4b> colors;
    bool colored = true, texcoords = false, normals = false;
    struct Corner { long index; long line; };
    std::vector<std::array<Corner, 3>> triangles;
    std::string line;
    long lineNo = 0;
    auto bad = [&](const std::string& what) {
        return Failure{path + ":" + std::to_string(lineNo) + ": " + what};
    };
    while (std::getline(file, line)) {
        ++lineNo;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key)) continue;
        if (key == "v") {
            std::vector<double> x;
            std::string word;
            while (ls >> word) {
                char* end = nullptr;
                const double value = std::strtod(word.c_str(), &end);
                if (end == word.c_str() || *end != '\0') throw bad("bad number '" + word + "'");
                x.push_back(value);
            }
            if (x.size() < 3) throw bad("a vertex needs 3 coordinates");
            positions.emplace_back(static_cast<float>(x[0]), static_cast<float>(x[1]),
                                   static_cast<float>(x[2]));
            if (x.size() == 6) {
                auto c = [&](double v) {
                    return static_cast<unsigned char>(std::lround(std::min(1.0, std::max(0.0, v)) * 255));
                };
                colors.emplace_back(c(x[3]), c(x[4]), c(x[5]), 255);
            } else {
                colored = false;
            }
        } else if (key == "vt") {
            texcoords = true;
        } else if (key == "vn") {
            normals = true;
        } else if (key == "f") {
            std::vector<Corner> corners;
            std::string token;
            while (ls >> token) {
                char* end = nullptr;
                const long i = std::strtol(token.c_str(), &end, 10);
                if (end == token.c_str() || (*end != '\0' && *end != '/'))
                    throw bad("bad face corner '" + token + "'");
                if (i == 0) throw bad("face index 0 (OBJ indices start at 1)");
                // negative: relative to the vertices read so far; positive: 1-based
                const long index = i < 0 ? static_cast<long>(positions.size()) + i : i - 1;
                if (index < 0) throw bad("face index " + std::to_string(i) + " before the first vertex");
                corners.push_back({index, lineNo});
            }
            if (corners.size() < 3) throw bad("a face needs at least 3 vertices");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k)
                triangles.push_back({corners[0], corners[k], corners[k + 1]});
        }
    }
    if (file.bad()) throw Failure{"cannot read " + path + ": " + std::strerror(errno)};
    for (const auto& t : triangles)
        for (const Corner& c : t)
            if (c.index >= static_cast<long>(positions.size()))
                throw Failure{path + ":" + std::to_string(c.line) + ": face index " +
                              std::to_string(c.index + 1) + " but only " +
                              std::to_string(positions.size()) + " vertices"};
    colored = colored && !positions.empty();

    auto vi = vcg::tri::Allocator<CMesh>::AddVertices(m, positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i, ++vi) {
        vi->P() = positions[i];
        if (colored) vi->C() = colors[i];
    }
    auto fi = vcg::tri::Allocator<CMesh>::AddFaces(m, triangles.size());
    for (std::size_t f = 0; f < triangles.size(); ++f, ++fi)
        for (int k = 0; k < 3; ++k)
            fi->V(k) = &m.vert[static_cast<std::size_t>(triangles[f][static_cast<std::size_t>(k)].index)];
    int mask = Mask::IOM_VERTCOORD | Mask::IOM_FACEINDEX;
    if (colored) mask |= Mask::IOM_VERTCOLOR;
    if (normals) mask |= Mask::IOM_VERTNORMAL;
    if (texcoords) mask |= Mask::IOM_WEDGTEXCOORD;
    return mask;
}

Loaded readMesh(CMesh& m, const std::string& path)
{
    Loaded info;
    info.format = requireFormat(path, "input");
    {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throw Failure{"cannot read " + path + ": " + std::strerror(errno)};
        std::fclose(f);
    }
    if (info.format == Format::OBJ) {
        info.mask = readObj(m, path);
    } else {
        using Importer = vcg::tri::io::Importer<CMesh>;
        int mask = 0;
        const int err = Importer::Open(m, path.c_str(), mask);
        if (err != 0 && Importer::ErrorCritical(err))
            throw Failure{"cannot read " + path + " as " + formatName(info.format) + ": " +
                          Importer::ErrorMsg(err)};
        info.mask = mask;
    }
    info.fileVertices = m.vn;
    if (info.format == Format::STL) {
        // STL stores every triangle with its own three corners: without merging, the surface
        // would be a soup of separate triangles (each with a fixed boundary: nothing would
        // move). Exact duplicates are merged, as MeshLab does on STL import.
        const int facesBefore = m.fn;
        info.merged = vcg::tri::Clean<CMesh>::RemoveDuplicateVertex(m);
        vcg::tri::Clean<CMesh>::RemoveUnreferencedVertex(m);
        info.degenerate = facesBefore - m.fn;
    }
    vcg::tri::Allocator<CMesh>::CompactEveryVector(m);
    if (m.fn == 0)
        throw Failure{path + " has no faces (" + std::to_string(m.vn) +
                      " vertices): implicit fairing needs a triangle mesh"};
    return info;
}

// What the output gets: positions and faces always; what the input had and the format can hold.
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

void writeMesh(CMesh& m, const std::string& path, Format f, int mask, bool ascii)
{
    int err = 0;
    const char* msg = "";
    switch (f) {
    case Format::PLY:
        err = vcg::tri::io::ExporterPLY<CMesh>::Save(m, path.c_str(), mask, !ascii);
        if (err) msg = vcg::tri::io::ExporterPLY<CMesh>::ErrorMsg(err);
        break;
    case Format::OBJ:
        err = vcg::tri::io::ExporterOBJ<CMesh>::Save(m, path.c_str(), mask);
        if (err) msg = vcg::tri::io::ExporterOBJ<CMesh>::ErrorMsg(err);
        break;
    case Format::OFF:
        err = vcg::tri::io::ExporterOFF<CMesh>::Save(m, path.c_str(), mask);
        if (err) msg = vcg::tri::io::ExporterOFF<CMesh>::ErrorMsg(err);
        break;
    case Format::STL:
        err = vcg::tri::io::ExporterSTL<CMesh>::Save(m, path.c_str(), !ascii);
        if (err) msg = vcg::tri::io::ExporterSTL<CMesh>::ErrorMsg(err);
        break;
    default: err = 1; msg = "unsupported format"; break;
    }
    if (err != 0) throw Failure{std::string("cannot write ") + formatName(f) + ": " + msg};
}

// ---------------------------------------------------------------------------------------------
// output helpers

std::string jsonNumber(double x)
{
    if (!std::isfinite(x)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string jsonString(const std::string& s)
{
    std::string out = "\"";
    for (const unsigned char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        case '\r': out += "\\r"; break;
        default:
            if (c < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", c);
                out += buf;
            } else {
                out += static_cast<char>(c);
            }
        }
    }
    return out + "\"";
}

class ProgressBar {
public:
    explicit ProgressBar(bool enabled) : enabled_(enabled) {}
    ~ProgressBar() { clear(); }
    void update(double fraction)
    {
        if (!enabled_) return;
        fraction = std::min(1.0, std::max(0.0, fraction));
        const int percent = static_cast<int>(fraction * 100 + 0.5);
        if (drawn_ && percent == percent_) return;  // redraw only when the number changes
        percent_ = percent;
        const int width = 30, filled = static_cast<int>(fraction * width + 0.5);
        std::fprintf(stderr, "\r%s [%s%s] %3d%%", kTool, std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(),
                     percent);
        std::fflush(stderr);
        drawn_ = true;
    }
    void clear()
    {
        if (enabled_ && drawn_) {
            std::fprintf(stderr, "\r\033[K");
            std::fflush(stderr);
        }
        drawn_ = false;
    }

private:
    bool enabled_;
    bool drawn_ = false;
    int percent_ = -1;
};

const std::map<std::string, fairing::Operator>& operatorNames()
{
    static const std::map<std::string, fairing::Operator> m = {
        {"umbrella", fairing::Operator::Umbrella},
        {"scale-dependent", fairing::Operator::ScaleDependent},
        {"curvature", fairing::Operator::CurvatureFlow}};
    return m;
}

// Word-wraps text at width columns (CLI11 2.1 does not wrap; it indents after '\n').
std::string wrap(const std::string& text, std::size_t width)
{
    std::istringstream words(text);
    std::string word, out;
    std::size_t column = 0;
    while (words >> word) {
        if (column > 0 && column + 1 + word.size() > width) {
            out += '\n';
            column = 0;
        } else if (column > 0) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
    }
    return out;
}

std::string fmt(double x)
{
    char buf[40];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

}  // namespace

int main(int argc, char** argv)
{
    const auto t0 = std::chrono::steady_clock::now();
    using filter_parameters::Values;
    const Values d = filter_parameters::defaults(fairing::Operator::CurvatureFlow);

    std::string in, out;
    std::string opName = "curvature", boundaryName = "fixed", preconditionerName = "auto";
    double timeStep = 0;
    int steps = d.steps, order = d.order + 1, maxIterations = d.maxIterations,
        threads = fairing::Options().threads;
    double tolerance = d.tolerance;
    bool explicitIntegration = false, normalized = false, noVolume = false, area = false;
    bool qualityWeights = false, invertWeights = false, freeze = false, acceptUnconverged = false;
    bool json = false, ascii = false, quiet = false;

    CLI::App app{"Implicit fairing (Desbrun, Meyer, Schroeder, Barr, SIGGRAPH 1999) of a "
                 "triangle mesh: reads IN, smooths it, writes OUT. The options mirror the MeshLab "
                 "filters \"Implicit Fairing: Umbrella Diffusion / Scale-Dependent Diffusion / "
                 "Curvature Flow\" (their parameter names in brackets) and mean the same.",
                 kTool};
    app.set_version_flag("--version", std::string(kTool) + " " + IMPLICIT_FAIRING_VERSION);
    app.get_formatter()->column_width(34);

    app.add_option("IN", in,
                   "Input mesh: .ply .obj .off .stl (by extension, any case). Polygons are "
                   "triangulated; duplicate vertices of STL input are merged (STL stores every "
                   "triangle separately).")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("OUT", out,
                   "Output mesh: .ply .obj .off .stl. Written only after success, through a "
                   "temporary file in the same folder renamed over OUT (on failure an existing "
                   "OUT is left untouched). May equal IN. Keeps what the input had and the format "
                   "holds: PLY vertex quality, colours, normals (recomputed).")
        ->required();

    std::ostringstream tsDefaults;
    tsDefaults << "Default: " << fmt(filter_parameters::defaultTimeStep(fairing::Operator::Umbrella))
               << " umbrella, "
               << fmt(filter_parameters::defaultTimeStep(fairing::Operator::ScaleDependent))
               << " scale-dependent, "
               << fmt(filter_parameters::defaultTimeStep(fairing::Operator::CurvatureFlow))
               << " curvature";

    auto* opOpt = app.add_option("--operator", opName,
                                 "umbrella (eq. 7, uniform weights), scale-dependent (eq. 11, "
                                 "Fujiwara's 1/|edge| weights) or curvature (eq. 14, the "
                                 "cotangent curvature flow). Default: curvature")
                      ->check(CLI::IsMember({"umbrella", "scale-dependent", "curvature"}));
    opOpt->type_name("NAME");
    auto* tsOpt = app.add_option("--time-step", timeStep,
                                 "[timeStep] Dimensionless time step (>= 0): lambda*dt = T * "
                                 "(mean edge)^(2*order) for scale-dependent and curvature, T for "
                                 "umbrella and --normalized. " + tsDefaults.str() +
                                     " (the filters' defaults)")
                      ->type_name("T");
    app.add_option("--steps", steps,
                   "[stepSmoothNum] Number of time steps. Default: " + std::to_string(d.steps))
        ->type_name("N");
    app.add_option("--order", order,
                   "[order] 1: diffusion with L; 2: with L^2 (section 2.6, recommended). "
                   "Default: " + std::to_string(d.order + 1))
        ->check(CLI::IsMember({1, 2}))
        ->type_name("1|2");
    app.add_flag("--explicit", explicitIntegration,
                 "[integration=Explicit] Forward Euler (eq. 8) instead of the implicit backward "
                 "Euler (eq. 9); stable only for small time steps (a warning says when not). "
                 "Default: implicit");
    app.add_flag("--normalized", normalized,
                 "[integration=Explicit, normalized operator] Explicit integration with the "
                 "normalized operator of section 5.5 (time step dimensionless, stable up to 1); "
                 "implies --explicit. Default: off");
    app.add_flag("--no-volume", noVolume,
                 "[preserveVolume=false] Do not restore the volume of closed components after "
                 "each step (sections 3.1-3.2). Default: volume preserved");
    app.add_flag("--area", area,
                 "[openInvariant=Area] Restore the surface area of open components (which "
                 "enclose no volume) after each step. Default: open components are not restored");
    app.add_option("--boundary", boundaryName,
                   "[boundaryMode] fixed (boundary vertices stay), curve (section 5.3: boundary "
                   "loops smoothed as curves first) or virtual (a hidden vertex at each loop's "
                   "barycentre). Default: fixed")
        ->check(CLI::IsMember({"fixed", "curve", "virtual"}))
        ->type_name("MODE");
    auto* qwOpt = app.add_flag("--weights-from-quality", qualityWeights,
                               "[qualityWeights] Per-vertex quality (PLY 'quality' property) as "
                               "smoothing weight (section 2.7), clamped to [0, 1]; 0 = the vertex "
                               "stays bit-identical. Default: off");
    app.add_flag("--invert-weights", invertWeights,
                 "[invertQuality] Weight = 1 - clamped quality. Needs --weights-from-quality. "
                 "Default: off")
        ->needs(qwOpt);
    app.add_flag("--freeze", freeze,
                 "[freezeOperator] Keep the first step's coefficients for all steps (section "
                 "4.3). Default: recomputed at each step");
    app.add_option("--tolerance", tolerance,
                   "[tolerance] Conjugate-gradient stopping rule: ||A X - b|| < E ||b|| for x, y "
                   "and z (> 0). Default: " + fmt(d.tolerance))
        ->type_name("E");
    app.add_option("--max-iterations", maxIterations,
                   "[maxIterations] Conjugate-gradient iteration cap per solve (>= 1). Default: " +
                       std::to_string(d.maxIterations))
        ->type_name("N");
    app.add_flag("--accept-unconverged", acceptUnconverged,
                 "[acceptUnconverged] When the iteration cap is hit, keep the last iterate with a "
                 "warning instead of failing. Default: fail");
    app.add_option("--preconditioner", preconditionerName,
                   "auto, jacobi or factored. factored (order 2 only) preconditions the L^2 system "
                   "with two first-order solves per iteration: its cost grows as the 4th root of "
                   "the time step instead of the square root. auto solves an L^2 step without "
                   "vertex weights as one complex first-order solve, Re (M + i sqrt(dt) K)^-1 b; "
                   "with weights it starts with jacobi and switches when the solve turns out "
                   "heavy. Default: auto")
        ->check(CLI::IsMember({"auto", "jacobi", "factored"}))
        ->type_name("NAME");
    app.add_option("--threads", threads,
                   "Threads for the solver on meshes of 50,000 vertices or more (smaller ones "
                   "always use one): 0 = all cores (or OMP_NUM_THREADS). Default: 0")
        ->check(CLI::Range(0, INT_MAX))
        ->type_name("N");
    app.add_flag("--json", json,
                 "Print one line of JSON on stdout (and nothing else there): vertices, faces, "
                 "operator, steps, lambda_dt (absolute), cg_iterations, residual, volume_before, "
                 "volume_after, seconds_engine (assembly + solve), seconds_total, and more. "
                 "Default: a one-line summary");
    app.add_flag("--ascii", ascii, "Write PLY and STL as ASCII. Default: binary");
    app.add_flag("-q,--quiet", quiet,
                 "No progress bar, summary or warnings (errors are still reported; --json still "
                 "prints). Default: off");
    for (CLI::Option* o : app.get_options()) o->description(wrap(o->get_description(), 64));
    app.description(wrap(app.get_description(), 98));
    app.footer(wrap("Coordinates are read into floats, as in MeshLab, so a run gives the "
                    "positions the MeshLab filter gives. vcglib writes OBJ with 6 decimals and "
                    "OFF with 7 significant digits; PLY and STL keep floats exactly. A progress "
                    "bar is drawn on stderr when it is a terminal. Exit status: 0 on success, 1 "
                    "when the run fails, 2 for a usage error; OUT is written only on success.",
                    98));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s\nRun '%s --help' for the options.\n", kTool, e.what(),
                     kTool);
        return 2;
    }

    const bool interactive = !quiet && isatty(STDERR_FILENO);
    auto warn = [&](const std::string& msg) {
        if (!quiet) std::fprintf(stderr, "%s: warning: %s\n", kTool, msg.c_str());
    };

    try {
        const fairing::Operator op = operatorNames().at(opName);
        const Format outFormat = requireFormat(out, "output");
        requireFormat(in, "input");

        // The filters' parameters, then the one translation into engine options.
        Values v = filter_parameters::defaults(op);
        if (!tsOpt->empty()) v.timeStep = timeStep;
        v.steps = steps;
        v.order = order - 1;
        v.integration = normalized ? 2 : explicitIntegration ? 1 : 0;
        v.preserveVolume = !noVolume;
        v.openInvariant = area ? 1 : 0;
        v.boundaryMode = boundaryName == "curve" ? 1 : boundaryName == "virtual" ? 2 : 0;
        v.qualityWeights = qualityWeights;
        v.invertQuality = invertWeights;
        v.selected = false;
        v.tolerance = tolerance;
        v.maxIterations = maxIterations;
        v.freezeOperator = freeze;
        v.acceptUnconverged = acceptUnconverged;
        fairing::Options options = filter_parameters::toOptions(op, v);
        options.threads = threads;
        options.preconditioner = preconditionerName == "jacobi" ? fairing::Preconditioner::Jacobi
                                 : preconditionerName == "factored"
                                     ? fairing::Preconditioner::Factored
                                     : fairing::Preconditioner::Automatic;

        TempFile temp(out);  // fails now, not after the work, when OUT's folder is unwritable

        CMesh m;
        const Loaded loaded = readMesh(m, in);
        if (loaded.merged > 0 && !quiet && !json)
            std::fprintf(stderr, "%s: STL: merged %d duplicate vertices (%d -> %d)%s\n", kTool,
                         loaded.merged, loaded.fileVertices, m.vn,
                         loaded.degenerate > 0
                             ? (", removed " + std::to_string(loaded.degenerate) +
                                " degenerate faces").c_str()
                             : "");

        vcg_adapters::ConstraintSettings cs;
        cs.onlySelected = false;
        cs.qualityWeights = v.qualityWeights;
        cs.invertQuality = v.invertQuality;
        cs.qualityMeaningful = (loaded.mask & Mask::IOM_VERTQUALITY) != 0;
        if (cs.qualityWeights && !cs.qualityMeaningful)
            throw Failure{"--weights-from-quality: " + in + " has no per-vertex quality (a PLY "
                          "vertex property 'quality' is needed)"};

        vcg_adapters::IndexMap map;
        const fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m, map);
        vcg_adapters::ConstraintReport crep;
        const fairing::Constraints c = vcg_adapters::makeConstraints(m, map, cs, &crep);

        ProgressBar bar(interactive);
        options.progress = [&bar](double f) { bar.update(f); };
        bar.update(0);
        fairing::Result r;
        try {
            r = fairing::fair(tm, c, options);
        } catch (...) {
            bar.clear();
            throw;
        }
        bar.clear();

        vcg_adapters::writePositions(m, map, r.positions);
        vcg_adapters::updateNormalsAndBox(m);
        vcg::tri::UpdateNormal<CMesh>::NormalizePerVertex(m);  // unit normals in the file

        const int mask = saveMask(outFormat, loaded);
        writeMesh(m, temp.path(), outFormat, mask, ascii);
        temp.commit();

        for (const auto& w : r.warnings) warn(w);
        if (crep.qualityClamped > 0)
            warn(std::to_string(crep.qualityClamped) +
                 " quality values outside [0, 1] were clamped");
        if ((loaded.mask & Mask::IOM_VERTQUALITY) && !(mask & Mask::IOM_VERTQUALITY))
            warn(std::string("vertex quality is not written to ") + formatName(outFormat));
        if ((loaded.mask & (Mask::IOM_VERTTEXCOORD | Mask::IOM_WEDGTEXCOORD)))
            warn("texture coordinates are not written");

        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const bool closed = r.volume_before != 0;
        if (json) {
            std::ostringstream j;
            j << "{\"vertices\":" << tm.positions.rows() << ",\"faces\":" << tm.triangles.size()
              << ",\"operator\":" << jsonString(opName) << ",\"order\":" << options.order
              << ",\"integration\":"
              << jsonString(options.integration == fairing::Integration::Implicit
                                ? "implicit"
                                : options.normalized ? "explicit-normalized" : "explicit")
              << ",\"boundary\":" << jsonString(boundaryName)
              << ",\"steps\":" << r.steps << ",\"time_step\":" << jsonNumber(options.time_step)
              << ",\"lambda_dt\":" << jsonNumber(r.lambda_dt)
              << ",\"cg_iterations\":" << r.total_iterations
              << ",\"inner_iterations\":" << r.total_inner_iterations
              << ",\"residual\":" << jsonNumber(r.max_residual)
              << ",\"volume_before\":" << jsonNumber(r.volume_before)
              << ",\"volume_after\":" << jsonNumber(r.volume_after)
              << ",\"vertices_moved\":" << r.vertices_moved
              << ",\"vertices_fixed\":" << r.vertices_fixed
              << ",\"merged_vertices\":" << loaded.merged
              << ",\"components\":" << r.components.size()
              << ",\"boundary_loops\":" << r.boundary_loops
              << ",\"seconds_engine\":" << jsonNumber(r.seconds)
              << ",\"seconds_total\":" << jsonNumber(seconds) << ",\"warnings\":[";
            for (std::size_t i = 0; i < r.warnings.size(); ++i)
                j << (i ? "," : "") << jsonString(r.warnings[i]);
            j << "]}";
            std::printf("%s\n", j.str().c_str());
        } else if (!quiet) {
            std::printf("%s: %s: %ld vertices (%d moved), %zu faces; %s, order %d, %d step%s, "
                        "lambda_dt %g; %d CG iterations, residual %.3g; %s%.6g s (engine %.6g s)"
                        "\n",
                        kTool, out.c_str(), static_cast<long>(tm.positions.rows()),
                        r.vertices_moved, tm.triangles.size(), opName.c_str(), options.order,
                        r.steps, r.steps == 1 ? "" : "s", r.lambda_dt, r.total_iterations,
                        r.max_residual,
                        closed ? ("volume " + fmt(r.volume_before) + " -> " +
                                  fmt(r.volume_after) + "; ").c_str()
                               : "",
                        seconds, r.seconds);
        }
        return 0;
    } catch (const Failure& e) {
        std::fprintf(stderr, "%s: error: %s\n", kTool, e.message.c_str());
    } catch (const fairing::Error& e) {
        std::fprintf(stderr, "%s: error: %s\n", kTool, e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", kTool, e.what());
    }
    std::fprintf(stderr, "%s: %s was not written\n", kTool, out.c_str());
    return 1;
}
