// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Denoising study peer (bench/denoise.sh): OpenMesh 9 JacobiLaplaceSmootherT (C0 uniform or C1
// second-order umbrella, Tangential_and_Normal), evaluated after each iteration count of a
// growing list until the error has risen 30 % above its best (or MAX iterations).
//   openmesh_denoise INPUT CLEAN TRUTH C0|C1 MAX
// One JSON line per checkpoint: iterations, rms, max (mean edges of CLEAN), volume_change (%),
// seconds (smoothing so far). Error convention and TRUTH: common/denoise_shapes.h.
#include "bench_mesh.h"
#include "denoise_shapes.h"

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
    if (argc != 6) {
        std::cerr << "usage: openmesh_denoise INPUT CLEAN TRUTH C0|C1 MAX\n";
        return 2;
    }
    try {
        bench::Mesh in = bench::read_mesh_as_float(argv[1]);
        const bench::Mesh clean = bench::read_mesh(argv[2]);
        const std::string spec = argv[3], cont = argv[4];
        const bench::Truth truth(spec == "mesh" ? argv[2] : spec);
        const double h = bench::mean_edge(clean);
        const int max_iterations = std::atoi(argv[5]);
        Mesh om;
        std::vector<Mesh::VertexHandle> vh;
        for (const auto& p : in.v) vh.push_back(om.add_vertex(Mesh::Point(p[0], p[1], p[2])));
        for (const auto& f : in.f)
            if (!om.add_face(vh[f[0]], vh[f[1]], vh[f[2]]).is_valid())
                throw std::runtime_error("OpenMesh refused a face (non-manifold input)");
        om.request_vertex_normals();
        om.request_face_normals();
        om.update_normals();
        OpenMesh::Smoother::JacobiLaplaceSmootherT<Mesh> smoother(om);
        smoother.initialize(OpenMesh::Smoother::SmootherT<Mesh>::Tangential_and_Normal,
                            cont == "C1" ? OpenMesh::Smoother::SmootherT<Mesh>::C1
                                         : OpenMesh::Smoother::SmootherT<Mesh>::C0);
        double seconds = 0, best = 1e300;
        int done = 0;
        for (int next = 1; next <= max_iterations;) {
            const auto t0 = std::chrono::steady_clock::now();
            smoother.smooth(static_cast<unsigned int>(next - done));
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            done = next;
            std::vector<bench::V3> out(in.v.size());
            for (size_t i = 0; i < out.size(); ++i) {
                const auto& p = om.point(vh[i]);
                out[i] = {double(float(p[0])), double(float(p[1])), double(float(p[2]))};
            }
            const bench::Score sc = bench::score(truth, h, in, out);
            std::printf("{\"iterations\":%d,\"rms\":%.8g,\"max\":%.8g,\"volume_change\":%.8g,\"seconds\":%.6f}\n",
                        done, sc.rms, sc.max, sc.volume_change, seconds);
            std::fflush(stdout);
            best = std::min(best, sc.rms);
            if (sc.rms > 1.3 * best) break;
            next = done < 10 ? done + 1 : int(done * 1.15) + 1;
        }
    } catch (const std::exception& e) {
        std::cerr << "openmesh_denoise: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
