// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// fairing-denoise-tool: meshes, noise, errors and our filters' time-step sweep for the
// denoising study (bench/denoise.sh, issue 11). Error convention: common/denoise_shapes.h.
//
//   make sphere2 LEVEL OUT.ply         unit sphere, two sampling densities, irregular
//   make plane N OUT.ply               flat irregular N x N patch in z = 0
//   make torus FACES OUT.ply           jittered torus R = 1, r = 0.4
//   noise IN OUT.ply SIGMA_EDGES SEED normal|iso
//                                      Gaussian noise, sigma in mean edges of IN, along the
//                                      area-weighted normals or per axis in all directions
//   info IN                            JSON: vertices, faces, mean_edge, volume, closed
//   eval CLEAN TRUTH INPUT RESULT...   one JSON line per RESULT: rms, max (in CLEAN's mean
//                                      edges), volume_change (percent, vs INPUT)
//   sweep INPUT CLEAN TRUTH OP ORDER STEPS X0 [--ts T1,T2,...] [--auto|--at-chosen]
//         [--no-volume|--scale] [--freeze] [--keep-drift] [--uniform-offset]
//         [--smooth-boundary|--virtual-boundary]
//                                      runs fairing::fair() in-process on INPUT (rounded to
//                                      float, as the CLI and MeshLab read it) and prints one JSON
//                                      line per time step (rms: to the surface; rms_normal:
//                                      along the clean normals, per vertex): the log-scale
//                                      search of the best one starting at X0
//                                      (bench::log_search), or the listed ones;
//                                      --auto adds the engine's automatic choice when it has
//                                      one (Options::time_step an optional value), else a line
//                                      with "auto":"n/a"; --at-chosen: the automatic choice and
//                                      then one fixed run at the time step it chose (nothing
//                                      else; for the cost row); --no-volume: volume not
//                                      restored; --scale: restored by the paper's scaling
//                                      instead of the default normal offset; --freeze: the
//                                      first step's operator for every step (section 4.3);
//                                      --keep-drift: Options::cancel_drift off;
//                                      --uniform-offset: Options::shaped_offset off;
//                                      --smooth-boundary / --virtual-boundary: BoundaryMode
//                                      SmoothCurve / VirtualVertex instead of Fixed (each line
//                                      also gives Result::boundary_time_step)
// TRUTH: sphere | plane | torus:R:r | mesh (the CLEAN mesh's surface).
#include "bench_mesh.h"
#include "denoise_shapes.h"

#include "fairing/fairing.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

using namespace bench;

namespace {

// The engine of the tree this is built with either has the automatic strength (issue 11:
// Options::time_step is an optional value, empty = automatic; Result::time_step,
// noise_level_edges and strength_seconds report the choice) or not; both compile.
template <class O> auto set_auto(O& o, int) -> decltype(o.time_step.reset(), bool()) {
    o.time_step.reset();
    return true;
}
template <class O> bool set_auto(O&, long) { return false; }
template <class R> auto chosen_step(const R& r, int) -> decltype(double(r.time_step)) { return r.time_step; }
template <class R> double chosen_step(const R&, long) { return std::nan(""); }
template <class R> auto noise_edges(const R& r, int) -> decltype(double(r.noise_level_edges)) { return r.noise_level_edges; }
template <class R> double noise_edges(const R&, long) { return std::nan(""); }
template <class R> auto strength_seconds(const R& r, int) -> decltype(double(r.strength_seconds)) { return r.strength_seconds; }
template <class R> double strength_seconds(const R&, long) { return std::nan(""); }
template <class R> auto curve_step(const R& r, int) -> decltype(double(r.boundary_time_step)) {
    return r.boundary_time_step;
}
template <class R> double curve_step(const R&, long) { return std::nan(""); }
template <class R> auto strength_steps(const R& r, int) -> decltype(int(r.strength_iterations)) { return r.strength_iterations; }
template <class R> int strength_steps(const R&, long) { return 0; }
// Options::cancel_drift = value, on an engine that has it (false: it has not).
template <class O> auto set_cancel_drift(O& o, bool value) -> decltype(o.cancel_drift = value, bool()) {
    o.cancel_drift = value;
    return true;
}
template <class O> bool set_cancel_drift(O&, int) { return false; }
// Options::shaped_offset = value, likewise.
template <class O>
auto set_shaped_offset(O& o, bool value) -> decltype(o.shaped_offset = value, bool()) {
    o.shaped_offset = value;
    return true;
}
template <class O> bool set_shaped_offset(O&, int) { return false; }

std::string num(double x) {
    if (!std::isfinite(x)) return "null";
    char b[40];
    std::snprintf(b, sizeof b, "%.8g", x);
    return b;
}

fairing::Operator parse_op(const std::string& s) {
    if (s == "umbrella") return fairing::Operator::Umbrella;
    if (s == "scale-dependent") return fairing::Operator::ScaleDependent;
    if (s == "curvature") return fairing::Operator::CurvatureFlow;
    throw std::runtime_error("unknown operator " + s + " (umbrella, scale-dependent, curvature)");
}

std::string truth_spec(const std::string& t, const std::string& clean) { return t == "mesh" ? clean : t; }

struct Run {
    Score s;
    double rms_normal = std::nan("");  // RMS of n_i . (x_i - clean_i) / h: what SURE estimates
    double seconds = 0, chosen = std::nan(""), noise = std::nan(""), choosing = std::nan("");
    double curve = std::nan("");  // Result::boundary_time_step (0: no smoothed boundary curve)
    int cg = 0, lanczos = 0;  // lanczos: the strength estimate's Lanczos steps
    std::string error;
};

// The error SURE estimates (auto_strength.h): per vertex, along the clean mesh's area-weighted
// normal, against the vertex's own clean position. Tangential sliding is free in both this and
// the distance to the surface; they differ where the surface turns within the error's reach: a
// vertex pulled inwards at a 90-degree crease is cos 45 degrees of its displacement from the
// nearest face (bench/results/issue11/auto-gap.md).
double rms_along_normals(const Mesh& clean, const std::vector<V3>& normals,
                         const std::vector<V3>& p, double h) {
    if (clean.v.size() != p.size()) return std::nan("");
    double e2 = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        const double d = dot(normals[i], sub(p[i], clean.v[i]));
        e2 += d * d;
    }
    return std::sqrt(e2 / double(std::max<size_t>(1, p.size()))) / h;
}

Run fair_once(const fairing::TriangleMesh& tm, const Mesh& input, const Truth& truth, double h,
              fairing::Options o, const Mesh& clean, const std::vector<V3>& normals) {
    Run run;
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const fairing::Result r = fairing::fair(tm, fairing::Constraints{}, o);
        run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::vector<V3> p(input.v.size());
        for (size_t i = 0; i < p.size(); ++i)
            for (int k = 0; k < 3; ++k) p[i][k] = double(float(r.positions(long(i), k)));  // stored as float
        run.s = score(truth, h, input, p);
        run.rms_normal = rms_along_normals(clean, normals, p, h);
        run.cg = r.total_iterations;
        run.chosen = chosen_step(r, 0);
        run.noise = noise_edges(r, 0);
        run.choosing = strength_seconds(r, 0);
        run.lanczos = strength_steps(r, 0);
        run.curve = curve_step(r, 0);
    } catch (const std::exception& e) {
        run.error = e.what();
        run.s.rms = std::nan("");
    }
    return run;
}

std::string json_text(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        o += (c == '\n' || c == '\t') ? ' ' : c;
    }
    return o;
}

void print_run(const char* kind, double ts, const Run& r) {
    std::printf("{\"kind\":\"%s\",\"time_step\":%s,\"rms\":%s,\"rms_normal\":%s,\"max\":%s,"
                "\"volume_change\":%s,\"seconds\":%s,\"cg\":%d,\"noise_level_edges\":%s,"
                "\"strength_seconds\":%s,\"strength_iterations\":%d,"
                "\"boundary_time_step\":%s%s%s%s}\n",
                kind, num(ts).c_str(), num(r.s.rms).c_str(), num(r.rms_normal).c_str(),
                num(r.s.max).c_str(),
                num(r.s.volume_change).c_str(), num(r.seconds).c_str(), r.cg, num(r.noise).c_str(),
                num(r.choosing).c_str(), r.lanczos, num(r.curve).c_str(),
                r.error.empty() ? "" : ",\"error\":\"", json_text(r.error).c_str(),
                r.error.empty() ? "" : "\"");
    std::fflush(stdout);
}

int sweep(int argc, char** argv) {
    const Mesh input = read_mesh_as_float(argv[2]), clean = read_mesh(argv[3]);
    const Truth truth(truth_spec(argv[4], argv[3]));
    const double h = mean_edge(clean);
    const std::vector<V3> normals = vertex_normals(clean);
    fairing::Options o;
    o.op = parse_op(argv[5]);
    o.order = std::atoi(argv[6]);
    o.steps = std::atoi(argv[7]);
    o.threads = 1;
    const double x0 = std::atof(argv[8]);
    std::vector<double> list;
    bool want_auto = false, at_chosen = false;
    for (int i = 9; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--auto") want_auto = true;
        else if (a == "--at-chosen") want_auto = at_chosen = true;
        else if (a == "--no-volume") o.preserve_volume = false;
        else if (a == "--scale") o.restoration = fairing::VolumeRestoration::Scale;
        else if (a == "--freeze") o.freeze_operator = true;
        else if (a == "--smooth-boundary") o.boundary = fairing::BoundaryMode::SmoothCurve;
        else if (a == "--virtual-boundary") o.boundary = fairing::BoundaryMode::VirtualVertex;
        else if (a == "--uniform-offset") {
            if (!set_shaped_offset(o, false))
                throw std::runtime_error("sweep: this engine has no Options::shaped_offset");
        } else if (a == "--keep-drift") {
            if (!set_cancel_drift(o, false))
                throw std::runtime_error("sweep: this engine has no Options::cancel_drift");
        }
        else if (a == "--ts" && i + 1 < argc) {
            std::stringstream ss(argv[++i]);
            std::string x;
            while (std::getline(ss, x, ',')) list.push_back(std::atof(x.c_str()));
        } else throw std::runtime_error("sweep: unknown argument " + a);
    }
    fairing::TriangleMesh tm;
    tm.positions.resize(long(input.v.size()), 3);
    for (size_t i = 0; i < input.v.size(); ++i)
        for (int k = 0; k < 3; ++k) tm.positions(long(i), k) = input.v[i][k];
    tm.triangles.assign(input.f.begin(), input.f.end());
    {
        Run r{score(truth, h, input, input.v)};
        r.rms_normal = rms_along_normals(clean, normals, input.v, h);
        print_run("input", 0, r);
    }
    if (want_auto) {
        fairing::Options a = o;
        if (set_auto(a, 0)) {
            const Run r = fair_once(tm, input, truth, h, a, clean, normals);
            print_run("auto", r.chosen, r);
            if (at_chosen && std::isfinite(r.chosen)) list.push_back(r.chosen);
        } else std::printf("{\"kind\":\"auto\",\"auto\":\"n/a\"}\n");
    }
    auto f = [&](double ts) {
        fairing::Options e = o;
        e.time_step = ts;
        const Run r = fair_once(tm, input, truth, h, e, clean, normals);
        print_run("fixed", ts, r);
        return r.s.rms;
    };
    if (!list.empty() || at_chosen)
        for (double ts : list) f(ts);
    else log_search(f, x0, 1e-4, 1e6);
    return 0;
}

int usage() {
    std::cerr << "usage: fairing-denoise-tool make|noise|info|eval|sweep ... (see the source)\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc < 2) return usage();
        const std::string cmd = argv[1];
        if (cmd == "make" && argc == 5) {
            const std::string what = argv[2];
            const long long n = std::atoll(argv[3]);
            // sphere2 takes a subdivision level (5: 51 k faces, each level 4x), plane a grid
            // size, torus a face count: a face count given as a level asked for 4^25000 faces.
            const long long most = what == "sphere2" ? 9 : what == "plane" ? 4000 : 100000000;
            if (n < 1 || n > most) {
                std::cerr << "make " << what << ": " << argv[3] << " is out of range 1.." << most
                          << (what == "sphere2" ? " (a subdivision level)" : "") << "\n";
                return 2;
            }
            if (what == "sphere2") write_ply(argv[4], sphere_two_densities(int(n)));
            else if (what == "plane") write_ply(argv[4], flat_patch(int(n)));
            else if (what == "torus") write_ply(argv[4], torus_faces(n));
            else return usage();
        } else if (cmd == "noise" && argc == 7) {
            const Mesh m = read_mesh(argv[2]);
            const double sigma = std::atof(argv[4]) * mean_edge(m);
            const unsigned seed = unsigned(std::atoi(argv[5]));
            const std::string kind = argv[6];
            if (kind != "normal" && kind != "iso") return usage();
            write_ply(argv[3], kind == "iso" ? add_isotropic_noise(m, sigma, seed) : add_normal_noise(m, sigma, seed));
        } else if (cmd == "info" && argc == 3) {
            const Mesh m = read_mesh(argv[2]);
            std::printf("{\"vertices\":%zu,\"faces\":%zu,\"mean_edge\":%.10g,\"volume\":%.12g,\"closed\":%s}\n",
                        m.v.size(), m.f.size(), mean_edge(m), volume(m), is_closed(m) ? "true" : "false");
        } else if (cmd == "eval" && argc >= 6) {
            const Mesh clean = read_mesh(argv[2]), input = read_mesh(argv[4]);
            const Truth truth(truth_spec(argv[3], argv[2]));
            const double h = mean_edge(clean);
            for (int i = 5; i < argc; ++i) {
                const Mesh r = read_mesh(argv[i]);
                if (r.v.size() != input.v.size()) throw std::runtime_error(std::string(argv[i]) + ": vertex count differs from INPUT");
                const Score s = score(truth, h, input, r.v);
                std::printf("{\"file\":\"%s\",\"rms\":%s,\"max\":%s,\"volume_change\":%s}\n", argv[i],
                            num(s.rms).c_str(), num(s.max).c_str(), num(s.volume_change).c_str());
            }
        } else if (cmd == "sweep" && argc >= 9) {
            return sweep(argc, argv);
        } else return usage();
    } catch (const std::exception& e) {
        std::cerr << "fairing-denoise-tool: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
