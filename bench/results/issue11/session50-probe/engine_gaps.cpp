// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// auto-gap.md section 50: the median and largest index gap of an edge after the engine's own
// renumbering (vertex_order.h) of a binary PLY as the bench tools write it.
// Build and run (repository root, after scripts/setup.sh):
//   g++ -O2 -std=c++17 -I fairing/src -I fairing/include -I /usr/include/eigen3 \
//       bench/results/issue11/session50-probe/engine_gaps.cpp build/fairing/libfairing.a \
//       -fopenmp -o /tmp/engine_gaps && /tmp/engine_gaps MESH.ply
#include "vertex_order.h"
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
#include <algorithm>
int main(int, char** argv) {
    std::ifstream in(argv[1], std::ios::binary); std::string line; int nv = 0, nf = 0;
    while (std::getline(in, line) && line != "end_header") {
        if (line.rfind("element vertex", 0) == 0) nv = std::stoi(line.substr(15));
        if (line.rfind("element face", 0) == 0) nf = std::stoi(line.substr(13));
    }
    fairing::TriangleMesh m; m.positions.resize(nv, 3);
    std::vector<double> buf(3 * nv); in.read((char*)buf.data(), 24 * (long)nv);
    for (int i = 0; i < nv; ++i) for (int c = 0; c < 3; ++c) m.positions(i, c) = buf[3 * i + c];
    for (int k = 0; k < nf; ++k) { unsigned char n; int t[3]; in.read((char*)&n, 1); in.read((char*)t, 12); m.triangles.push_back({t[0], t[1], t[2]}); }
    const auto local = fairing::detail::renumbered(m, fairing::detail::locality_order(m));
    std::vector<int> g;
    for (const auto& t : local.triangles) for (int k = 0; k < 3; ++k) g.push_back(std::abs(t[k] - t[(k + 1) % 3]));
    std::sort(g.begin(), g.end());
    std::printf("vertices %d: median gap %d, largest %d\n", nv, g[g.size() / 2], g.back());
}
