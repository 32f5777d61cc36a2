// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Denoising study peer (bench/denoise.sh): CGAL 5.5 Polygon_mesh_processing::smooth_shape at its
// best time, found by bench::log_search over the diffusion time c h^2 (time = c h^2 / 4, see
// cgal_smooth_shape.cpp for the mapping), with a given number of iterations.
//   cgal_denoise INPUT CLEAN TRUTH ITERATIONS C0
// One JSON line per evaluated time: c, time, rms, max (mean edges of CLEAN), volume_change (%),
// seconds (smooth_shape only). Error convention and TRUTH: common/denoise_shapes.h.
#include "bench_mesh.h"
#include "denoise_shapes.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <iostream>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
    if (argc != 6) {
        std::cerr << "usage: cgal_denoise INPUT CLEAN TRUTH ITERATIONS C0\n";
        return 2;
    }
    try {
        bench::Mesh in = bench::read_mesh_as_float(argv[1]);
        const bench::Mesh clean = bench::read_mesh(argv[2]);
        const std::string spec = argv[3];
        const bench::Truth truth(spec == "mesh" ? argv[2] : spec);
        const double h = bench::mean_edge(clean);
        const unsigned iterations = unsigned(std::atoi(argv[4]));
        auto f = [&](double c) {
            SM sm;
            std::vector<SM::Vertex_index> vi;
            for (const auto& p : in.v) vi.push_back(sm.add_vertex(K::Point_3(p[0], p[1], p[2])));
            for (const auto& t : in.f)
                if (sm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]) == SM::null_face())
                    throw std::runtime_error("CGAL refused a face (non-manifold input)");
            const double time = c * h * h / 4;
            const auto t0 = std::chrono::steady_clock::now();
            PMP::smooth_shape(sm, time, CGAL::parameters::number_of_iterations(iterations));
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::vector<bench::V3> out(in.v.size());
            for (size_t i = 0; i < out.size(); ++i) {
                const auto& p = sm.point(vi[i]);
                out[i] = {double(float(p.x())), double(float(p.y())), double(float(p.z()))};
            }
            const bench::Score sc = bench::score(truth, h, in, out);
            std::printf("{\"c\":%.8g,\"time\":%.8g,\"iterations\":%u,\"rms\":%.8g,\"max\":%.8g,"
                        "\"volume_change\":%.8g,\"seconds\":%.6f}\n",
                        c, time, iterations, sc.rms, sc.max, sc.volume_change, s);
            std::fflush(stdout);
            return sc.rms;
        };
        bench::log_search(f, std::atof(argv[5]), 1e-3, 1e5);
    } catch (const std::exception& e) {
        std::cerr << "cgal_denoise: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
