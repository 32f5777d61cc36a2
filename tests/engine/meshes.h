// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Test meshes and independent geometry helpers for the engine tests.
//
// Everything here is written from the definitions (the paper, the public headers), never from
// the engine's sources: generators build indexed triangle meshes counter-clockwise seen from
// outside; the helpers recompute volumes, areas, edge lengths and dense matrices on their own so
// that the tests compare the engine against an independent computation.
#pragma once

#include "fairing/fairing.h"
#include "fairing/operators.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace meshes {

using fairing::Positions;
using fairing::Triangle;
using fairing::TriangleMesh;
using fairing::Vec3;

constexpr double kPi = 3.14159265358979323846;

// The paper's three operators, for tests that check all of them.
const fairing::Operator kOperators[] = {fairing::Operator::Umbrella,
                                        fairing::Operator::ScaleDependent,
                                        fairing::Operator::CurvatureFlow};

// ------------------------------------------------------------------------------------------
// Deterministic random numbers (splitmix64), identical on every platform.
struct Rng {
    std::uint64_t state;
    explicit Rng(std::uint64_t seed) : state(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
    // Uniform in [-1, 1).
    double symmetric() { return 2.0 * uniform() - 1.0; }
    // Standard normal (Box-Muller; one draw per call).
    double normal() {
        const double u = 1.0 - uniform();  // in (0, 1]: a finite logarithm
        return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * uniform());
    }
};

inline Vec3 row(const Positions& p, int i) { return p.row(i).transpose(); }
inline void set_row(Positions& p, int i, const Vec3& v) { p.row(i) = v.transpose(); }

// ------------------------------------------------------------------------------------------
// Generators.

// The quad a b c d (counter-clockwise) as two triangles, split along a-c or else along b-d.
inline void add_quad(TriangleMesh& m, int a, int b, int c, int d, bool along_ac) {
    if (along_ac) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
    } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
    }
}

// Regular torus grid, nu x nv vertices, valence 6 everywhere: every quad
// (u,v) (u+1,v) (u+1,v+1) (u,v+1) is split along the same diagonal (u,v)-(u+1,v+1), so the
// neighbours of (u,v) are at the offsets (+-1,0), (0,+-1), (1,1), (-1,-1).
inline int torus_index(int u, int v, int nu, int nv) {
    u = ((u % nu) + nu) % nu;
    v = ((v % nv) + nv) % nv;
    return v * nu + u;
}

inline const std::array<std::array<int, 2>, 6>& torus_neighbour_offsets() {
    static const std::array<std::array<int, 2>, 6> offsets = {
        {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}}};
    return offsets;
}

// A torus grid of nu x nv vertices: tube_offset(u, v) is added to the tube radius r at (u,v),
// which moves the vertex along the torus's normal, and the quad (u,v) (u+1,v) (u+1,v+1) (u,v+1)
// is split along (u,v)-(u+1,v+1) where along_first_diagonal(u, v), else along the other one.
template <class Offset, class Split>
TriangleMesh torus_mesh(int nu, int nv, double R, double r, const Offset& tube_offset,
                        const Split& along_first_diagonal) {
    TriangleMesh m;
    m.positions.resize(nu * nv, 3);
    for (int v = 0; v < nv; ++v) {
        for (int u = 0; u < nu; ++u) {
            const double a = 2 * kPi * u / nu, b = 2 * kPi * v / nv;
            const double rho = r + tube_offset(u, v);
            set_row(m.positions, torus_index(u, v, nu, nv),
                    Vec3((R + rho * std::cos(b)) * std::cos(a),
                         (R + rho * std::cos(b)) * std::sin(a), rho * std::sin(b)));
        }
    }
    for (int v = 0; v < nv; ++v) {
        for (int u = 0; u < nu; ++u) {
            const int p00 = torus_index(u, v, nu, nv), p10 = torus_index(u + 1, v, nu, nv);
            const int p11 = torus_index(u + 1, v + 1, nu, nv), p01 = torus_index(u, v + 1, nu, nv);
            // d/du x d/dv is the outward normal of this parameterization.
            add_quad(m, p00, p10, p11, p01, along_first_diagonal(u, v));
        }
    }
    return m;
}

inline TriangleMesh torus_grid(int nu, int nv, double R = 3.0, double r = 1.0) {
    return torus_mesh(nu, nv, R, r, [](int, int) { return 0.0; }, [](int, int) { return true; });
}

// The torus grid (nu, nv even) with each quad split along the diagonal through its corner (u,v)
// where u + v is even, the "union jack": valence 8 where u + v is even, 4 where it is odd, as in
// CAD and parametric tessellations; tube_offset as in torus_mesh.
template <class Offset>
TriangleMesh union_jack_torus(int nu, int nv, double R, double r, const Offset& tube_offset) {
    return torus_mesh(nu, nv, R, r, tube_offset, [](int u, int v) { return (u + v) % 2 == 0; });
}

inline TriangleMesh icosahedron(double radius = 1.0) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    const double raw[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                               {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                               {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    TriangleMesh m;
    m.positions.resize(12, 3);
    for (int i = 0; i < 12; ++i)
        set_row(m.positions, i, Vec3(raw[i][0], raw[i][1], raw[i][2]).normalized() * radius);
    m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    return m;
}

// Splits the faces flagged in `red` 1-to-4 and closes the refinement red-green style: a face with
// two or three split edges is split 1-to-4 too (repeated until stable), a face with exactly one
// split edge is split in two (green). New vertices are edge midpoints, projected on the sphere
// |x - center| = radius when radius > 0.
inline TriangleMesh refine(const TriangleMesh& in, std::vector<char> red, double radius = 0.0,
                           const Vec3& center = Vec3::Zero()) {
    const int nf = static_cast<int>(in.triangles.size());
    auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
    std::set<std::pair<int, int>> split;
    for (bool changed = true; changed;) {
        changed = false;
        split.clear();
        for (int f = 0; f < nf; ++f)
            if (red[f])
                for (int k = 0; k < 3; ++k)
                    split.insert(key(in.triangles[f][k], in.triangles[f][(k + 1) % 3]));
        for (int f = 0; f < nf; ++f) {
            if (red[f]) continue;
            int count = 0;
            for (int k = 0; k < 3; ++k)
                count += split.count(key(in.triangles[f][k], in.triangles[f][(k + 1) % 3])) ? 1 : 0;
            if (count >= 2) {
                red[f] = 1;
                changed = true;
            }
        }
    }
    std::vector<Vec3> pts;
    for (int i = 0; i < in.positions.rows(); ++i) pts.push_back(row(in.positions, i));
    std::map<std::pair<int, int>, int> mid;
    for (const auto& e : split) {
        Vec3 p = 0.5 * (pts[e.first] + pts[e.second]);
        if (radius > 0) p = center + (p - center).normalized() * radius;
        mid[e] = static_cast<int>(pts.size());
        pts.push_back(p);
    }
    TriangleMesh out;
    for (int f = 0; f < nf; ++f) {
        const Triangle& t = in.triangles[f];
        if (red[f]) {
            const int m01 = mid.at(key(t[0], t[1])), m12 = mid.at(key(t[1], t[2]));
            const int m20 = mid.at(key(t[2], t[0]));
            out.triangles.push_back({t[0], m01, m20});
            out.triangles.push_back({t[1], m12, m01});
            out.triangles.push_back({t[2], m20, m12});
            out.triangles.push_back({m01, m12, m20});
            continue;
        }
        bool green = false;
        for (int k = 0; k < 3 && !green; ++k) {
            const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
            auto it = mid.find(key(a, b));
            if (it == mid.end()) continue;
            out.triangles.push_back({a, it->second, c});
            out.triangles.push_back({it->second, b, c});
            green = true;
        }
        if (!green) out.triangles.push_back(t);
    }
    out.positions.resize(static_cast<int>(pts.size()), 3);
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) set_row(out.positions, i, pts[i]);
    return out;
}

// Icosphere: an icosahedron subdivided 1-to-4 `levels` times, vertices on the sphere.
inline TriangleMesh icosphere(int levels, double radius = 1.0, const Vec3& center = Vec3::Zero()) {
    TriangleMesh m = icosahedron(radius);
    for (int l = 0; l < levels; ++l)
        m = refine(m, std::vector<char>(m.triangles.size(), 1), radius);
    for (int i = 0; i < m.positions.rows(); ++i)
        set_row(m.positions, i, row(m.positions, i) + center);
    return m;
}

// Sphere with two sampling densities (Fig. 10 of the paper): an icosphere whose faces with a
// centroid above z = 0 get one more 1-to-4 subdivision, with red-green transition triangles.
// Every vertex lies on the sphere.
inline TriangleMesh two_density_sphere(int levels, double radius = 1.0) {
    TriangleMesh m = icosphere(levels, radius);
    std::vector<char> red(m.triangles.size(), 0);
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const Triangle& t = m.triangles[f];
        const double cz = (m.positions(t[0], 2) + m.positions(t[1], 2) + m.positions(t[2], 2)) / 3;
        red[f] = cz > 0 ? 1 : 0;
    }
    return refine(m, red, radius);
}

// Open planar grid of nx x ny quads on [x0, x0+sx] x [y0, y0+sy], z = 0, vertex (i, j) at index
// j*(nx+1)+i. Diagonals: all (i,j)-(i+1,j+1) when rng is null, otherwise chosen at random.
inline int grid_index(int i, int j, int nx) { return j * (nx + 1) + i; }

inline TriangleMesh grid(int nx, int ny, double sx = 1.0, double sy = 1.0, Rng* rng = nullptr,
                         double x0 = 0.0, double y0 = 0.0) {
    TriangleMesh m;
    m.positions.resize((nx + 1) * (ny + 1), 3);
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            set_row(m.positions, grid_index(i, j, nx),
                    Vec3(x0 + sx * i / nx, y0 + sy * j / ny, 0.0));
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const int a = grid_index(i, j, nx), b = grid_index(i + 1, j, nx);
            const int c = grid_index(i + 1, j + 1, nx), d = grid_index(i, j + 1, nx);
            add_quad(m, a, b, c, d, !(rng && rng->uniform() < 0.5));
        }
    }
    return m;
}

// Flat, irregularly triangulated patch in z = 0 on [0,1]^2: graded spacing (cells grow by a
// factor ~4.5 from one side to the other in x and ~2.7 in y), random diagonals, interior vertices
// jittered by up to 20% of the local spacing (no triangle flips).
inline TriangleMesh irregular_plane(int n, std::uint64_t seed = 7) {
    Rng rng(seed);
    TriangleMesh m = grid(n, n, 1.0, 1.0, &rng);
    auto gx = [](double t) { return (std::exp(1.5 * t) - 1.0) / (std::exp(1.5) - 1.0); };
    auto gy = [](double t) { return (std::exp(1.0 * t) - 1.0) / (std::exp(1.0) - 1.0); };
    const double hx = gx(1.0 / n), hy = gy(1.0 / n);  // smallest spacings
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            double x = gx(double(i) / n), y = gy(double(j) / n);
            if (i > 0 && i < n && j > 0 && j < n) {
                x += 0.2 * hx * rng.symmetric();
                y += 0.2 * hy * rng.symmetric();
            }
            set_row(m.positions, grid_index(i, j, n), Vec3(x, y, 0.0));
        }
    }
    return m;
}

// Open grid on [-1,1]^2 with a noisy boundary: boundary vertices get in-plane noise of amplitude
// `boundary_noise` (cell size units) and every vertex a z-noise of `z_noise` (cell size units).
inline TriangleMesh noisy_open_grid(int n, double boundary_noise, double z_noise,
                                    std::uint64_t seed = 11) {
    Rng rng(seed);
    TriangleMesh m = grid(n, n, 2.0, 2.0, &rng, -1.0, -1.0);
    const double h = 2.0 / n;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const int v = grid_index(i, j, n);
            const bool boundary = i == 0 || j == 0 || i == n || j == n;
            if (boundary) {
                m.positions(v, 0) += boundary_noise * h * rng.symmetric();
                m.positions(v, 1) += boundary_noise * h * rng.symmetric();
            }
            m.positions(v, 2) += z_noise * h * rng.symmetric();
        }
    }
    return m;
}

// Closed box [0,size.x]x[0,size.y]x[0,size.z], cells[a] cells along axis a (shared edge
// vertices), outward.
inline TriangleMesh box_cells(const std::array<int, 3>& cells, const Vec3& size) {
    TriangleMesh m;
    std::map<std::array<int, 3>, int> index;
    std::vector<Vec3> pts;
    auto vertex = [&](const std::array<int, 3>& l) {
        auto it = index.find(l);
        if (it != index.end()) return it->second;
        const int id = static_cast<int>(pts.size());
        index[l] = id;
        Vec3 p;
        for (int a = 0; a < 3; ++a) p(a) = size(a) * l[a] / cells[a];
        pts.push_back(p);
        return id;
    };
    // Each side: fixed axis `a` at level 0 or cells[a], (b, c) spanning it with b x c = outward
    // normal.
    for (int a = 0; a < 3; ++a) {
        for (int side = 0; side < 2; ++side) {
            int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b x e_c = +e_a
            if (side == 0) std::swap(b, c);         // -e_a
            for (int i = 0; i < cells[b]; ++i) {
                for (int j = 0; j < cells[c]; ++j) {
                    auto lattice = [&](int di, int dj) {
                        std::array<int, 3> l{};
                        l[a] = side * cells[a];
                        l[b] = i + di;
                        l[c] = j + dj;
                        return vertex(l);
                    };
                    const int p00 = lattice(0, 0), p10 = lattice(1, 0);
                    const int p11 = lattice(1, 1), p01 = lattice(0, 1);
                    m.triangles.push_back({p00, p10, p11});
                    m.triangles.push_back({p00, p11, p01});
                }
            }
        }
    }
    m.positions.resize(static_cast<int>(pts.size()), 3);
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) set_row(m.positions, i, pts[i]);
    return m;
}

// Closed box [0,sx]x[0,sy]x[0,sz], every side an n x n grid (shared edge vertices), outward.
inline TriangleMesh box(int n, double sx = 1.0, double sy = 1.0, double sz = 1.0) {
    return box_cells({{n, n, n}}, Vec3(sx, sy, sz));
}

// Disjoint union: b's vertices come after a's.
inline TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b) {
    TriangleMesh m;
    const int na = static_cast<int>(a.positions.rows());
    m.positions.resize(na + b.positions.rows(), 3);
    m.positions.topRows(na) = a.positions;
    m.positions.bottomRows(b.positions.rows()) = b.positions;
    m.triangles = a.triangles;
    for (Triangle t : b.triangles) m.triangles.push_back({t[0] + na, t[1] + na, t[2] + na});
    return m;
}

// Constraints for "every option" tests: every `stride`-th vertex of n selected (hard), or soft
// weights ramping over 0.3..1 in a fixed pattern.
inline fairing::Constraints every_nth_fixed(int n, int stride) {
    fairing::Constraints c;
    c.fixed.assign(n, 0);
    for (int i = 0; i < n; i += stride) c.fixed[i] = 1;
    return c;
}
inline fairing::Constraints ramped_weights(int n) {
    fairing::Constraints c;
    c.weights.assign(n, 1.0);
    for (int i = 0; i < n; ++i) c.weights[i] = 0.3 + 0.7 * ((i * 7) % 10) / 9.0;
    return c;
}

inline TriangleMesh translated(TriangleMesh m, const Vec3& d) {
    for (int i = 0; i < m.positions.rows(); ++i) set_row(m.positions, i, row(m.positions, i) + d);
    return m;
}

inline TriangleMesh scaled(TriangleMesh m, double s) {
    m.positions *= s;
    return m;
}

// Moves every vertex radially (about `center`) by a relative amount in [-amplitude, amplitude].
inline TriangleMesh radial_noise(TriangleMesh m, double amplitude, std::uint64_t seed = 3,
                                 const Vec3& center = Vec3::Zero()) {
    Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i) {
        const Vec3 p = row(m.positions, i) - center;
        set_row(m.positions, i, center + p * (1.0 + amplitude * rng.symmetric()));
    }
    return m;
}

// Moves every vertex along its direction from `center` by Gaussian noise of standard deviation
// sigma (the study's noise along the normals, on a sphere about its centre).
inline TriangleMesh gaussian_radial_noise(TriangleMesh m, double sigma, std::uint64_t seed = 3,
                                          const Vec3& center = Vec3::Zero()) {
    Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i) {
        const Vec3 p = row(m.positions, i) - center;
        set_row(m.positions, i, center + p + sigma * rng.normal() * p.normalized());
    }
    return m;
}

// Moves every vertex by a random vector with Gaussian coordinates of standard deviation sigma
// (the study's noise "in all directions").
inline TriangleMesh gaussian_isotropic_noise(TriangleMesh m, double sigma, std::uint64_t seed = 3) {
    Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i)
        for (int k = 0; k < 3; ++k) m.positions(i, k) += sigma * rng.normal();
    return m;
}

// Moves every vertex by a random vector with coordinates in [-amplitude, amplitude].
inline TriangleMesh box_noise(TriangleMesh m, double amplitude, std::uint64_t seed = 5) {
    Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i)
        for (int k = 0; k < 3; ++k) m.positions(i, k) += amplitude * rng.symmetric();
    return m;
}

// ------------------------------------------------------------------------------------------
// Independent geometry.

inline std::vector<std::pair<int, int>> edges(const std::vector<Triangle>& tris) {
    std::set<std::pair<int, int>> s;
    for (const Triangle& t : tris)
        for (int k = 0; k < 3; ++k)
            s.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    return {s.begin(), s.end()};
}

inline std::vector<std::set<int>> neighbours(const std::vector<Triangle>& tris, int n) {
    std::vector<std::set<int>> nb(n);
    for (const Triangle& t : tris)
        for (int k = 0; k < 3; ++k) {
            nb[t[k]].insert(t[(k + 1) % 3]);
            nb[t[k]].insert(t[(k + 2) % 3]);
        }
    return nb;
}

inline double mean_edge_length(const Positions& p, const std::vector<Triangle>& tris) {
    const auto e = edges(tris);
    double s = 0;
    for (const auto& ab : e) s += (row(p, ab.first) - row(p, ab.second)).norm();
    return s / static_cast<double>(e.size());
}

inline double triangle_area(const Positions& p, const Triangle& t) {
    return 0.5 * (row(p, t[1]) - row(p, t[0])).cross(row(p, t[2]) - row(p, t[0])).norm();
}

inline double area(const Positions& p, const std::vector<Triangle>& tris) {
    double s = 0;
    for (const Triangle& t : tris) s += triangle_area(p, t);
    return s;
}

// Eq. 10 on coordinates relative to a reference point (the mean of the face vertices), which
// leaves the value of a closed surface unchanged and keeps it accurate far from the origin.
inline double volume(const Positions& p, const std::vector<Triangle>& tris) {
    Vec3 ref = Vec3::Zero();
    for (const Triangle& t : tris) ref += row(p, t[0]);
    ref /= static_cast<double>(tris.size());
    double v = 0;
    for (const Triangle& t : tris) {
        const Vec3 a = row(p, t[0]) - ref, b = row(p, t[1]) - ref, c = row(p, t[2]) - ref;
        v += a.dot(b.cross(c));
    }
    return v / 6.0;
}

// Centroid of the solid bounded by a closed outward surface.
inline Vec3 solid_centroid(const Positions& p, const std::vector<Triangle>& tris) {
    Vec3 ref = Vec3::Zero();
    for (const Triangle& t : tris) ref += row(p, t[0]);
    ref /= static_cast<double>(tris.size());
    Vec3 moment = Vec3::Zero();
    double vol = 0;
    for (const Triangle& t : tris) {
        const Vec3 a = row(p, t[0]) - ref, b = row(p, t[1]) - ref, c = row(p, t[2]) - ref;
        const double v = a.dot(b.cross(c)) / 6.0;
        moment += v * (a + b + c) / 4.0;
        vol += v;
    }
    return ref + moment / vol;
}

// Algebraic least-squares sphere fit |x - c|^2 = rho^2 (exact for points on a sphere).
inline Vec3 fitted_sphere_center(const Positions& p) {
    const int n = static_cast<int>(p.rows());
    Eigen::MatrixXd A(n, 4);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
        A(i, 0) = 2 * p(i, 0);
        A(i, 1) = 2 * p(i, 1);
        A(i, 2) = 2 * p(i, 2);
        A(i, 3) = 1;
        b(i) = row(p, i).squaredNorm();
    }
    const Eigen::Vector4d s = A.colPivHouseholderQr().solve(b);
    return s.head<3>();
}

// (max r - min r) / mean r with r measured from the fitted sphere's center.
inline double radius_spread(const Positions& p) {
    const Vec3 c = fitted_sphere_center(p);
    double lo = 1e300, hi = 0, sum = 0;
    for (int i = 0; i < p.rows(); ++i) {
        const double r = (row(p, i) - c).norm();
        lo = std::min(lo, r);
        hi = std::max(hi, r);
        sum += r;
    }
    return (hi - lo) / (sum / static_cast<double>(p.rows()));
}

// Free flags for n vertices with every k-th one (0, k, 2k, ...) fixed.
inline std::vector<char> every_kth_fixed(int n, int k) {
    std::vector<char> free(n, 1);
    for (int i = 0; i < n; i += k) free[i] = 0;
    return free;
}

// A mesh with its half-edge view and one operator assembled at its positions (solver tests).
struct Assembled {
    TriangleMesh mesh;
    fairing::HalfEdgeMesh he;
    fairing::SparseOperator op;
    double h = 0;  // mean edge length
};

inline Assembled assembled(const TriangleMesh& mesh, fairing::Operator op) {
    Assembled c;
    c.mesh = mesh;
    c.he = fairing::HalfEdgeMesh::build(c.mesh.positions, c.mesh.triangles);
    c.op = fairing::assemble(op, c.he, c.mesh.positions);
    c.h = mean_edge_length(c.mesh.positions, c.mesh.triangles);
    return c;
}

inline double bbox_diagonal(const Positions& p) {
    return (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
}

inline double max_row_distance(const Positions& a, const Positions& b) {
    double d = 0;
    for (int i = 0; i < a.rows(); ++i) d = std::max(d, (a.row(i) - b.row(i)).norm());
    return d;
}

inline bool all_finite(const Positions& p) { return p.allFinite(); }

// Boundary loops recomputed from the triangles: directed boundary edges (those whose reverse is
// no triangle's edge) chained into loops. Returns the loops as vertex sequences.
inline std::vector<std::vector<int>> boundary_loops(const std::vector<Triangle>& tris) {
    std::set<std::pair<int, int>> directed;
    for (const Triangle& t : tris)
        for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
    std::map<int, int> next;
    for (const auto& e : directed)
        if (!directed.count({e.second, e.first})) next[e.first] = e.second;
    std::vector<std::vector<int>> loops;
    std::set<int> seen;
    for (const auto& kv : next) {
        if (seen.count(kv.first)) continue;
        std::vector<int> loop;
        for (int v = kv.first; !seen.count(v); v = next.at(v)) {
            seen.insert(v);
            loop.push_back(v);
        }
        loops.push_back(loop);
    }
    return loops;
}

inline double loop_length(const Positions& p, const std::vector<int>& loop) {
    double s = 0;
    for (size_t k = 0; k < loop.size(); ++k)
        s += (row(p, loop[k]) - row(p, loop[(k + 1) % loop.size()])).norm();
    return s;
}

// ------------------------------------------------------------------------------------------
// Dense views of the engine's sparse operator (for small meshes only).

// K_ij = sum of the CSR weights stored for (i, j), K_ii = -sum of row i's weights.
inline Eigen::MatrixXd dense_k(const fairing::SparseOperator& op) {
    const int n = op.size();
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int e = op.row_start[i]; e < op.row_start[i + 1]; ++e) {
            K(i, op.column[e]) += op.weight[e];
            K(i, i) -= op.weight[e];
        }
    return K;
}

inline Eigen::VectorXd mass_vector(const fairing::SparseOperator& op) {
    Eigen::VectorXd m(op.size());
    for (int i = 0; i < op.size(); ++i) m(i) = op.mass[i];
    return m;
}

inline Eigen::MatrixXd to_dense(const Positions& p) { return Eigen::MatrixXd(p); }

inline Positions to_positions(const Eigen::MatrixXd& m) {
    Positions p(m.rows(), 3);
    p = m;
    return p;
}

// Dense reference for one implicit step as the headers define it (fairing.h, solver.h):
//   order 1: (D - lambda_dt K) X' = D X_old,
//   order 2: (D + lambda_dt K P M^-1 K) X' = D X_old,
//   order p: (D + lambda_dt (-K) (P M^-1 (-K))^(p-1)) X' = D X_old (section 2.6, Figure 3a),
// D_i = M_i / w_i (w = 1 when `weights` is empty). Rows with free[i] == 0 (or w_i == 0) are hard
// constraints: they keep X_old, L(x_i) = 0 there (section 2.7: P zeroes those rows, so
// L^2 = L P L) and their terms move to the right-hand side. Solved with a dense LDLT.
inline Positions dense_implicit_step(const fairing::SparseOperator& op, const Positions& x_old,
                                     double lambda_dt, int order,
                                     const std::vector<double>& weights = {},
                                     const std::vector<char>& free = {}) {
    const int n = op.size();
    const Eigen::MatrixXd K = dense_k(op);
    const Eigen::VectorXd M = mass_vector(op);
    Eigen::VectorXd D = M;
    std::vector<char> is_free(n, 1);
    for (int i = 0; i < n; ++i) {
        if (!free.empty() && !free[i]) is_free[i] = 0;
        if (!weights.empty()) {
            if (weights[i] == 0.0) is_free[i] = 0;
            else D(i) = M(i) / weights[i];
        }
    }
    // A = D + lambda_dt C, C = (-K) (P M^-1 (-K))^(order-1) (order 2: K P M^-1 K).
    Eigen::VectorXd inv = Eigen::VectorXd::Zero(n);  // P M^-1
    for (int i = 0; i < n; ++i)
        if (M(i) > 0 && is_free[i]) inv(i) = 1.0 / M(i);
    Eigen::MatrixXd C = -K;
    for (int p = 2; p <= order; ++p) C = C * inv.asDiagonal() * (-K);
    const Eigen::MatrixXd A = Eigen::MatrixXd(D.asDiagonal()) + lambda_dt * C;
    std::vector<int> f;
    for (int i = 0; i < n; ++i)
        if (is_free[i]) f.push_back(i);
    const int nf = static_cast<int>(f.size());
    Eigen::MatrixXd Aff(nf, nf), rhs(nf, 3);
    const Eigen::MatrixXd X = to_dense(x_old);
    for (int a = 0; a < nf; ++a) {
        rhs.row(a) = D(f[a]) * X.row(f[a]);
        for (int j = 0; j < n; ++j)
            if (!is_free[j]) rhs.row(a) -= A(f[a], j) * X.row(j);
        for (int b = 0; b < nf; ++b) Aff(a, b) = A(f[a], f[b]);
    }
    const Eigen::MatrixXd s = Aff.ldlt().solve(rhs);
    Positions out = x_old;
    for (int a = 0; a < nf; ++a) out.row(f[a]) = s.row(a);
    return out;
}

}  // namespace meshes
