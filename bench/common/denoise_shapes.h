// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Denoising study (issue 11): shapes with a known surface, noise models, the error measure, and a
// one-dimensional search on a log scale. Benchmark-only, header-only, C++17, no engine code.
//
// Error convention (bench/README.md, "Denoising study"): RMS over the vertices of the distance
// from each result vertex to the TRUE surface, divided by the clean mesh's mean edge length h.
// The true surface is exact for the synthetic shapes ("sphere": unit sphere at the origin,
// "torus:R:r": z-axis torus, "plane": z = 0) and the clean mesh for scans (any other spec is a
// mesh path, queried through bench::SurfaceGrid).
#pragma once

#include "bench_mesh.h"

#include <functional>
#include <map>
#include <memory>
#include <utility>

namespace bench {

// ---------------------------------------------------------------- true surfaces
class Truth {
public:
    explicit Truth(const std::string& spec, double cell_hint = 0) {
        if (spec == "sphere") kind_ = Sphere;
        else if (spec == "plane") kind_ = Plane;
        else if (spec.rfind("torus:", 0) == 0) {
            kind_ = Torus;
            if (std::sscanf(spec.c_str() + 6, "%lf:%lf", &R_, &r_) != 2)
                throw std::runtime_error("truth '" + spec + "': expected torus:R:r");
        } else {
            kind_ = MeshSurface;
            mesh_ = read_mesh(spec);
            grid_ = std::make_unique<SurfaceGrid>(mesh_, cell_hint > 0 ? cell_hint : 2 * mean_edge(mesh_));
        }
    }
    double distance(const V3& p) const {
        switch (kind_) {
        case Sphere: return std::abs(norm(p) - 1.0);
        case Plane: return std::abs(p[2]);
        case Torus: {
            const double q = std::hypot(p[0], p[1]) - R_;
            return std::abs(std::hypot(q, p[2]) - r_);
        }
        default: return grid_->distance(p);
        }
    }
    bool exact() const { return kind_ != MeshSurface; }

private:
    enum Kind { Sphere, Plane, Torus, MeshSurface } kind_ = Sphere;
    double R_ = 1, r_ = 0.4;
    Mesh mesh_;
    std::unique_ptr<SurfaceGrid> grid_;
};

struct Score {
    double rms = 0;            // RMS distance to the true surface / h
    double max = 0;            // largest distance / h
    double volume_change = 0;  // percent, result vs input (closed meshes; 0 volume: 0)
};

inline Score score(const Truth& truth, double h, const Mesh& input, const std::vector<V3>& result) {
    Score s;
    double e2 = 0;
    for (const auto& p : result) {
        const double d = truth.distance(p);
        e2 += d * d;
        s.max = std::max(s.max, d);
    }
    s.rms = std::sqrt(e2 / double(std::max<size_t>(1, result.size()))) / h;
    s.max /= h;
    Mesh r{result, input.f};
    const double v0 = volume(input), v1 = volume(r);
    s.volume_change = v0 != 0 ? 100.0 * (v1 - v0) / v0 : 0;
    return s;
}

// Closed = every edge has exactly two faces (volume is then meaningful).
inline bool is_closed(const Mesh& m) {
    std::unordered_map<uint64_t, int> count;
    count.reserve(m.f.size() * 2);
    for (const auto& f : m.f)
        for (int k = 0; k < 3; ++k) {
            const int a = f[k], b = f[(k + 1) % 3];
            ++count[edge_key(a, b)];
        }
    for (const auto& kv : count)
        if (kv.second != 2) return false;
    return true;
}

// ---------------------------------------------------------------- noise
// Gaussian, sigma (absolute) per axis in all three directions: its normal component has the
// same sigma as add_normal_noise's, plus a tangential part of twice that variance.
inline Mesh add_isotropic_noise(const Mesh& m, double sigma, unsigned seed = 1) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, sigma);
    Mesh out = m;
    for (auto& p : out.v)
        for (int k = 0; k < 3; ++k) p[k] += g(rng);
    return out;
}

// ---------------------------------------------------------------- shapes with a known surface
// Unit sphere sampled at two densities: an icosahedron subdivided `level` times, then the
// faces of the upper half (centroid z > 0) split once more (red-green, so the mesh stays
// conforming: a face with one or two split edges is bisected or cut in three). Every vertex is
// then moved tangentially by up to 0.25 of its shortest edge, at random, and put back on the
// sphere: irregular sampling, edge length halved across the equator, vertices exactly on it.
inline Mesh sphere_two_densities(int level, unsigned seed = 3) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    Mesh m;
    m.v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
           {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
           {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    auto project = [](V3 p) { return mul(p, 1.0 / norm(p)); };
    for (auto& p : m.v) p = project(p);
    // split: faces to refine fully; their edges get midpoints; other faces are closed red-green.
    auto refine = [&](const std::vector<char>& full) {
        std::unordered_map<uint64_t, int> mid;
        for (size_t i = 0; i < m.f.size(); ++i)
            if (full[i])
                for (int k = 0; k < 3; ++k) {
                    const int a = m.f[i][k], b = m.f[i][(k + 1) % 3];
                    if (mid.emplace(edge_key(a, b), 0).second) {
                        mid[edge_key(a, b)] = int(m.v.size());
                        m.v.push_back(project(mul(add(m.v[a], m.v[b]), 0.5)));
                    }
                }
        std::vector<T3> nf;
        for (const auto& f : m.f) {
            int e[3], n = 0;
            for (int k = 0; k < 3; ++k) {
                auto it = mid.find(edge_key(f[k], f[(k + 1) % 3]));
                e[k] = it == mid.end() ? -1 : it->second;
                n += e[k] >= 0;
            }
            if (n == 0) nf.push_back(f);
            else if (n == 3) {
                nf.push_back({f[0], e[0], e[2]});
                nf.push_back({f[1], e[1], e[0]});
                nf.push_back({f[2], e[2], e[1]});
                nf.push_back({e[0], e[1], e[2]});
            } else {
                // rotate so that edge 0 (f0 f1) is split
                int r = 0;
                while (e[r] < 0) ++r;
                const int a = f[r], b = f[(r + 1) % 3], c = f[(r + 2) % 3];
                const int eab = e[r], ebc = e[(r + 1) % 3], eca = e[(r + 2) % 3];
                if (n == 1) { nf.push_back({a, eab, c}); nf.push_back({eab, b, c}); }
                else if (ebc >= 0) { nf.push_back({a, eab, c}); nf.push_back({eab, b, ebc}); nf.push_back({eab, ebc, c}); }
                else { nf.push_back({a, eab, eca}); nf.push_back({eab, b, c}); nf.push_back({eab, c, eca}); }
            }
        }
        m.f = std::move(nf);
    };
    for (int l = 0; l < level; ++l) refine(std::vector<char>(m.f.size(), 1));
    std::vector<char> upper(m.f.size());
    for (size_t i = 0; i < m.f.size(); ++i)
        upper[i] = m.v[m.f[i][0]][2] + m.v[m.f[i][1]][2] + m.v[m.f[i][2]][2] > 0;
    refine(upper);
    std::vector<double> shortest(m.v.size(), 1e300);
    for (const auto& f : m.f)
        for (int k = 0; k < 3; ++k) {
            const double l = norm(sub(m.v[f[k]], m.v[f[(k + 1) % 3]]));
            shortest[f[k]] = std::min(shortest[f[k]], l);
            shortest[f[(k + 1) % 3]] = std::min(shortest[f[(k + 1) % 3]], l);
        }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (size_t i = 0; i < m.v.size(); ++i) {
        V3 d = {u(rng), u(rng), u(rng)};
        d = sub(d, mul(m.v[i], dot(d, m.v[i])));
        const double l = norm(d);
        if (l > 0) m.v[i] = project(add(m.v[i], mul(d, 0.25 * shortest[i] * u(rng) / l)));
    }
    return m;
}

// Flat irregular patch in z = 0: an n x n grid of the unit square, interior vertices jittered
// by up to +-0.3 cell, each quad split along a random diagonal. Open (its boundary stays fixed
// under the default boundary mode of every filter compared).
inline Mesh flat_patch(int n, unsigned seed = 5) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jit(-0.3, 0.3);
    std::bernoulli_distribution coin(0.5);
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const bool inner = i > 0 && j > 0 && i < n && j < n;
            m.v.push_back({(i + (inner ? jit(rng) : 0)) / n, (j + (inner ? jit(rng) : 0)) / n, 0});
        }
    auto id = [&](int i, int j) { return i * (n + 1) + j; };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (coin(rng)) { m.f.push_back({a, b, c}); m.f.push_back({a, c, d}); }
            else { m.f.push_back({a, b, d}); m.f.push_back({b, c, d}); }
        }
    return m;
}

// ---------------------------------------------------------------- 1-D search on a log scale
// Minimises f over x > 0, f assumed unimodal in log x: walks from x0 by factor 2 until the value
// rose twice past the best (or the range [lo, hi] ends), then narrows the bracket around the
// best with golden-section steps until it is within `ratio` (default 1.05). Every evaluation is
// kept (x, f) for the plot; returns them, the best first element is not guaranteed.
inline std::vector<std::pair<double, double>> log_search(const std::function<double(double)>& f, double x0,
                                                        double lo, double hi, double ratio = 1.05) {
    std::map<double, double> seen;
    auto eval = [&](double x) {
        auto it = seen.find(x);
        if (it != seen.end()) return it->second;
        const double v = f(x);
        seen[x] = std::isfinite(v) ? v : 1e300;
        return seen[x];
    };
    auto best_x = [&] {
        return std::min_element(seen.begin(), seen.end(),
                                [](const auto& a, const auto& b) { return a.second < b.second; })->first;
    };
    eval(x0);
    for (int dir : {+1, -1}) {  // up, then down, from the current best
        double x = best_x();
        int rises = 0;
        double prev = eval(x);
        while (rises < 2) {
            x = dir > 0 ? x * 2 : x / 2;
            if (x > hi || x < lo) break;
            const double v = eval(x);
            // a failed run (1e300) counts as a rise: two in a row end the walk
            rises = (v > prev || v >= 1e300) ? rises + 1 : (v < eval(best_x()) ? 0 : rises);
            prev = v;
        }
    }
    // golden section in log x on the bracket around the best sample
    double b = best_x();
    auto it = seen.find(b);
    double a = it == seen.begin() ? b / 2 : std::prev(it)->first;
    double c = std::next(it) == seen.end() ? b * 2 : std::next(it)->first;
    const double g = 0.381966;
    for (int iter = 0; iter < 30 && c / a > ratio * ratio; ++iter) {
        const double la = std::log(a), lb = std::log(b), lc = std::log(c);
        const bool right = lc - lb > lb - la;
        const double x = std::exp(right ? lb + g * (lc - lb) : lb - g * (lb - la));
        if (x < lo || x > hi) break;
        if (eval(x) < eval(b)) { (right ? a : c) = b; b = x; }
        else (right ? c : a) = x;
    }
    return {seen.begin(), seen.end()};
}

}  // namespace bench
