// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Benchmark-only mesh utilities (no engine code): PLY/OFF I/O, generators (jittered torus),
// Loop subdivision, normals, mean edge length, volume, and a uniform-grid closest-point query on
// a triangle soup (for the vertex-to-surface error). Header-only, C++17.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace bench {

using V3 = std::array<double, 3>;
using T3 = std::array<int, 3>;

struct Mesh {
    std::vector<V3> v;
    std::vector<T3> f;
};

inline V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 mul(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }

// ---------------------------------------------------------------- I/O
namespace detail {
inline int type_size(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    throw std::runtime_error("PLY: unknown type " + t);
}
inline double read_bin(const char* p, const std::string& t) {
    if (t == "char" || t == "int8") return *reinterpret_cast<const int8_t*>(p);
    if (t == "uchar" || t == "uint8") return *reinterpret_cast<const uint8_t*>(p);
    int16_t s; uint16_t us; int32_t i; uint32_t ui; float fl; double d;
    if (t == "short" || t == "int16") { std::memcpy(&s, p, 2); return s; }
    if (t == "ushort" || t == "uint16") { std::memcpy(&us, p, 2); return us; }
    if (t == "int" || t == "int32") { std::memcpy(&i, p, 4); return i; }
    if (t == "uint" || t == "uint32") { std::memcpy(&ui, p, 4); return ui; }
    if (t == "float" || t == "float32") { std::memcpy(&fl, p, 4); return fl; }
    std::memcpy(&d, p, 8);
    return d;
}
struct Prop {
    std::string name, type, count_type;  // count_type non-empty: list
};
struct Element {
    std::string name;
    long long count = 0;
    std::vector<Prop> props;
};
}  // namespace detail

inline Mesh read_ply(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line, format;
    std::vector<detail::Element> elems;
    std::getline(in, line);
    if (line.rfind("ply", 0) != 0) throw std::runtime_error(path + ": not a PLY file");
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream s(line);
        std::string w;
        s >> w;
        if (w == "format") s >> format;
        else if (w == "element") {
            detail::Element e;
            s >> e.name >> e.count;
            elems.push_back(e);
        } else if (w == "property") {
            detail::Prop p;
            std::string t;
            s >> t;
            if (t == "list") s >> p.count_type >> p.type >> p.name;
            else { p.type = t; s >> p.name; }
            elems.back().props.push_back(p);
        } else if (w == "end_header") break;
    }
    Mesh m;
    const bool ascii = format == "ascii";
    if (!ascii && format != "binary_little_endian")
        throw std::runtime_error(path + ": unsupported PLY format " + format);
    std::vector<char> buf(64);
    for (const auto& e : elems) {
        const bool isv = e.name == "vertex", isf = e.name == "face";
        if (isv) m.v.resize(e.count);
        if (isf) m.f.reserve(e.count);
        for (long long k = 0; k < e.count; ++k) {
            for (const auto& p : e.props) {
                if (p.count_type.empty()) {
                    double val;
                    if (ascii) in >> val;
                    else {
                        const int sz = detail::type_size(p.type);
                        in.read(buf.data(), sz);
                        val = detail::read_bin(buf.data(), p.type);
                    }
                    if (isv) {
                        if (p.name == "x") m.v[k][0] = val;
                        else if (p.name == "y") m.v[k][1] = val;
                        else if (p.name == "z") m.v[k][2] = val;
                    }
                } else {
                    double cnt;
                    if (ascii) in >> cnt;
                    else {
                        in.read(buf.data(), detail::type_size(p.count_type));
                        cnt = detail::read_bin(buf.data(), p.count_type);
                    }
                    std::vector<int> idx(static_cast<size_t>(cnt));
                    for (auto& x : idx) {
                        double val;
                        if (ascii) in >> val;
                        else {
                            in.read(buf.data(), detail::type_size(p.type));
                            val = detail::read_bin(buf.data(), p.type);
                        }
                        x = static_cast<int>(val);
                    }
                    if (isf && (p.name == "vertex_indices" || p.name == "vertex_index"))
                        for (size_t t = 1; t + 1 < idx.size(); ++t) m.f.push_back({idx[0], idx[t], idx[t + 1]});
                }
            }
        }
        if (!in) throw std::runtime_error(path + ": truncated PLY");
    }
    return m;
}

inline Mesh read_off(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string tok;
    in >> tok;
    if (tok != "OFF") throw std::runtime_error(path + ": not an OFF file");
    long long nv, nf, ne;
    in >> nv >> nf >> ne;
    Mesh m;
    m.v.resize(nv);
    for (auto& p : m.v) in >> p[0] >> p[1] >> p[2];
    for (long long k = 0; k < nf; ++k) {
        int n;
        in >> n;
        std::vector<int> idx(n);
        for (auto& x : idx) in >> x;
        for (int t = 1; t + 1 < n; ++t) m.f.push_back({idx[0], idx[t], idx[t + 1]});
    }
    if (!in) throw std::runtime_error(path + ": truncated OFF");
    return m;
}

inline Mesh read_mesh(const std::string& path) {
    const auto dot = path.rfind('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    for (auto& c : ext) c = static_cast<char>(std::tolower(c));
    if (ext == "off") return read_off(path);
    return read_ply(path);
}

// The mesh as the float hosts see it (MeshLab 2020.09, PLY read as float): every peer and our
// sweep start from the same rounded coordinates.
inline Mesh read_mesh_as_float(const std::string& path) {
    Mesh m = read_mesh(path);
    for (auto& p : m.v)
        for (auto& c : p) c = double(float(c));
    return m;
}

// Binary little-endian PLY, double coordinates (float when as_float: MeshLab 2020 reads both).
inline void write_ply(const std::string& path, const Mesh& m, bool as_float = false) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + path);
    const char* t = as_float ? "float" : "double";
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.v.size() << "\nproperty "
        << t << " x\nproperty " << t << " y\nproperty " << t << " z\nelement face " << m.f.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : m.v) {
        if (as_float) {
            float q[3] = {float(p[0]), float(p[1]), float(p[2])};
            out.write(reinterpret_cast<const char*>(q), sizeof q);
        } else out.write(reinterpret_cast<const char*>(p.data()), 24);
    }
    for (const auto& f : m.f) {
        const unsigned char n = 3;
        out.write(reinterpret_cast<const char*>(&n), 1);
        out.write(reinterpret_cast<const char*>(f.data()), 12);
    }
    if (!out) throw std::runtime_error("write failed: " + path);
}

// ---------------------------------------------------------------- measures
inline double mean_edge(const Mesh& m) {
    double s = 0;
    long long c = 0;
    for (const auto& f : m.f)
        for (int k = 0; k < 3; ++k) {  // each interior edge twice: same mean on closed meshes
            s += norm(sub(m.v[f[(k + 1) % 3]], m.v[f[k]]));
            ++c;
        }
    return c ? s / double(c) : 0;
}

inline double volume(const Mesh& m) {
    V3 o = {0, 0, 0};
    for (const auto& p : m.v) o = add(o, p);
    if (!m.v.empty()) o = mul(o, 1.0 / double(m.v.size()));
    double s = 0;
    for (const auto& f : m.f)
        s += dot(sub(m.v[f[0]], o), cross(sub(m.v[f[1]], o), sub(m.v[f[2]], o)));
    return s / 6.0;
}

// Area-weighted vertex normals, unit length.
inline std::vector<V3> vertex_normals(const Mesh& m) {
    std::vector<V3> n(m.v.size(), V3{0, 0, 0});
    for (const auto& f : m.f) {
        const V3 fn = cross(sub(m.v[f[1]], m.v[f[0]]), sub(m.v[f[2]], m.v[f[0]]));
        for (int k = 0; k < 3; ++k) n[f[k]] = add(n[f[k]], fn);
    }
    for (auto& x : n) {
        const double l = norm(x);
        if (l > 0) x = mul(x, 1.0 / l);
    }
    return n;
}

// ---------------------------------------------------------------- generators
// Torus (R = 1, r = 0.4) on an nu x nv grid, vertices jittered in parameter space by up to
// +-0.3 cell and each quad split along a random diagonal: irregular, closed, genus 1.
inline Mesh torus(int nu, int nv, unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jit(-0.3, 0.3);
    std::bernoulli_distribution coin(0.5);
    const double R = 1.0, r = 0.4, pi = 3.14159265358979323846;
    Mesh m;
    m.v.reserve(size_t(nu) * nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * pi * (i + jit(rng)) / nu, w = 2 * pi * (j + jit(rng)) / nv;
            m.v.push_back({(R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u),
                           r * std::sin(w)});
        }
    auto id = [&](int i, int j) { return ((i % nu) * nv) + (j % nv); };
    m.f.reserve(size_t(2) * nu * nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (coin(rng)) { m.f.push_back({a, b, c}); m.f.push_back({a, c, d}); }
            else { m.f.push_back({a, b, d}); m.f.push_back({b, c, d}); }
        }
    return m;
}

// Torus with about `faces` faces (aspect 2:1).
inline Mesh torus_faces(long long faces, unsigned seed = 7) {
    const int nv = std::max(3, int(std::lround(std::sqrt(double(faces) / 4.0))));
    return torus(2 * nv, nv, seed);
}

// An undirected edge as one integer (the smaller index in the high half).
inline uint64_t edge_key(int a, int b) { return (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b)); }

// The 1-to-4 split of every face of m into out.f, edge_vertex(a, b) giving the new vertex on
// edge ab (called for each face's edges in order ab, bc, ca).
template <class EdgeVertex>
void split_faces_1_to_4(const Mesh& m, EdgeVertex&& edge_vertex, Mesh& out) {
    out.f.reserve(m.f.size() * 4);
    for (const auto& f : m.f) {
        const int e0 = edge_vertex(f[0], f[1]), e1 = edge_vertex(f[1], f[2]), e2 = edge_vertex(f[2], f[0]);
        out.f.push_back({f[0], e0, e2});
        out.f.push_back({f[1], e1, e0});
        out.f.push_back({f[2], e2, e1});
        out.f.push_back({e0, e1, e2});
    }
}

// Loop subdivision (one level). Boundary edges get the midpoint and boundary vertices stay put
// (the benchmark meshes are closed).
inline Mesh loop_subdivide(const Mesh& m) {
    const int n = int(m.v.size());
    std::unordered_map<uint64_t, int> edge_vertex;
    edge_vertex.reserve(m.f.size() * 2);
    // opposite corners per edge
    std::unordered_map<uint64_t, std::array<int, 2>> opp;
    opp.reserve(m.f.size() * 2);
    for (const auto& f : m.f)
        for (int k = 0; k < 3; ++k) {
            auto it = opp.find(edge_key(f[k], f[(k + 1) % 3]));
            if (it == opp.end()) opp.emplace(edge_key(f[k], f[(k + 1) % 3]), std::array<int, 2>{f[(k + 2) % 3], -1});
            else it->second[1] = f[(k + 2) % 3];
        }
    Mesh out;
    out.v.resize(n);
    std::vector<V3> nsum(n, V3{0, 0, 0});
    std::vector<int> val(n, 0);
    std::vector<char> boundary(n, 0);
    for (const auto& [k, o] : opp) {
        const int a = int(k >> 32), b = int(k & 0xffffffffu);
        nsum[a] = add(nsum[a], m.v[b]);
        nsum[b] = add(nsum[b], m.v[a]);
        ++val[a];
        ++val[b];
        if (o[1] < 0) boundary[a] = boundary[b] = 1;
    }
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < n; ++i) {
        if (boundary[i] || val[i] == 0) { out.v[i] = m.v[i]; continue; }
        const double k = val[i];
        const double c = 3.0 / 8.0 + 0.25 * std::cos(2 * pi / k);
        const double beta = (5.0 / 8.0 - c * c) / k;  // Loop's original weights
        out.v[i] = add(mul(m.v[i], 1 - k * beta), mul(nsum[i], beta));
    }
    for (const auto& [k, o] : opp) {
        const int a = int(k >> 32), b = int(k & 0xffffffffu);
        V3 p;
        if (o[1] < 0) p = mul(add(m.v[a], m.v[b]), 0.5);
        else p = add(mul(add(m.v[a], m.v[b]), 3.0 / 8.0), mul(add(m.v[o[0]], m.v[o[1]]), 1.0 / 8.0));
        edge_vertex[k] = int(out.v.size());
        out.v.push_back(p);
    }
    split_faces_1_to_4(m, [&](int a, int b) { return edge_vertex[edge_key(a, b)]; }, out);
    return out;
}

// Midpoint subdivision (one level): every triangle split 1-to-4 at its edge midpoints, no
// vertex moved, so each child is similar to its parent and a raw scan keeps its triangle shapes
// (its obtuse and thin triangles) at four times the faces, where Loop subdivision evens them
// out.
inline Mesh midpoint_subdivide(const Mesh& m) {
    std::unordered_map<uint64_t, int> edge_vertex;
    edge_vertex.reserve(m.f.size() * 2);
    Mesh out;
    out.v = m.v;
    split_faces_1_to_4(m, [&](int a, int b) {
        const auto [it, added] = edge_vertex.emplace(edge_key(a, b), int(out.v.size()));
        if (added) out.v.push_back(mul(add(m.v[a], m.v[b]), 0.5));
        return it->second;
    }, out);
    return out;
}

// Gaussian noise of sigma (absolute) along the vertex normals.
inline Mesh add_normal_noise(const Mesh& m, double sigma, unsigned seed = 1) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, sigma);
    const auto n = vertex_normals(m);
    Mesh out = m;
    for (size_t i = 0; i < m.v.size(); ++i) out.v[i] = add(m.v[i], mul(n[i], g(rng)));
    return out;
}

// ---------------------------------------------------------------- closest point on triangles
inline double point_triangle_dist2(const V3& p, const V3& a, const V3& b, const V3& c) {
    // Ericson, Real-Time Collision Detection, 5.1.5.
    const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    auto d2of = [&](const V3& q) { const V3 d = sub(p, q); return dot(d, d); };
    if (d1 <= 0 && d2 <= 0) return d2of(a);
    const V3 bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return d2of(b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return d2of(add(a, mul(ab, d1 / (d1 - d3))));
    const V3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return d2of(c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return d2of(add(a, mul(ac, d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return d2of(add(b, mul(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denom = 1.0 / (va + vb + vc);
    return d2of(add(a, add(mul(ab, vb * denom), mul(ac, vc * denom))));
}

// Uniform grid over the triangles' bounding boxes; exact nearest distance by growing shells.
class SurfaceGrid {
public:
    SurfaceGrid(const Mesh& m, double cell) : m_(m), cell_(cell) {
        lo_ = {1e300, 1e300, 1e300};
        V3 hi = {-1e300, -1e300, -1e300};
        for (const auto& p : m.v)
            for (int k = 0; k < 3; ++k) { lo_[k] = std::min(lo_[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
        for (int k = 0; k < 3; ++k) dim_[k] = std::max(1, int((hi[k] - lo_[k]) / cell_) + 1);
        start_.assign(size_t(dim_[0]) * dim_[1] * dim_[2] + 1, 0);
        for (int pass = 0; pass < 2; ++pass) {
            std::vector<int> fill;
            if (pass == 1) {
                for (size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
                items_.resize(start_.back());
                fill.assign(start_.begin(), start_.end() - 1);
            }
            for (int t = 0; t < int(m.f.size()); ++t) {
                int a[3], b[3];
                for (int k = 0; k < 3; ++k) {
                    double mn = 1e300, mx = -1e300;
                    for (int c = 0; c < 3; ++c) { mn = std::min(mn, m.v[m.f[t][c]][k]); mx = std::max(mx, m.v[m.f[t][c]][k]); }
                    a[k] = clampi(int((mn - lo_[k]) / cell_), k);
                    b[k] = clampi(int((mx - lo_[k]) / cell_), k);
                }
                for (int x = a[0]; x <= b[0]; ++x)
                    for (int y = a[1]; y <= b[1]; ++y)
                        for (int z = a[2]; z <= b[2]; ++z) {
                            const size_t c = (size_t(x) * dim_[1] + y) * dim_[2] + z;
                            if (pass == 0) ++start_[c + 1];
                            else items_[fill[c]++] = t;
                        }
            }
        }
    }
    double distance(const V3& p) const {
        int c[3];
        for (int k = 0; k < 3; ++k) c[k] = clampi(int((p[k] - lo_[k]) / cell_), k);
        double best = 1e300;
        const int maxr = std::max(dim_[0], std::max(dim_[1], dim_[2]));
        for (int r = 0; r <= maxr; ++r) {
            for (int x = c[0] - r; x <= c[0] + r; ++x)
                for (int y = c[1] - r; y <= c[1] + r; ++y)
                    for (int z = c[2] - r; z <= c[2] + r; ++z) {
                        if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;
                        if (x < 0 || y < 0 || z < 0 || x >= dim_[0] || y >= dim_[1] || z >= dim_[2]) continue;
                        const size_t cc = (size_t(x) * dim_[1] + y) * dim_[2] + z;
                        for (int k = start_[cc]; k < start_[cc + 1]; ++k) {
                            const T3& t = m_.f[items_[k]];
                            best = std::min(best, point_triangle_dist2(p, m_.v[t[0]], m_.v[t[1]], m_.v[t[2]]));
                        }
                    }
            // Every unvisited cell is at least r * cell away (p may lie outside the grid: clamp).
            double outside = 0;
            for (int k = 0; k < 3; ++k) {
                const double lo = lo_[k], hi = lo_[k] + dim_[k] * cell_;
                if (p[k] < lo) outside = std::max(outside, lo - p[k]);
                if (p[k] > hi) outside = std::max(outside, p[k] - hi);
            }
            const double reach = r * cell_ + outside * 0;  // conservative
            if (best < 1e300 && std::sqrt(best) <= reach) break;
        }
        return std::sqrt(best);
    }

private:
    int clampi(int v, int k) const { return std::min(std::max(v, 0), dim_[k] - 1); }
    const Mesh& m_;
    double cell_;
    V3 lo_;
    int dim_[3];
    std::vector<int> start_, items_;
};

}  // namespace bench
