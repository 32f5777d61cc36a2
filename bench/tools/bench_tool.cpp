// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// fairing-bench-tool: mesh preparation and measurement for bench/run.sh.
//   torus FACES OUT.ply                      jittered torus with about FACES faces
//   loop IN OUT.ply [LEVELS]                 Loop subdivision
//   midpoint IN OUT.ply [LEVELS]             1-to-4 split at the edge midpoints (keeps triangle shapes)
//   noise IN OUT.ply SIGMA_EDGES [SEED]      Gaussian noise of SIGMA mean edges along normals
//   convert IN OUT.ply                       OFF/PLY -> binary PLY (float coordinates)
//   info IN                                  JSON: vertices, faces, mean_edge, volume
//   metrics CLEAN INPUT RESULT               JSON: error of RESULT (and INPUT) to CLEAN's
//                                            surface, volume change vs INPUT, tangential drift
//   fair IN OUT.ply OP ORDER TIME_STEP|auto [STEPS [threads=N] [preconditioner=P] [freeze=1]
//                                            [volume=0|1] [shaped=0|1]]
//                                            runs fairing::fair() directly: JSON with seconds,
//                                            iterations and the engine's extra peak memory
#include "bench_mesh.h"

#include "fairing/fairing.h"

#include <fstream>
#include <cstring>
#include <string>
#include <cstdlib>
#include <chrono>
#include <ctime>
#include <iostream>
#include <sys/resource.h>

using namespace bench;

namespace {

long peak_rss_kb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

// VmRSS or VmHWM of /proc/self/status in kB, -1 when unavailable.
long status_kb(const char* key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + std::strlen(key) + 1);
    return -1;
}

// Resets the kernel's peak-RSS mark (VmHWM) to the current RSS, so the peak measured after a
// call is that call's own and not an earlier transient such as the mesh reader's buffers.
bool reset_peak_rss() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    return static_cast<bool>(clear);
}

int usage() {
    std::cerr << "usage: fairing-bench-tool torus|loop|midpoint|noise|convert|info|metrics|fair ... (see source)\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc < 2) return usage();
        const std::string cmd = argv[1];
        if (cmd == "torus" && argc == 4) {
            write_ply(argv[3], torus_faces(std::atoll(argv[2])));
        } else if (cmd == "loop" && argc >= 4) {
            Mesh m = read_mesh(argv[2]);
            const int levels = argc > 4 ? std::atoi(argv[4]) : 1;
            for (int l = 0; l < levels; ++l) m = loop_subdivide(m);
            write_ply(argv[3], m);
        } else if (cmd == "midpoint" && argc >= 4) {
            Mesh m = read_mesh(argv[2]);
            const int levels = argc > 4 ? std::atoi(argv[4]) : 1;
            for (int l = 0; l < levels; ++l) m = midpoint_subdivide(m);
            write_ply(argv[3], m);
        } else if (cmd == "noise" && argc >= 5) {
            const Mesh m = read_mesh(argv[2]);
            const double sigma = std::atof(argv[4]) * mean_edge(m);
            write_ply(argv[3], add_normal_noise(m, sigma, argc > 5 ? unsigned(std::atoi(argv[5])) : 1u));
        } else if (cmd == "convert" && argc == 4) {
            write_ply(argv[3], read_mesh(argv[2]));
        } else if (cmd == "info" && argc == 3) {
            const Mesh m = read_mesh(argv[2]);
            std::printf("{\"vertices\":%zu,\"faces\":%zu,\"mean_edge\":%.10g,\"volume\":%.12g}\n",
                        m.v.size(), m.f.size(), mean_edge(m), volume(m));
        } else if (cmd == "metrics" && argc == 5) {
            const Mesh clean = read_mesh(argv[2]), input = read_mesh(argv[3]),
                       result = read_mesh(argv[4]);
            if (input.v.size() != clean.v.size() || result.v.size() != clean.v.size())
                throw std::runtime_error("metrics: CLEAN, INPUT and RESULT must share vertices");
            const double h = mean_edge(clean);
            const SurfaceGrid grid(clean, 2 * h);
            const auto n = vertex_normals(clean);
            double e_in = 0, e_out = 0, drift = 0, maxd = 0;
            for (size_t i = 0; i < clean.v.size(); ++i) {
                const double di = grid.distance(input.v[i]), dr = grid.distance(result.v[i]);
                e_in += di * di;
                e_out += dr * dr;
                maxd = std::max(maxd, dr);
                const V3 d = sub(result.v[i], clean.v[i]);
                const V3 t = sub(d, mul(n[i], dot(d, n[i])));
                drift += dot(t, t);
            }
            const double N = double(clean.v.size());
            const double v0 = volume(input), v1 = volume(result);
            std::printf("{\"rms_input\":%.6g,\"rms_result\":%.6g,\"max_result\":%.6g,"
                        "\"tangential_drift\":%.6g,\"volume_change_percent\":%.6g,"
                        "\"mean_edge\":%.10g}\n",
                        std::sqrt(e_in / N) / h, std::sqrt(e_out / N) / h, maxd / h,
                        std::sqrt(drift / N) / h, 100.0 * (v1 - v0) / v0, h);
        } else if (cmd == "fair" && argc >= 7) {
            const Mesh m = read_mesh(argv[2]);
            fairing::TriangleMesh tm;
            tm.positions.resize(long(m.v.size()), 3);
            for (size_t i = 0; i < m.v.size(); ++i)
                for (int k = 0; k < 3; ++k) tm.positions(long(i), k) = m.v[i][k];
            tm.triangles.assign(m.f.begin(), m.f.end());
            fairing::Options o;
            const std::string op = argv[4];
            o.op = op == "umbrella" ? fairing::Operator::Umbrella
                 : op == "scale-dependent" ? fairing::Operator::ScaleDependent
                                           : fairing::Operator::CurvatureFlow;
            o.order = std::atoi(argv[5]);
            if (std::string(argv[6]) == "auto") o.time_step.reset();  // automatic strength
            else o.time_step = std::atof(argv[6]);
            o.steps = argc > 7 ? std::atoi(argv[7]) : 1;
            // Optional after STEPS: threads=N, preconditioner=auto|jacobi|factored, freeze=0|1,
            // volume=0|1 (Options::preserve_volume, default 1), shaped=0|1 (Options::shaped_offset,
            // default 1).
            for (int k = 8; k < argc; ++k) {
                const std::string kv = argv[k];
                const std::size_t eq = kv.find('=');
                const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
                if (key == "threads") o.threads = std::atoi(value.c_str());
                else if (key == "freeze") o.freeze_operator = value == "1";
                else if (key == "volume") o.preserve_volume = value == "1";
                else if (key == "shaped") o.shaped_offset = value == "1";
                else if (key == "preconditioner")
                    o.preconditioner = value == "jacobi" ? fairing::Preconditioner::Jacobi
                                     : value == "factored" ? fairing::Preconditioner::Factored
                                     : value == "multigrid" ? fairing::Preconditioner::Multigrid
                                                           : fairing::Preconditioner::Automatic;
                else return usage();
            }
            // Extra memory of fair(): its peak RSS above the RSS with the mesh loaded.
            const bool reset = reset_peak_rss();
            const long before = reset ? status_kb("VmRSS:") : peak_rss_kb();
            const auto t0 = std::chrono::steady_clock::now();
            // Process CPU time as well: on a shared, loaded machine the one-thread runs' CPU time
            // is the work done, where the wall time also counts the waits for a core.
            const std::clock_t c0 = std::clock();
            const fairing::Result r = fairing::fair(tm, fairing::Constraints{}, o);
            const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            const long after = reset ? status_kb("VmHWM:") : peak_rss_kb();
            Mesh out = m;
            for (size_t i = 0; i < m.v.size(); ++i)
                for (int k = 0; k < 3; ++k) out.v[i][k] = r.positions(long(i), k);
            write_ply(argv[3], out);
            // Per solve (one per step, or one for frozen steps taken at once): its iterations.
            std::string per_solve;
            for (const fairing::SolveReport& solve : r.solves)
                per_solve += (per_solve.empty() ? "" : ",") + std::to_string(solve.iterations);
            std::printf("{\"seconds\":%.6f,\"seconds_engine\":%.6f,\"cg_iterations\":%d,"
                        "\"inner_iterations\":%d,\"cpu_seconds\":%.6f,"
                        "\"extra_peak_bytes_per_vertex\":%.1f,\"peak_rss_kb\":%ld,"
                        "\"time_step\":%.9g,\"strength_seconds\":%.6f,\"strength_iterations\":%d,"
                        "\"solve_iterations\":[%s]}\n",
                        s, r.seconds, r.total_iterations, r.total_inner_iterations, cpu,
                        1024.0 * double(after - before) / double(m.v.size()), after, r.time_step,
                        r.strength_seconds, r.strength_iterations, per_solve.c_str());
        } else return usage();
    } catch (const std::exception& e) {
        std::cerr << "fairing-bench-tool: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
