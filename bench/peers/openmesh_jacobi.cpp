// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Peer driver: OpenMesh::Smoother::JacobiLaplaceSmootherT (Debian 12's libopenmesh-dev),
// Tangential_and_Normal, C0 (uniform weights: LaplaceSmootherT::initialize).
//   openmesh_jacobi IN OUT.ply ITERATIONS
// One iteration: x += 0.5 (mean of neighbours - x) (JacobiLaplaceSmootherT_impl.hh), an explicit
// umbrella step with lambda = 0.5: diffusion time 0.5 * h^2/4 = h^2/8 per iteration on a regular
// mesh of edge h. No volume restoration. seconds covers initialize + smooth only.
#include "bench_mesh.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>

#include <chrono>
#include <iostream>

struct Traits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: openmesh_jacobi IN OUT.ply ITERATIONS\n";
        return 2;
    }
    try {
        bench::Mesh m = bench::read_mesh(argv[1]);
        const int iterations = std::atoi(argv[3]);
        Mesh om;
        std::vector<Mesh::VertexHandle> vh;
        vh.reserve(m.v.size());
        for (const auto& p : m.v) vh.push_back(om.add_vertex(Mesh::Point(p[0], p[1], p[2])));
        for (const auto& f : m.f)
            if (!om.add_face(vh[f[0]], vh[f[1]], vh[f[2]]).is_valid())
                throw std::runtime_error("OpenMesh refused a face (non-manifold input)");
        om.request_vertex_normals();
        om.request_face_normals();
        om.update_normals();
        const auto t0 = std::chrono::steady_clock::now();
        OpenMesh::Smoother::JacobiLaplaceSmootherT<Mesh> smoother(om);
        smoother.initialize(OpenMesh::Smoother::SmootherT<Mesh>::Tangential_and_Normal,
                            OpenMesh::Smoother::SmootherT<Mesh>::C0);
        smoother.smooth(static_cast<unsigned int>(iterations));
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t i = 0; i < m.v.size(); ++i) {
            const auto& p = om.point(vh[i]);
            m.v[i] = {p[0], p[1], p[2]};
        }
        bench::write_ply(argv[2], m);
        std::printf("{\"peer\":\"openmesh_jacobi\",\"seconds\":%.6f,\"iterations\":%d}\n", s, iterations);
    } catch (const std::exception& e) {
        std::cerr << "openmesh_jacobi: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
