// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Peer driver: CGAL::Polygon_mesh_processing::smooth_shape (CGAL 5.5, Debian 12's libcgal-dev).
//   cgal_smooth_shape IN OUT.ply TIME [ITERATIONS]
// One implicit step solves (M - TIME * K) X' = M X with K_ij = cot a + cot b and the lumped mass
// M_ii = (one-ring area)/6 (curvature_flow_impl.h), i.e. L = M^-1 K ~ 4 Laplace-Beltrami:
// TIME = T/4 for diffusion time T. Volume: smooth_shape rescales closed meshes itself.
// Prints one JSON line; seconds covers smooth_shape only (not I/O, not building the mesh).
#include "bench_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <iostream>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: cgal_smooth_shape IN OUT.ply TIME [ITERATIONS]\n";
        return 2;
    }
    try {
        bench::Mesh m = bench::read_mesh(argv[1]);
        const double time = std::atof(argv[3]);
        const unsigned iterations = argc > 4 ? unsigned(std::atoi(argv[4])) : 1u;
        SM sm;
        std::vector<SM::Vertex_index> vi;
        vi.reserve(m.v.size());
        for (const auto& p : m.v) vi.push_back(sm.add_vertex(K::Point_3(p[0], p[1], p[2])));
        for (const auto& f : m.f)
            if (sm.add_face(vi[f[0]], vi[f[1]], vi[f[2]]) == SM::null_face())
                throw std::runtime_error("CGAL refused a face (non-manifold input)");
        const auto t0 = std::chrono::steady_clock::now();
        PMP::smooth_shape(sm, time, CGAL::parameters::number_of_iterations(iterations));
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t i = 0; i < m.v.size(); ++i) {
            const auto& p = sm.point(vi[i]);
            m.v[i] = {p.x(), p.y(), p.z()};
        }
        bench::write_ply(argv[2], m);
        std::printf("{\"peer\":\"cgal_smooth_shape\",\"seconds\":%.6f,\"time\":%.10g,\"iterations\":%u}\n",
                    s, time, iterations);
    } catch (const std::exception& e) {
        std::cerr << "cgal_smooth_shape: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
