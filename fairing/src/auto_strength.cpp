// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "auto_strength.h"
#include "fairing/invariants.h"

#include "fairing/solver.h"
#include "geometry.h"
#include "kernels.h"
#include "lanczos_filter.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>

namespace fairing {
namespace detail {

Positions robust_normals(const HalfEdgeMesh& mesh, const Positions& x) {
    const Positions area = area_normal_sums(mesh, x);
    // Averaging over the one-ring tames the noise's tilt of the normals (a quarter-edge noise
    // tilts single-face normals by ~15 degrees), which would otherwise leak tangential sliding
    // into the normal residual.
    Positions smooth = area;
    for (const Triangle& t : mesh.faces()) {
        const Eigen::RowVector3d sum = area.row(t[0]) + area.row(t[1]) + area.row(t[2]);
        for (int k = 0; k < 3; ++k) smooth.row(t[k]) += sum;
    }
    normalize_rows(smooth);
    return smooth;
}

namespace {

// x moved `passes` times halfway to the mean of its one-ring, neighbour k weighted by weight(k).
template <class Weight>
Positions lazy_passes(const SparseOperator& op, const Positions& x, int data, int passes,
                      const Weight& weight) {
    Positions a = x.topRows(data), b(data, 3);
    for (int pass = 0; pass < passes; ++pass) {
        for (int i = 0; i < data; ++i) {
            Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
            double total = 0;
            for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
                if (op.column[k] < data) {
                    const double w = weight(k);
                    sum += w * a.row(op.column[k]);
                    total += w;
                }
            b.row(i) = total > 0 ? Eigen::RowVector3d(0.5 * a.row(i) + 0.5 * sum / total)
                                 : a.row(i);
        }
        a.swap(b);
    }
    return a;
}

}  // namespace

Positions smoothed_copy(const SparseOperator& op, const Positions& x, int data, int passes) {
    return lazy_passes(op, x, data, passes, [](int) { return 1.0; });
}

Positions smoothed_copy_weighted(const SparseOperator& op, const Positions& x, int data,
                                 int passes) {
    return lazy_passes(op, x, data, passes, [&op](int k) {
        return op.unit_weights ? 1.0 : std::max(0.0, op.weight[static_cast<std::size_t>(k)]);
    });
}

namespace {

// Number of neighbours of i among the data vertices.
int valence(const SparseOperator& op, int i, int data) {
    int m = 0;
    for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k) m += op.column[k] < data;
    return m;
}

// Median of |v - median(v)| (v is reordered).
double median_absolute_deviation(std::vector<double>& v) {
    if (v.empty()) return 0;
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    const double median = *middle;
    for (double& a : v) a = std::abs(a - median);
    std::nth_element(v.begin(), middle, v.end());
    return *middle;
}

// types[k] is the combinatorial type of the vertex of values[k] (vertex_type).
struct NormalizedValues {
    std::vector<double> values;
    std::vector<std::uint64_t> types;
};

// A vertex's combinatorial type: its valence and how many of its neighbours have each valence
// (3 or less, 4 ... 9, 10 or more), packed exactly up to 63 neighbours per class.
std::uint64_t vertex_type(const SparseOperator& op, const std::vector<int>& valences, int i,
                          int n) {
    std::array<int, 8> classes{};
    for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
        if (op.column[k] < n) ++classes[static_cast<std::size_t>(
                                  std::min(std::max(valences[op.column[k]], 3), 10) - 3)];
    std::uint64_t type = static_cast<std::uint64_t>(std::min(valences[i], 255));
    for (int c : classes) type = (type << 6) | static_cast<std::uint64_t>(std::min(c, 63));
    return type;
}

// The normal component of the uniform bi-Laplacian at every vertex whose two-ring is interior,
// divided by the norm of its stencil (so every value has the noise's variance), for vertices
// with use[i] (all when `use` is empty), each with its vertex's type.
NormalizedValues normalized_bilaplacian(const SparseOperator& op, const HalfEdgeMesh& mesh,
                                        const Positions& x, const Positions& normals,
                                        const std::vector<char>& use, bool strict) {
    const int n = mesh.num_vertices();
    std::vector<int> m(n);
    Positions lx(n, 3);
    for (int i = 0; i < n; ++i) {
        m[i] = valence(op, i, n);
        Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
        for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
            if (op.column[k] < n) sum += x.row(op.column[k]);
        lx.row(i) = m[i] > 0 ? Eigen::RowVector3d(sum / m[i] - x.row(i)) : Eigen::RowVector3d::Zero();
    }
    const auto interior = [&](int i) { return m[i] >= 3 && !mesh.is_boundary_vertex(i); };
    std::vector<double> coef(n, 0.0);
    NormalizedValues out;
    std::vector<char> listed(n, 0);
    std::vector<int> touched;
    const auto add = [&](int j, double c) {
        if (!listed[j]) touched.push_back(j);
        listed[j] = 1;
        coef[j] += c;
    };
    for (int i = 0; i < n; ++i) {
        if ((!use.empty() && !use[i]) || !interior(i) || normals.row(i).squaredNorm() == 0) continue;
        bool ok = true;
        for (int k = op.row_start[i]; k < op.row_start[i + 1] && ok; ++k)
            ok = op.column[k] < n && (!strict || interior(op.column[k]));
        if (!ok) continue;
        // Row i of L^2 = L (L x), L = A - I, A_ij = 1/m_i on the one-ring:
        // e_i - sum_j (2/m_i) e_j + sum_j sum_{k ~ j} e_k / (m_i m_j).
        Eigen::RowVector3d bilaplacian = -lx.row(i);
        add(i, 1.0);
        for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k) {
            const int j = op.column[k];
            bilaplacian += lx.row(j) / m[i];
            add(j, -2.0 / m[i]);
            for (int l = op.row_start[j]; l < op.row_start[j + 1]; ++l)
                if (op.column[l] < n) add(op.column[l], 1.0 / (static_cast<double>(m[i]) * m[j]));
        }
        double norm2 = 0;
        for (int j : touched) {
            norm2 += coef[j] * coef[j];
            coef[j] = 0;
            listed[j] = 0;
        }
        touched.clear();
        if (norm2 > 0) {
            out.values.push_back(normals.row(i).dot(bilaplacian) / std::sqrt(norm2));
            out.types.push_back(vertex_type(op, m, i, n));
        }
    }
    return out;
}

// Median of |v - the median of v's stratum| (v is reordered). A stratum holds the values of one
// vertex type (vertex_type) when at least kStratum share it, else of one valence, else all the
// rest together.
double stratified_median_absolute_deviation(NormalizedValues& nv) {
    constexpr int kStratum = 64;
    std::vector<double>& v = nv.values;
    std::vector<std::uint64_t>& key = nv.types;
    const auto pool = [&key](const auto& coarser) {
        std::unordered_map<std::uint64_t, int> count;
        for (std::uint64_t k : key) ++count[k];
        for (std::uint64_t& k : key)
            if (count[k] < kStratum) k = coarser(k);
    };
    // A type fills bits 0-55 (its valence bits 48-55); the coarser keys set bit 62 or bit 63, so
    // they meet no type.
    pool([](std::uint64_t k) { return (std::uint64_t{1} << 62) | (k >> 48); });
    pool([](std::uint64_t) { return std::uint64_t{1} << 63; });
    std::unordered_map<std::uint64_t, std::size_t> id;
    for (std::uint64_t k : key) id.emplace(k, id.size());
    std::vector<std::size_t> start(id.size() + 1, 0);
    for (std::uint64_t k : key) ++start[id[k] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<double> grouped(v.size());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < v.size(); ++k) grouped[next[id[key[k]]]++] = v[k];
    v.clear();
    for (std::size_t g = 0; g + 1 < start.size(); ++g) {
        const auto first = grouped.begin() + static_cast<std::ptrdiff_t>(start[g]);
        const auto last = grouped.begin() + static_cast<std::ptrdiff_t>(start[g + 1]);
        const auto middle = first + (last - first) / 2;
        std::nth_element(first, middle, last);
        const double median = *middle;
        for (auto a = first; a != last; ++a) v.push_back(*a - median);
    }
    return median_absolute_deviation(v);
}

}  // namespace

double estimate_noise(const SparseOperator& op, const HalfEdgeMesh& mesh, const Positions& x,
                      const Positions& normals, const std::vector<char>& use) {
    // Too few qualifying vertices for a median: widen the set rather than guess.
    constexpr std::size_t kEnough = 16;
    NormalizedValues v = normalized_bilaplacian(op, mesh, x, normals, use, true);
    if (v.values.size() < kEnough) v = normalized_bilaplacian(op, mesh, x, normals, {}, true);
    if (v.values.size() < kEnough) v = normalized_bilaplacian(op, mesh, x, normals, {}, false);
    return 1.482602218505602 * stratified_median_absolute_deviation(v);
}

namespace {

// The filter of `steps` steps of lambda each (fair() gives every step the whole time step).
struct Filter {
    double lambda = 0;
    int steps = 1;
    bool explicit_steps = false;
    int power = 1;  // > 1: T is the first-order G1 and the filter's G = G1^power (see Context)
};

// Three independent Lanczos processes on G (one per column), in the coordinates q = D^-1/2 v,
// where G v = D^-1/2 C q and the inner product is <a, b>_D = sum_free D_i a_i b_i. Never more
// than two basis vectors are kept. The product with the operator lives only within a step, so
// the processes, which step in turn, share one (search()).
struct Lanczos {
    Positions previous, current;
    std::array<std::vector<double>, 3> alpha, beta;  // beta[j] joins basis vectors j and j+1
    std::array<double, 3> start_norm{{0, 0, 0}};
    std::array<bool, 3> active{{true, true, true}};
    // With `pending`, current holds the next basis vector before its last two operations: the
    // pass that reads it first (Sketch::add) makes it (current - shift previous) * scale on the
    // free rows (0 elsewhere), as advance() would have, and so saves a pass over it. advance()
    // leaves shift at 0; step_pair() leaves alpha there (it never forms the vector at all).
    bool pending = false;
    std::array<double, 3> scale{{0, 0, 0}}, shift{{0, 0, 0}};
};

struct Context {
    const StrengthProblem& p;
    LinearSystem c;           // lambda_dt = length_unit, no diagonal (D = 0): apply() is unit * C
    std::vector<char> data;   // free data rows: they count in the risk and the trace
    Positions scratch;
    int n = 0;
    // L^2 with D = M (no soft weights): on the free rows K P M^-1 K = C1 M^-1 C1, so the L^2
    // filter's G is G1^2 with G1 = M^-1/2 C1 M^-1/2 (C1 = -K, unit (mean edge)^2). The Lanczos
    // processes then run on G1: one product with K per step instead of two, and as many steps
    // as the filter's poles at +-i/sqrt(lambda) need instead of those of the pole of
    // (1 + lambda g)^-1 on the squared spectrum (umbrella L^2 on the 1.2 M-face bunny: 78
    // Lanczos steps). The same for L^p, p = 3 or 4 (the paper's Figure 3a): G = G1^p, the
    // filter's poles at the p-th roots of -1/lambda (lanczos_filter.h).
    bool squared = false;
    // With soft weights (D = M/w) the L^2 filter's G = W^1/2 G1^2 W^1/2 is no square; it is
    // modelled as G~^2, G~ = W^1/4 G1 W^1/4 (exact for uniform weights, and up to the commutator
    // of G1 with the weights' variation otherwise), so that these problems keep the G1 path.
    // On the L^2 operator itself the processes converged so slowly that the curvature flow on
    // CGAL's camel and on the 1.2 M-face bunny reached the step cap before the time steps that
    // matter. Measured (bench/results/issue11/auto-gap.md §6): uniform weights give the
    // unweighted choice exactly; weights varying along the mesh give the converged L^2
    // process's choice within 4 % on scans, but on the sphere and the torus, whose best steps
    // act on the smoothest modes where the commutator is not small, a 4-11x weaker one: such
    // choices are redone on G itself (kWeightModelKeeps). Per row w^-1/4 (L^p: G~ = W^1/(2p)
    // G1 W^1/(2p), w^-1/(2p); empty: no soft weights).
    std::vector<double> weight_root;
    Positions scaled;  // scratch for the product with G~
};

// D_i = M_i / w_i of a free row, computed where needed rather than kept (8 bytes per vertex and
// process): the same division gives the same bits every time.
double d_of(const StrengthProblem& p, int i) {
    return p.weight && i < p.data_vertices ? p.op->mass[i] / (*p.weight)[i] : p.op->mass[i];
}

Filter filter_at(const Context& ctx, double lambda) {
    return Filter{lambda, ctx.p.steps, ctx.p.explicit_integration, ctx.squared ? ctx.p.order : 1};
}

// product = unit * C current (with Context::weight_root: W^-1/4 C1 W^-1/4 current); returns
// alpha = <current, D^-1 product>_D per column.
std::array<double, 3> multiply(Context& ctx, Lanczos& l, Positions& product) {
    if (ctx.weight_root.empty()) return ctx.c.apply_dot(l.current, product, ctx.scratch);
    const int n = ctx.n;
    ctx.scaled.resize(n, 3);
    const double* root = ctx.weight_root.data();
    const double* cur = l.current.data();
    double* scaled = ctx.scaled.data();
    const int threads = ctx.p.op->threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) scaled[3 * i + c] = root[i] * cur[3 * i + c];
    const std::array<double, 3> dot = ctx.c.apply_dot(ctx.scaled, product, ctx.scratch);
    double* prod = product.data();
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) prod[3 * i + c] *= root[i];
    return dot;
}

// beta_j^2 of every active column, measured: stores beta_j and the division by it (the vector
// is left pending, Lanczos::pending); a column whose beta_j vanishes against alpha_j and
// beta_{j-1} has broken down (its Krylov space is exhausted: T_k is exact) and stops.
void finish_step(Lanczos& l, int j, const std::array<double, 3>& squared) {
    for (int c = 0; c < 3; ++c) {
        l.scale[c] = 0;
        if (!l.active[c]) continue;
        const double a = l.alpha[c][j], b = j > 0 ? l.beta[c][j - 1] : 0.0;
        const double norm = std::sqrt(squared[c]);  // NaN for a rounded negative: breakdown
        if (!(norm > 1e-13 * (std::abs(a) + b))) {
            l.active[c] = false;
            continue;
        }
        l.beta[c].push_back(norm);
        l.scale[c] = 1.0 / norm;
    }
    l.pending = true;
}

// Forms the pending vector's numerator current - shift previous (Lanczos::pending) and returns its
// squared D-norm per column; the division by beta stays pending.
std::array<double, 3> measure_pending(const Context& ctx, Lanczos& l) {
    const StrengthProblem& p = ctx.p;
    const char* f = p.free->data();
    double* w = l.current.data();
    const double* v = l.previous.data();
    const std::array<double, 3> shift = l.shift;
    l.shift = std::array<double, 3>{{0, 0, 0}};
    return blocked_sum<3>(ctx.n, p.op->threads, [=, &p](int i, double* acc) {
        if (!f[i]) return;
        const double d = d_of(p, i);
        for (int c = 0; c < 3; ++c) {
            w[3 * i + c] -= shift[c] * v[3 * i + c];
            acc[c] += d * w[3 * i + c] * w[3 * i + c];
        }
    });
}

// step_pair() measures beta_j directly when its expansion keeps less than this share of |w'|^2
// (about 5 of the 16 digits lost; the expansion's rounding is then ~1e-11 of beta_j^2).
constexpr double kCancelled = 1e-5;

// One Lanczos step of two processes on first-order operators of the same sparsity pattern,
// without soft weights, in one pass over the pattern: the movement and the Hutchinson probes of
// a linear operator (one operator), or the movement and the Monte-Carlo perturbed movement (the
// operators at the data and at the perturbed data: the same rows and columns, other weights).
// Each row's columns are read once, from `ca`'s operator (a second k_row on the same operator
// finds its entries cached). The product y = unit C v is never stored: the pass writes
// w' = y / d - beta_{j-1} v_{j-1} over v_{j-1} and sums what the next vector
// (w' - alpha_j v_j) / beta_j needs, beta_j^2 = |w'|^2 - 2 alpha_j <w', v_j> + alpha_j^2 |v_j|^2
// (D-inner products), so advance()'s pass over four vectors per process is gone; the vector is
// formed where it is first read (Lanczos::pending). The expansion cancels when beta_j is small
// against |w'|: then the vector is formed and measured directly (measure_pending()).
// With three processes (the later steps' movement beside them, see search()) the third reads
// its own weights along the same columns, or, with a Blend, forms them from two operators' (the
// mean's and the first step's, which the pass reads anyway: the later operator's weights need
// not be kept).
struct Blend {
    const double* a = nullptr;
    const double* b = nullptr;
    double ca = 0, cb = 0;
    double operator[](int e) const { return ca * a[e] + cb * b[e]; }
};

// What step_group's pass reads and writes of one process, and the rows it shares.
struct ProcessRows {
    const double* x;         // v_j
    double* w;               // v_{j-1}, overwritten by w'
    const double* diagonal;  // D of A = D - lambda_dt K, or null (0)
    const double* mass;
    const double* soft;  // soft weights of the data rows, or null
    int data;            // data rows
    double scale;        // -lambda_dt
    double beta[3];      // beta_{j-1} per column (0 for j = 0 or an inactive column)
    const char* free;
    const int* start;
    const int* column;
    // D_i of a free row (d_of(), from the arrays).
    double d(int i) const { return soft && i < data ? mass[i] / soft[i] : mass[i]; }
};

// Rows [first, end) of process r: w' = y / d - beta_{j-1} v_{j-1} over v_{j-1}, with y = A v_j
// (unit C v_j), and their shares of the sums acc (alpha, |w'|^2, <w', v>, |v|^2 per column),
// each sum in row order. One process at a time over a block keeps its twelve sums in
// registers (through memory, per row, they took a load and a store each).
template <class Weights>
void process_rows(const ProcessRows& r, const Weights& weight, int first, int end, double* acc) {
    for (int i = first; i < end; ++i) {
        double s0, s1, s2, y[3];
        k_row_with(i, r.x, r.start, r.column, weight, s0, s1, s2);
        const double* x = r.x + 3 * i;
        system_row(r.diagonal ? r.diagonal[i] : 0.0, r.scale, x, s0, s1, s2, r.free[i] != 0, y,
                   acc);
        if (!r.free[i]) continue;
        const double d = r.d(i);
        const double xc[3] = {x[0], x[1], x[2]};  // read before w is written: no alias to fear
        double* w = r.w + 3 * i;
        for (int c = 0; c < 3; ++c) {
            const double wc = y[c] / d - r.beta[c] * w[c];
            w[c] = wc;
            acc[3 + c] += d * wc * wc;
            acc[6 + c] += d * wc * xc[c];
            acc[9 + c] += d * xc[c] * xc[c];
        }
    }
}

#ifdef FAIRING_AVX
// process_rows in AVX, lane c column c: every entry goes through the same operations in the same
// order (the target is AVX alone, no fused multiply-add), so the bits are the same. A row's
// three divisions y / d take one instruction. The curvature flow's one-click estimate, one
// thread, the least of three alternating runs: the 1.2 M-face bunny 7.67 s against 7.98 s in
// scalar, the 1 M-face torus 6.40 s against 6.91 s (auto-gap.md section 55).
template <class Weights>
__attribute__((target("avx"))) void process_rows_avx(const ProcessRows& r, const Weights& weight,
                                                     int first, int end, double* acc) {
    const AvxGather gather;
    const __m256d scale = _mm256_set1_pd(r.scale);
    const __m256d beta = _mm256_setr_pd(r.beta[0], r.beta[1], r.beta[2], 0.0);
    __m256d alpha = load_row(acc), ww = load_row(acc + 3), wx = load_row(acc + 6),
            xx = load_row(acc + 9);
    for (int i = first; i < end; ++i) {
        const __m256d x = load_row(r.x + 3 * i);
        const __m256d s = gather.sum(i, r.x, r.start, r.column, weight, x);
        const __m256d diagonal = _mm256_set1_pd(r.diagonal ? r.diagonal[i] : 0.0);
        const __m256d y = _mm256_add_pd(_mm256_mul_pd(diagonal, x), _mm256_mul_pd(scale, s));
        if (!r.free[i]) continue;
        alpha = _mm256_add_pd(alpha, _mm256_mul_pd(x, y));
        const __m256d d = _mm256_set1_pd(r.d(i));
        double* at = r.w + 3 * i;
        const __m256d w =
            _mm256_sub_pd(_mm256_div_pd(y, d), _mm256_mul_pd(beta, load_row(at)));
        store_row(at, w);
        const __m256d dw = _mm256_mul_pd(d, w);
        ww = _mm256_add_pd(ww, _mm256_mul_pd(dw, w));
        wx = _mm256_add_pd(wx, _mm256_mul_pd(dw, x));
        xx = _mm256_add_pd(xx, _mm256_mul_pd(_mm256_mul_pd(d, x), x));
    }
    store_row(acc, alpha);
    store_row(acc + 3, ww);
    store_row(acc + 6, wx);
    store_row(acc + 9, xx);
}
#endif

// Rows [first, end) of every process in turn (process_rows, or with Avx process_rows_avx),
// their sums added to sum[12 k ..].
template <int K, bool BlendLast, bool Avx>
void group_rows(const std::array<ProcessRows, K>& rs, const std::array<const double*, K>& weights,
                const Blend& blend, int first, int end, double* sum) {
    for (int k = 0; k < K; ++k) {
        double acc[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        const auto rows = [&](const auto& weight) {
#ifdef FAIRING_AVX
            if constexpr (Avx) return process_rows_avx(rs[k], weight, first, end, acc);
#endif
            process_rows(rs[k], weight, first, end, acc);
        };
        if (BlendLast && k == K - 1) rows(blend);
        else with_weights(weights[k], rows);
        for (int m = 0; m < 12; ++m) sum[12 * k + m] += acc[m];
    }
}

#ifdef FAIRING_AVX
// group_rows compiled for AVX, for a processor that has it (has_avx()).
template <int K, bool BlendLast>
FAIRING_AVX_TARGET void group_rows_avx(const std::array<ProcessRows, K>& rs,
                                       const std::array<const double*, K>& weights,
                                       const Blend& blend, int first, int end, double* sum) {
    group_rows<K, BlendLast, true>(rs, weights, blend, first, end, sum);
}
#endif

template <int K, bool BlendLast = false>
void step_group(const std::array<Context*, K>& cs, const std::array<Lanczos*, K>& ls, int j,
                const Blend& blend = Blend{}) {
    const SparseOperator& op = *cs[0]->c.op;
    std::array<ProcessRows, K> rs;
    std::array<const double*, K> weights;
    for (int k = 0; k < K; ++k) {
        const Context& ck = *cs[k];
        ProcessRows& r = rs[k];
        r.x = ls[k]->current.data();
        r.w = ls[k]->previous.data();
        r.diagonal = ck.c.diagonal.empty() ? nullptr : ck.c.diagonal.data();
        r.mass = ck.p.op->mass.data();
        r.soft = ck.p.weight ? ck.p.weight->data() : nullptr;
        r.data = ck.p.data_vertices;
        r.scale = -ck.c.lambda_dt;  // order 1: A = D - lambda_dt K
        for (int c = 0; c < 3; ++c)
            r.beta[c] = ls[k]->active[c] && j > 0 ? ls[k]->beta[c][j - 1] : 0.0;
        r.free = cs[0]->p.free->data();
        r.start = op.row_start.data();
        r.column = op.column.data();
        weights[k] = weights_of(*ck.c.op);
    }
    // The passes are bound by their instructions, not by memory: one pass that forms the vectors
    // ahead of the operator's rows instead of a pass of their own was 1.3x slower (auto-gap.md
    // section 54).
    const bool avx = has_avx();
    const auto sums = blocked_sum_by_block<12 * K>(
        op.size(), op.threads, [&](int first, int end, double* sum) {
#ifdef FAIRING_AVX
            if (avx) return group_rows_avx<K, BlendLast>(rs, weights, blend, first, end, sum);
#endif
            (void)avx;
            group_rows<K, BlendLast, false>(rs, weights, blend, first, end, sum);
        });
    for (int k = 0; k < K; ++k) {
        Lanczos& l = *ls[k];
        bool cancelled = false;
        std::array<double, 3> squared{{0, 0, 0}};
        for (int c = 0; c < 3; ++c) {
            if (!l.active[c]) continue;
            const double alpha = sums[12 * k + c];
            const double ww = sums[12 * k + 3 + c];
            l.alpha[c].push_back(alpha);
            squared[c] = ww - 2 * alpha * sums[12 * k + 6 + c] + alpha * alpha * sums[12 * k + 9 + c];
            cancelled = cancelled || !(squared[c] > kCancelled * ww);
        }
        l.previous.swap(l.current);  // current: w'; previous: v_j
        l.shift = l.scale = std::array<double, 3>{{0, 0, 0}};
        for (int c = 0; c < 3; ++c)
            if (l.active[c]) l.shift[c] = l.alpha[c][j];
        if (cancelled) squared = measure_pending(*cs[k], l);
        finish_step(l, j, squared);
    }
}

void step_pair(Context& ca, Lanczos& a, Context& cb, Lanczos& b, int j) {
    step_group<2>({{&ca, &cb}}, {{&a, &b}}, j);
}

// Whether step_pair serves the processes of contexts a and b (one check per search: it
// compares the sparsity patterns).
bool pairable(const Context& a, const Context& b) {
    return a.weight_root.empty() && b.weight_root.empty() && a.c.order == 1 && b.c.order == 1 &&
           (a.c.op == b.c.op ||
            (a.c.op->row_start == b.c.op->row_start && a.c.op->column == b.c.op->column));
}

// One recurrence step given alpha_j and beta_{j-1}: previous <- the next basis vector (its
// division by beta left to the pass that reads it first with `defer`).
void advance(Context& ctx, Lanczos& l, int j, const Positions& product, bool defer = false) {
    const int n = ctx.n;
    std::array<double, 3> a{}, b{};
    for (int c = 0; c < 3; ++c) {
        if (!l.active[c]) continue;
        a[c] = l.alpha[c][j];
        b[c] = j > 0 ? l.beta[c][j - 1] : 0.0;
    }
    const StrengthProblem& p = ctx.p;
    const char* f = p.free->data();
    double* prev = l.previous.data();
    const double* cur = l.current.data();
    const double* prod = product.data();
    const int threads = p.op->threads;
    // Summed in fixed blocks (kernels.h), so the same on any number of threads.
    const std::array<double, 3> sums = blocked_sum<3>(n, threads, [=, &p](int i, double* acc) {
        if (!f[i]) return;
        const double d = d_of(p, i);
        for (int c = 0; c < 3; ++c) {
            const double w = prod[3 * i + c] / d - a[c] * cur[3 * i + c] - b[c] * prev[3 * i + c];
            prev[3 * i + c] = w;
            acc[c] += d * w * w;
        }
    });
    l.previous.swap(l.current);
    l.shift = std::array<double, 3>{{0, 0, 0}};
    finish_step(l, j, sums);
    if (defer) return;
    const std::array<double, 3> inverse = l.scale;
    double* next = l.current.data();
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) next[3 * i + c] = f[i] ? next[3 * i + c] * inverse[c] : 0.0;
    l.pending = false;
}

int size_of(const Lanczos& l, int c) {
    return std::min(static_cast<int>(l.alpha[c].size()), static_cast<int>(l.beta[c].size()) + 1);
}

// The filter applied to e1 through the Lanczos tridiagonal matrix T_k: implicit steps (squared
// for Context::squared) by lanczos_filter.h; explicit ones as w_j = (I - lambda T) w_{j-1},
// w_0 = e1. Returns the displacement coefficients phi(T) e1 = lambda sum w_j (j = 1..s; explicit
// j = 0..s-1) and sets kept = e1' w_s, the Gauss quadrature of e1' h(T) e1 (Golub & Meurant).
// O(steps k) per lambda, no eigenvectors.
Eigen::VectorXd filtered(const Lanczos& l, int c, const Filter& f, double& kept) {
    const int k = size_of(l, c);
    const std::vector<double>& a = l.alpha[c];
    const std::vector<double>& b = l.beta[c];
    if (!f.explicit_steps) {
        const std::vector<double> sum =
            implicit_steps_filter(a, b, k, f.lambda, f.steps, f.power, &kept);
        return Eigen::Map<const Eigen::VectorXd>(sum.data(), k);
    }
    Eigen::VectorXd w = Eigen::VectorXd::Zero(k), sum = Eigen::VectorXd::Zero(k), next(k);
    kept = 0;
    if (k == 0) return sum;
    w(0) = 1;
    for (int step = 0; step < f.steps; ++step) {
        sum += w;
        for (int i = 0; i < k; ++i) {
            double t = a[i] * w(i);
            if (i > 0) t += b[i - 1] * w(i - 1);
            if (i + 1 < k) t += b[i] * w(i + 1);
            next(i) = w(i) - f.lambda * t;
        }
        w.swap(next);
    }
    kept = w(0);
    return f.lambda * sum;
}

// tr H(lambda) over the data rows for every lambda of the grid (each probe column's quadrature,
// averaged).
std::vector<double> traces(const Context& ctx, const Lanczos& z, double count,
                           const std::vector<double>& grid) {
    std::vector<double> out(grid.size(), 0.0);
    int probes = 0;
    for (int c = 0; c < 3; ++c) probes += size_of(z, c) > 0;
    for (std::size_t g = 0; g < grid.size(); ++g) {
        const Filter filter = filter_at(ctx, grid[g]);
        for (int c = 0; c < 3; ++c) {
            if (size_of(z, c) == 0) continue;
            double kept = 0;
            filtered(z, c, filter, kept);
            out[g] += count / probes * kept;
        }
    }
    return out;
}

// First basis vector of the movement: u = D^-1/2 C x for the positions.
void start_movement(Context& ctx, Lanczos& u) {
    const int n = ctx.n;
    u.current.setZero(n, 3);
    LinearSystem filter_c = ctx.c;  // the filter's own C (Context::squared runs on C1)
    filter_c.order = ctx.p.order;
    filter_c.lambda_dt = ctx.p.length_unit;
    Positions cx;
    filter_c.apply(*ctx.p.x, cx, ctx.scratch);
    // The processes' own products need the scratch vector only for L^2 (apply_dot); on C1
    // (Context::squared, the default) it would sit unused through the search.
    if (ctx.c.order == 1) ctx.scratch.resize(0, 3);
    std::array<double, 3> su{{0, 0, 0}};
    for (int i = 0; i < n; ++i) {
        if (!(*ctx.p.free)[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double v = cx(i, c);
            su[c] += v * v / d_of(ctx.p, i);
            u.current(i, c) = v / d_of(ctx.p, i);
        }
    }
    for (int c = 0; c < 3; ++c) {
        u.start_norm[c] = std::sqrt(su[c]);
        u.active[c] = u.start_norm[c] > 0;
        u.current.col(c) *= u.active[c] ? 1 / u.start_norm[c] : 0.0;
    }
    u.previous.setZero(n, 3);
}

// First basis vectors of the trace: Rademacher probes on the `count` data rows.
void start_probes(Context& ctx, Lanczos& z, double count) {
    const int n = ctx.n;
    z.current.setZero(n, 3);
    for (int i = 0; i < n; ++i) {
        if (!ctx.data[i]) continue;
        const std::uint64_t bits = splitmix64(static_cast<std::uint64_t>(i));
        for (int c = 0; c < 3; ++c) z.current(i, c) = ((bits >> c) & 1 ? 1.0 : -1.0) / std::sqrt(d_of(ctx.p, i));
    }
    for (int c = 0; c < 3; ++c) {
        z.start_norm[c] = std::sqrt(count);
        z.active[c] = count > 0;
        z.current.col(c) *= z.active[c] ? 1 / z.start_norm[c] : 0.0;
    }
    z.previous.setZero(n, 3);
}

// Monte-Carlo divergence (header, "Divergence"): the problem at y + eps b n, its movement's
// Lanczos process, and the probe's functional b n . v_j of both processes' basis vectors.
struct Perturbation {
    double eps = 0;
    // b_i on the data rows, 0 elsewhere: the probe is b_i n_i, multiplied out where used
    // rather than kept (24 bytes per vertex).
    std::vector<signed char> sign;
    Positions x;
    SparseOperator op;
    StrengthProblem problem;
    std::unique_ptr<Context> ctx;
    Lanczos u;
    std::array<std::vector<double>, 3> w, w_perturbed;  // [c][j]: b n . (basis vector j)
    // The movement's and this process's products share a pass (step_pair), which reads the
    // rows and columns of the surface operator only: op's own copies are released (28 bytes per
    // vertex).
    bool paired = false;
};

// b n . r(lambda) from a movement process and its functionals.
double probed_movement(const Lanczos& l, const std::array<std::vector<double>, 3>& w,
                       const Filter& filter) {
    double total = 0;
    for (int c = 0; c < 3; ++c) {
        double kept = 0;
        const Eigen::VectorXd coef = filtered(l, c, filter, kept);
        const int k = std::min(static_cast<int>(coef.size()), static_cast<int>(w[c].size()));
        for (int j = 0; j < k; ++j) total += l.start_norm[c] * coef(j) * w[c][j];
    }
    return total;
}

// The filter's divergence over the data rows for every lambda of the grid:
// N - b n . (r'(lambda) - r(lambda)) / eps.
std::vector<double> divergences(const Context& ctx, const Lanczos& u, const Perturbation& mc,
                                double count, const std::vector<double>& grid) {
    std::vector<double> out(grid.size(), 0.0);
    for (std::size_t g = 0; g < grid.size(); ++g) {
        const Filter filter = filter_at(ctx, grid[g]);
        const double moved = probed_movement(mc.u, mc.w_perturbed, filter) -
                             probed_movement(u, mc.w, filter);
        out[g] = std::max(0.0, std::min(count, count - moved / mc.eps));
    }
    return out;
}

// Relative size of the Monte-Carlo perturbation: small enough for a first-order difference,
// large enough against the Lanczos processes' rounding (Ramani et al. use about sigma / 100).
constexpr double kPerturbation = 1e-2;

// Umbrella passes (half steps) smoothing the copy the later steps' operator is assembled at
// (StrengthProblem::pilot). Chosen from 1, 2, 3, 4, 8 and 16 on twelve cases (a sphere at two
// densities, the torus, four scans at three noise levels; curvature flow with 4 steps,
// scale-dependent with 2): 2 gave the lowest geometric mean of the automatic choice's error over
// the best fixed step's, 1.06 (curvature) and 1.02 (scale-dependent), against 1.18 and 1.03
// with the first step's operator for every step; 8 gave 1.11 and 1.04. With the operator's own
// weights (StrengthProblem::pilot_on_own_weights) 2 again: 1 and 4 passes measured no better
// (auto-gap.md, section 29).
constexpr int kPilotPasses = 2;

// With StrengthProblem::pilot, `first` (the operator at x) becomes the steps' mean operator:
// one step on it, s - 1 on the operator at x's data rows smoothed (virtual vertices as they
// are). K and M are linear in the weights and masses, so the mean is one symmetric operator.
// The operator of the later steps: assembled at x's data rows smoothed (virtual vertices as they
// are); `first` (the operator at x) gives the one-rings.
SparseOperator later_operator(const StrengthProblem& p, const Positions& x,
                              const SparseOperator& first) {
    Positions smooth = x;
    smooth.topRows(p.data_vertices) =
        p.pilot_on_own_weights
            ? smoothed_copy_weighted(first, x, p.data_vertices, kPilotPasses)
            : smoothed_copy(first, x, p.data_vertices, kPilotPasses);
    return p.assemble_at(smooth);
}

// model_steps: see above. `kept` (optional) takes the later steps' operator, which later_steps()
// would otherwise assemble again at the same positions.
void model_steps(const StrengthProblem& p, const Positions& x, SparseOperator& first,
                 SparseOperator* kept = nullptr) {
    if (!p.pilot) return;
    SparseOperator later = later_operator(p, x, first);
    if (later.column != first.column || later.row_start != first.row_start) return;
    const double share = (p.steps - 1.0) / p.steps;
    for (std::size_t k = 0; k < first.weight.size(); ++k)
        first.weight[k] += share * (later.weight[k] - first.weight[k]);
    first.unit_weights = false;
    for (std::size_t i = 0; i < first.mass.size(); ++i)
        first.mass[i] += share * (later.mass[i] - first.mass[i]);
    if (kept) *kept = std::move(later);
}

// The perturbed problem, or nothing when the operator is linear in the data or the perturbed
// one loses a free row's mass.
// `assembled`, when not empty, is the perturbed operator of an earlier run of the same problem
// (the perturbation is deterministic), taken instead of assembling it again: fair() releases
// what assembly needs after the estimate's last assembly.
std::unique_ptr<Perturbation> perturb(const Context& ctx, const Positions& normals, double sigma,
                                      SparseOperator* assembled = nullptr) {
    const StrengthProblem& p = ctx.p;
    if (!p.assemble_at) return nullptr;
    auto mc = std::make_unique<Perturbation>();
    mc->eps = kPerturbation * sigma;
    mc->sign.assign(ctx.n, 0);
    mc->x = *p.x;
    for (int i = 0; i < p.data_vertices; ++i) {
        if (!ctx.data[i]) continue;
        const bool plus = splitmix64(static_cast<std::uint64_t>(i) ^ 0x27d4eb2f165667c5ull) & 1;
        mc->sign[i] = plus ? 1 : -1;
        const Eigen::RowVector3d probe = (plus ? 1.0 : -1.0) * normals.row(i);
        mc->x.row(i) += mc->eps * probe;
    }
    if (assembled && assembled->size() > 0) {
        mc->op = std::move(*assembled);
    } else {
        mc->op = p.assemble_at(mc->x);
        model_steps(p, mc->x, mc->op);
    }
    mc->op.threads = p.op->threads;
    if (mc->op.size() != p.op->size()) return nullptr;
    mc->problem = p;
    std::vector<int>().swap(mc->problem.restored);  // the restoration is the outer problem's
    mc->problem.op = &mc->op;
    mc->problem.x = &mc->x;
    mc->ctx.reset(new Context{mc->problem, ctx.c, ctx.data, Positions(), ctx.n, ctx.squared,
                              ctx.weight_root, Positions()});
    mc->ctx->c.op = &mc->op;
    for (int i = 0; i < ctx.n; ++i) {
        if (!(*p.free)[i]) continue;
        if (!(mc->op.mass[i] > 0)) return nullptr;
    }
    start_movement(*mc->ctx, mc->u);
    mc->x.resize(0, 3);  // only the start vector needed the perturbed positions
    mc->paired = pairable(ctx, *mc->ctx);
    if (mc->paired) {
        std::vector<int>().swap(mc->op.row_start);
        std::vector<int>().swap(mc->op.column);
    }
    return mc;
}

// One Lanczos step of a block: alpha measured, then the next vector.
// `defer`: leave the new basis vector's division by beta to the pass that reads it first
// (Lanczos::pending), which must run before the next step.
void step(Context& ctx, Lanczos& l, int j, Positions& product, bool defer = false) {
    const std::array<double, 3> a = multiply(ctx, l, product);
    for (int c = 0; c < 3; ++c)
        if (l.active[c]) l.alpha[c].push_back(a[c]);
    advance(ctx, l, j, product, defer);
}

int argmin(const std::vector<double>& v) {
    return static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
}

// Relative change of the curves between two checkpoints below which a point counts as converged.
constexpr double kConverged = 2e-2;
// The same for implicit L^2 on G itself (soft weights, kWeightModelKeeps). Its Krylov
// approximation of the filter converges so slowly that two checkpoints 1.4x apart differ by far
// less than either's error: at 2 % the torus (10 k faces, a quarter edge of noise, all weights
// 0.9) chose 2.2-2.4x off, at 0.1 % right. The tolerance relaxes geometrically towards
// kConverged (reached at kRelaxedSteps; 1 % at the last checkpoint, kMaxSteps), so that a run the
// cap stops still has converged points to choose from.
constexpr double kConvergedSquaredSpectrum = 1e-3;
constexpr int kStrictSteps = 100;  // Lanczos steps held to kConvergedSquaredSpectrum
constexpr int kRelaxedSteps = 400;
// The Lanczos process runs until its curves are converged up to this factor above the risk's
// minimizer (and the minimizer has settled). It was 1.5 before the three-checkpoint rule
// (kNear, kFar), whose converged range advances faster: with 1.5 the 1 M-face torus's curvature
// flow at noise 0.1 (one L^2 step) stopped at 109 Lanczos steps on a minimizer of 5012, two grid
// points inside a flat risk, and chose 7943 (1.14x the best fixed step's error); with 2 it runs
// on to 296 and chooses 3.8e4 (1.03x). On the 160 runs of auto-gap.md section 10, errors within
// -1.5 % / +0.9 % of the rule before, in 6,068 Lanczos steps against its 7,764.
constexpr double kMargin = 2.0;
// With the later steps' process (StrengthProblem::residual_on_later_steps) and at least
// kLaterRuleSteps steps, the search, once the mean risk has settled, also finds the minimizer of
// the risk the choice minimizes (the later steps' residual with the mean's divergence) up to
// kLaterReach times the mean's, and runs on until the curves have converged to kMargin times
// that. Before, it stopped on the mean risk alone, and the choice, confined to 2.5x the mean's
// minimizer, sat at the top of its grid (the curvature flow's four L^2 steps on the 13 k sphere
// at half an edge: 3147, the best fixed step 1.2e4, 1.29x its error). Measured on those four
// steps (auto / best fixed step's error, auto-gap.md section 31): the study's spheres, torus
// and five scans at four noises, seed 1, gmean 1.048 -> 1.039, worst 1.288 -> 1.231 (the 13 k
// sphere 1.288 -> 1.023 at half an edge, 1.090 -> 1.018 at a quarter; worse at 0.1 edge, 1.092
// -> 1.121, and the 51 k sphere's 1.001 -> 1.033; the scans as before); other draws (seeds 2
// and 8) the same way, the 13 k sphere at half an edge 1.086 -> 1.031. Unbounded (no
// kLaterReach), the 13 k sphere at a quarter edge ran to 4e5 (3.5x its best error): the model
// misses what the real steps do there. With two or three steps the later operator is less of
// the filter and the rule chose worse (1.058 -> 1.083 and 1.086 -> 1.101 in geometric mean), so
// they keep the mean's rule.
constexpr int kLaterRuleSteps = 4;
constexpr double kLaterReach = 4.0;
// What a checkpoint's bound on the final excess risk gives up (header, "An estimate that cannot
// win"), in units of N sigma^2, for the converged points' tolerance (kConvergedSquaredSpectrum)
// and rounding: on 224 runs of the two filters that compare frozen and recomputed steps no
// checkpoint's bound exceeded the final value (a point-wise first form did, by up to 0.028 on
// the sponge; auto-gap.md section 47).
constexpr double kBoundSlack = 0.002;
// The cap on the Lanczos steps: the last checkpoint (they fall at 6, 8, 11, ... 152, 212, 296,
// 1.4x apart; search()). The cap was 400, whose next checkpoint would have been at 414: a run
// that had not settled by 296 spent 104 more steps on each process that no checkpoint judged,
// and chose from the checkpoint at 296 (the final curves, around that choice, from all 400).
// On the 1 M-face torus with half an edge of noise (umbrella L^2, one step) that was 7.51 s
// against 5.93 s at 296 for the same time step to 9 digits: the estimate then cost 2.34 against
// 1.78 steps at the chosen strength. No run of the study's meshes needs more than 212 steps.
constexpr int kMaxSteps = 296;
// Checkpoints fall kCheckpointGrowth apart. A checkpoint whose mean risk's minimizer has settled,
// and whose converged points fall short of kMargin times it by at most kShortGridPoints points of
// the risk's grid (kGridDecades apart), calls the next one only kShortGrowth on: the margin is then
// a few Lanczos steps away, which the 40 % step overshot by some 30. On the 1.2 M-face Loop bunny
// (curvature flow, a quarter edge) both searches settled at 78 steps 1.58x short of 2x and ran to
// 109: 178 Lanczos steps instead of 218 now, the error 0.993x. On 224 runs (14 meshes, 4 noises,
// 2 seeds; the curvature flow's and the scale-dependent filter's defaults) 5-7 % fewer Lanczos
// steps, 62 choices moved, the error 0.9985x in geometric mean (0.709x to 1.011x); on the study's
// seven sets 9.7 % fewer, no one-click row moved across 10 % of its oracle, of 4,010 automatic
// rows 6 moved past it and 2 back within. Only the mean risk's margin: the same short step on
// the later steps' risk (kLaterRuleSteps) stopped the 51 k sphere at a quarter edge before its
// later process had converged (time step 42,919 -> 68,986, 1.14x the best fixed step's error;
// auto-gap.md section 49).
constexpr double kCheckpointGrowth = 1.4;
constexpr double kShortGrowth = 1.15;
constexpr int kShortGridPoints = 2;
// A search on a sketched residual stops only once its risk has risen at least this much past the
// minimizer, in units of the noise's energy N sigma^2 (the risk at the last converged point less
// its minimum), else it runs on (to the cap at most): within that, the sketch's error decides
// where the minimizer falls. On the 1 M-face torus at a quarter edge (curvature flow) one draw of
// the sketch in twelve found the sketched risk flat from 631 to 2,512 (all within 1e-4), stopped
// there after 96 Lanczos steps and chose 1,534, 1.57x the error of the best draw; the risk of the
// other draws falls on to a minimum near 1e4 and rises 0.004 past it. With the rule that draw
// runs on to 192 steps and chooses 9,541 (1.04x). No choice of 224 runs of smaller meshes moved
// (auto-gap.md section 53).
constexpr double kSketchFlat = 1e-3;
// The risk's grid of time steps (search()): kGridDecades apart in log10, from 1e-4 up.
constexpr double kGridDecades = 0.1;
// Rows of the sketch of the normal components (exact below this many data vertices).
constexpr int kSketch = 8192;
// Sketch::add asks for the row of the vertex this many ahead: its rows are hashed, so nearly
// every vertex's row is a cache miss, and the pass otherwise waits on each in turn. Output
// unchanged; the 1 M-face torus's one click (one thread) estimated in 5.77 s instead of 6.38 s
// at 8,192 rows, in 9.4 s instead of 13.4 s at 32,768 (auto-gap.md §51,
// session51-probe/rows_prefetch_torus.txt).
constexpr int kSketchPrefetch = 16;
// Fixed chunks of rows of Sketch::add (so its sums are the same on any number of threads), and
// the most restored components it still splits into chunks for.
constexpr int kSketchChunks = 8;
constexpr int kSketchChunkComponents = 1024;
// Rows per run of Sketch::add, which takes one process at a time over a run (their shared data
// stays in cache between them).
constexpr int kSketchRun = 2048;
// Basis vectors per block of the sketch's storage (Sketch::blocks_).
constexpr Eigen::Index kSketchBlock = 64;
// Soft weights: the model of Context::weight_root holds where the chosen filter acts on the
// noise's scale, not where it reaches the smoothest modes. Its choice keeping less than this
// share of the noise (tr H / N) is redone on the L^2 operator itself, unless the weights are
// uniform (the model is then exact). Measured at noise 0.25
// (weights ramped or stepped along the mesh, bench/results/issue11/auto-gap.md §6b): 0.33-0.48
// on scans, where the model is right, and 0.10-0.14 on the sphere and the torus, where it chose
// 4-11x too weak.
constexpr double kWeightModelKeeps = 0.2;
// ... on meshes of at most this many data vertices, where the L^2 process's 296 steps cost little
// (it needed up to 300 on the 10 k-face torus; the 1.2 M-face bunny, whose Loop subdivision keeps
// little noise per mode, also chooses below kWeightModelKeeps and there reached the cap after
// 33 s), and only when that process settles within its cap.
constexpr double kWeightedDirectVertices = 50000;
// Second pass: points of the final lambda grid.
constexpr int kGrid = 16;
// Restored components whose fields' sketches have columns of their own (the largest ones; see
// Sketch::restored): each holds two sketched fields of kSketch rows. The others with rows of
// their own share one such pair (Layout::past_slots), and only their drift is not modelled.
constexpr int kSketchedComponents = 16;
// Sums per restored component in Sketch::add: a . n.r, s . n.r and w . n.r per column; then
// per sketched component, drift-cancelled or not, its three moments m_d per column.
constexpr int kComponentSums = 9;
constexpr int kMomentSums = 9 * kSketchedComponents;

// A sketch of the normal components n_i . r_i: CountSketch (Charikar, Chen & Farach-Colton
// 2002) of every basis vector's normal part, so that |sketch of r(lambda)|^2 estimates
// RSS_n(lambda) to about sqrt(2 / rows) without keeping the basis (the error is common to all
// lambda: the same buckets serve every point of the curve). With no more data vertices than
// rows it is exact (one row per vertex). Kept in double precision (at most 8192 x 8 bytes per
// basis vector): the risk is a small difference of large terms (RSS_n is about N sigma^2, and
// for a rescaled component (1 - beta)^2 |s|^2 is N times the squared size of the shape), and in
// single precision the chosen time step of the same mesh at scales 1e-3 and 1e3 differed by
// up to 0.4 %.
class Sketch {
public:
    // The volume restoration after each step (sections 3.1-3.2) undoes the part of the normal
    // residual along one field per restored component: s_i = n_i . (x_i - centroid) for a
    // rescaling, w on the free vertices for a normal offset (its shape: 1, or
    // StrengthProblem::offset_shape), by the multiple that restores the volume (see restored()).
    // Three linear functionals of r per component, kept exactly beside the sketch: a . n.r (the
    // volume lost), s . n.r and w . n.r (a_i: vertex areas).
    //
    // A component whose drift is cancelled (Options::cancel_drift, `drift_cancelled`) is translated
    // by the least-squares translation of its normal residual rho (after the restoration):
    // tau = P^-1 sum a_i n_i rho_i, P = sum a_i n_i n_i^T, and loses n_i . tau. With the
    // restoration's residual (1 - beta) s + beta n.r or n.r - t, that is
    // tau = P^-1 (beta m + (1 - beta) q_s) or P^-1 (m - t q_1), where m = sum a n n.r are three
    // more functionals per column and q_s = sum a n s, q_1 = sum a w n constants; n . tau is
    // formed in the sketch's space from the sketched normal components n_d of the component.
    // Only the kSketchedComponents largest are so modelled (a bounded memory; the translation
    // of smaller ones is left in the residual).
    struct Restoration {
        std::vector<int> component;  // per data vertex, -1: not restored
        std::vector<double> field, area;
        // Per data vertex the normal offset's shape w (StrengthProblem::offset_shape): the
        // offset is t w_i, and its functional w . n.r in place of 1 . n.r. Empty: all 1.
        std::vector<double> shape;
        std::vector<char> offset;  // per component, as StrengthProblem::offset
        std::vector<char> drift_cancelled;  // per component: its drift cancelled
        const Positions* normals = nullptr;
        int components = 0;
        int restorations = 1;  // StrengthProblem::restorations
    };

    Sketch(const Context& ctx, int data_count, Restoration restoration)
        : Sketch(layout(ctx, data_count, std::move(restoration))) {}
    // A sketch of the same data rows and restoration as `same` (the same buckets, signs and
    // fields, shared: 28 bytes per vertex), with basis vectors of its own.
    static std::unique_ptr<Sketch> like(const Sketch& same) {
        return std::unique_ptr<Sketch>(new Sketch(same.layout_));
    }
    bool exact() const { return layout_->exact; }
    // Adds the current basis vector of every active column and, with `probe` (the Monte-Carlo
    // probe's signs b), appends b n . v to (*probed)[c] (Perturbation::w), and with `partner`
    // (the perturbed movement's process) b n . v' of its current basis vector v' to
    // (*partner_probed)[c] (Perturbation::w_perturbed), dividing either's pending basis vector by
    // beta (Lanczos::pending). A process that has broken down (no active column) adds nothing.
    // One pass over the vertices for all of it, as kSketchChunks fixed chunks of rows run in
    // parallel: each chunk sums into its own buckets, which are then added in chunk order, so the
    // sums do not depend on the number of threads. (Serial, with the probe's sums a pass of their
    // own, these took 15 % of perf's samples of an automatic scale-dependent L^2 step on the
    // 1 M-face torus with two threads; the partner's functionals, a pass of their own, 6 % with
    // one thread.)
    // With `twin` (a sketch of the same data rows and restoration: the same buckets and fields)
    // and its process twin_u, the twin's basis vector goes into the twin in the same pass, with
    // the same sums as a pass of its own would make.
    void add(Lanczos& u, const Positions& normals, const char* free, int threads,
             const std::vector<signed char>* probe = nullptr,
             std::array<std::vector<double>, 3>* probed = nullptr, Lanczos* partner = nullptr,
             std::array<std::vector<double>, 3>* partner_probed = nullptr, Sketch* twin = nullptr,
             Lanczos* twin_u = nullptr) {
        const std::array<Eigen::Index, 3> slot = open_columns(u);
        const std::array<Eigen::Index, 3> twin_slot =
            twin ? twin->open_columns(*twin_u) : std::array<Eigen::Index, 3>{{-1, -1, -1}};
        const int nc = layout_->restoration.components;
        const int n = static_cast<int>(layout_->bucket.size());
        // Many restored components (each chunk holds nine sums per component): one chunk.
        const int chunks = nc <= kSketchChunkComponents ? kSketchChunks : 1;
        const int per_chunk = (n + chunks - 1) / chunks;
        const std::size_t buckets = 3 * static_cast<std::size_t>(layout_->rows);
        const std::size_t stride =
            buckets + kComponentSums * static_cast<std::size_t>(nc) + kMomentSums + 6;
        chunk_sums_.assign(chunks * stride, 0.0);
        if (twin) twin->chunk_sums_.assign(chunks * stride, 0.0);
        const int* bucket = layout_->bucket.data();
        const float* sign = layout_->sign.data();
        const int* component = layout_->restoration.component.data();
        const int components_known = static_cast<int>(layout_->restoration.component.size());
        const double* area = layout_->restoration.area.data();
        const double* field = layout_->restoration.field.data();
        const double* shape =
            layout_->restoration.shape.empty() ? nullptr : layout_->restoration.shape.data();
        const char* drift_cancelled = layout_->restoration.drift_cancelled.data();
        const bool any_drift_cancelled = layout_->drift_cancelled;
        const int* component_slot = layout_->slot.data();
        const signed char* b_sign = probe ? probe->data() : nullptr;
        const double* nv = normals.data();
        double* v = u.current.data();
        double* v_partner = partner ? partner->current.data() : nullptr;
        double* v_twin = twin ? twin_u->current.data() : nullptr;
        const std::array<bool, 3> partner_active =
            partner ? partner->active : std::array<bool, 3>{{false, false, false}};
        double* sums = chunk_sums_.data();
        double* twin_sums = twin ? twin->chunk_sums_.data() : nullptr;
        (void)threads;
        const Rows rows{bucket, sign, component, components_known, area, field, shape, nv,
                        drift_cancelled, any_drift_cancelled, component_slot};
        const bool avx = has_avx();
        (void)avx;
        FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1 && chunks > 1))
        for (int chunk = 0; chunk < chunks; ++chunk) {
            double* to_bucket = sums + chunk * stride;
            double* to_component = to_bucket + buckets;
            double* to_moment = to_component + kComponentSums * static_cast<std::size_t>(nc);
            double* to_probe = to_moment + kMomentSums;
            double* twin_bucket = twin_sums ? twin_sums + chunk * stride : nullptr;
            double* twin_component = twin_bucket ? twin_bucket + buckets : nullptr;
            double* twin_moment =
                twin_component ? twin_component + kComponentSums * static_cast<std::size_t>(nc)
                               : nullptr;
            const int end = std::min(n, (chunk + 1) * per_chunk);
            // One process at a time over runs of kSketchRun rows, which stay in cache for the
            // next process: its sums keep their row order (the same bits as row by row, all
            // processes in turn), and a few of them stay in registers (add_rows).
            for (int first = chunk * per_chunk; first < end; first += kSketchRun) {
                const int last = std::min(end, first + kSketchRun);
                const auto run = [&](auto lanes) {
                    lanes.settle_rows(u, free, v, first, last);
                    lanes.add_rows(rows, slot, v, b_sign, first, last, end, to_bucket,
                                   to_component, to_moment, to_probe);
                    if (v_partner) {
                        lanes.settle_rows(*partner, free, v_partner, first, last);
                        if (b_sign)
                            lanes.add_probe(b_sign, nv, v_partner, partner_active, first, last,
                                            to_probe + 3);
                    }
                    if (v_twin) {
                        lanes.settle_rows(*twin_u, free, v_twin, first, last);
                        lanes.add_rows(rows, twin_slot, v_twin, nullptr, first, last, end,
                                       twin_bucket, twin_component, twin_moment, nullptr);
                    }
                };
#ifdef FAIRING_AVX
                if (avx) {
                    run(AvxLanes{});
                    continue;
                }
#endif
                run(ScalarLanes{});
            }
        }
        u.pending = false;
        if (partner) partner->pending = false;
        const std::array<double, 3> probe_sum = close_columns(slot, chunks, stride, sums);
        if (twin) {
            twin_u->pending = false;
            twin->close_columns(twin_slot, chunks, stride, twin_sums);
        }
        for (int c = 0; c < 3; ++c)
            if (probed && slot[c] >= 0) (*probed)[c].push_back(probe_sum[c]);
        std::array<double, 3> partner_sum{{0, 0, 0}};
        for (int chunk = 0; chunk < chunks; ++chunk) {
            const double* from_probe =
                sums + chunk * stride + buckets + kComponentSums * static_cast<std::size_t>(nc) +
                kMomentSums;
            for (int c = 0; c < 3; ++c) partner_sum[c] += from_probe[3 + c];
        }
        for (int c = 0; c < 3; ++c)
            if (partner_probed && partner_active[c]) (*partner_probed)[c].push_back(partner_sum[c]);
    }
    // |sum_c S_c y_c(lambda)|^2 for every lambda of `grid` from `first` to `last` (exclusive),
    // with y from the Lanczos tridiagonal matrices; NaN elsewhere.
    // `offsets` (optional): per restored component, whether the last lambda's residual was
    // modelled with the offset (1) or the scaling (0).
    std::vector<double> rss(const Context& ctx, const Lanczos& u, const std::vector<double>& grid,
                            std::size_t first, std::size_t last,
                            std::vector<double>* gains = nullptr,
                            std::vector<char>* offsets = nullptr) const {
        std::vector<double> out(grid.size(), std::numeric_limits<double>::quiet_NaN());
        if (gains) gains->assign(grid.size(), 1.0);
        if (last <= first) return out;
        Eigen::MatrixXd y = Eigen::MatrixXd::Zero(used_, static_cast<Eigen::Index>(last - first));
        for (std::size_t g = first; g < last; ++g) {
            const Filter filter = filter_at(ctx, grid[g]);
            for (int c = 0; c < 3; ++c) {
                double kept = 0;
                const Eigen::VectorXd coef = filtered(u, c, filter, kept);
                const int k = std::min(static_cast<int>(coef.size()), static_cast<int>(index_[c].size()));
                for (int j = 0; j < k; ++j)
                    y(index_[c][j], static_cast<Eigen::Index>(g - first)) =
                        u.start_norm[c] * coef(j);
            }
        }
        // One product per block of columns for all lambda.
        Eigen::MatrixXd v = Eigen::MatrixXd::Zero(layout_->rows, y.cols());
        for (std::size_t k = 0; k < blocks_.size(); ++k) {
            const Eigen::Index first_column = static_cast<Eigen::Index>(k) * kSketchBlock;
            const Eigen::Index width = std::min<Eigen::Index>(kSketchBlock, used_ - first_column);
            v.noalias() += blocks_[k].leftCols(width) * y.middleRows(first_column, width);
        }
        for (std::size_t g = first; g < last; ++g) {
            const Eigen::Index col = static_cast<Eigen::Index>(g - first);
            double gain = 1;
            out[g] = restored(y.col(col), v.col(col), gain, offsets);
            if (gains) (*gains)[g] = gain;
        }
        return out;
    }

private:
    // What add_rows() reads of the layout, per data vertex.
    struct Rows {
        const int* bucket;
        const float* sign;
        const int* component;
        int components_known;
        const double *area, *field, *shape;
        const double* nv;
        const char* drift_cancelled;
        bool any_drift_cancelled;
        const int* component_slot;
        // Row i's bucket b, component k (-1: none) and probe sign bi (0: none), once the bucket
        // of the row kSketchPrefetch ahead in the chunk is asked for.
        std::array<int, 3> head(int i, int chunk_end, const signed char* b_sign,
                                double* to_bucket) const {
            const int ahead = i + kSketchPrefetch < chunk_end ? bucket[i + kSketchPrefetch] : -1;
            if (ahead >= 0) prefetch_for_write(to_bucket + 3 * static_cast<std::size_t>(ahead));
            return {bucket[i], i < components_known ? component[i] : -1, b_sign ? b_sign[i] : 0};
        }
    };
    // Sketch::add's work on one run of rows, one process at a time, row by row (ScalarLanes) or
    // with a row's three columns in one register (AvxLanes, the same bits).
    struct ScalarLanes {
        // Forms rows [first, end) of l's pending basis vector v (Lanczos::pending): (current -
        // shift previous) * scale on the free rows, 0 elsewhere, written back.
        void settle_rows(const Lanczos& l, const char* free, double* v, int first,
                         int end) const {
            if (!l.pending) return;
            const double* previous = l.previous.data();
            const double shift[3] = {l.shift[0], l.shift[1], l.shift[2]};
            const double scale[3] = {l.scale[0], l.scale[1], l.scale[2]};
            for (int i = first; i < end; ++i)
                for (int c = 0; c < 3; ++c)
                    v[3 * i + c] = free[i] ? (v[3 * i + c] - shift[c] * previous[3 * i + c]) *
                                                 scale[c]
                                           : 0.0;
        }
        // One process's rows [first, end) (formed) of a chunk ending at chunk_end: each vertex's
        // normal components n_c v_c into its bucket (b >= 0) and its component's sums (k >= 0;
        // and add_moments()), with b_sign the probe's sums b n_c v_c too. A run of rows of one
        // component keeps that component's nine sums in registers (loaded at the run's start and
        // stored at its end) and the probe's three for the whole range, so every sum takes the
        // same rows in the same order.
        void add_rows(const Rows& r, const std::array<Eigen::Index, 3>& slot, const double* v,
                      const signed char* b_sign, int first, int end, int chunk_end,
                      double* to_bucket, double* to_component, double* to_moment,
                      double* to_probe) const {
            double probe[3] = {0, 0, 0};
            if (to_probe)
                for (int c = 0; c < 3; ++c) probe[c] = to_probe[c];
            double sums[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
            int run = -1;  // the component whose sums `sums` holds
            for (int i = first; i < end; ++i) {
                const auto [b, k, bi] = r.head(i, chunk_end, b_sign, to_bucket);
                if (k != run) {
                    if (run >= 0)
                        for (int m = 0; m < 9; ++m) to_component[9 * run + m] = sums[m];
                    if (k >= 0)
                        for (int m = 0; m < 9; ++m) sums[m] = to_component[9 * k + m];
                    run = k;
                }
                if (b < 0 && k < 0 && bi == 0) continue;
                const double* n = r.nv + 3 * i;
                const double* vi = v + 3 * i;
                const double sign = static_cast<double>(r.sign[i]);
                const double area = k >= 0 ? r.area[i] : 0.0;
                const double field = k >= 0 ? r.field[i] : 0.0;
                const double shape = r.shape ? r.shape[i] : 1.0;
                for (int c = 0; c < 3; ++c) {
                    if (slot[c] < 0) continue;
                    const double nv_c = n[c] * vi[c];
                    if (b >= 0) to_bucket[3 * b + c] += sign * nv_c;
                    if (bi != 0) probe[c] += bi * nv_c;
                    if (k < 0) continue;
                    sums[c] += area * nv_c;
                    sums[3 + c] += field * nv_c;
                    sums[6 + c] += shape * nv_c;
                }
                const int moment_slot = k >= 0 && r.any_drift_cancelled && r.drift_cancelled[k]
                                            ? r.component_slot[k]
                                            : -1;
                if (moment_slot >= 0) add_moments(slot, area, n, vi, to_moment + 9 * moment_slot);
            }
            if (run >= 0)
                for (int m = 0; m < 9; ++m) to_component[9 * run + m] = sums[m];
            if (to_probe)
                for (int c = 0; c < 3; ++c) to_probe[c] = probe[c];
        }
        // The perturbed movement's probe functionals b n . v' over rows [first, end), its three
        // sums in registers.
        void add_probe(const signed char* b_sign, const double* nv, const double* v,
                       const std::array<bool, 3>& active, int first, int end,
                       double* to_probe) const {
            double probe[3] = {to_probe[0], to_probe[1], to_probe[2]};
            for (int i = first; i < end; ++i) {
                const int bi = b_sign[i];
                if (bi == 0) continue;
                for (int c = 0; c < 3; ++c)
                    if (active[c]) probe[c] += bi * nv[3 * i + c] * v[3 * i + c];
            }
            for (int c = 0; c < 3; ++c) to_probe[c] = probe[c];
        }
    };
#ifdef FAIRING_AVX
    // ScalarLanes's passes in AVX, lane c column c: every entry goes through the same operations
    // in the same order (the target is AVX alone, no fused multiply-add), so the bits are the
    // same. A row is loaded with load_row and stored with store_row (no masked store), a
    // bucket likewise. Lanes of inactive columns are zeroed before they are added anywhere.
    // With process_rows_avx, the bunny's one-click estimate (as there) took 7.54 s against
    // 8.51 s, the least of five alternating runs (auto-gap.md section 55).
    struct AvxLanes {
        static __attribute__((target("avx"))) __m256d lanes_of(const std::array<bool, 3>& on) {
            return _mm256_castsi256_pd(_mm256_set_epi64x(0, on[2] ? -1 : 0, on[1] ? -1 : 0,
                                                         on[0] ? -1 : 0));
        }
        __attribute__((target("avx"))) void settle_rows(const Lanczos& l, const char* free,
                                                        double* v, int first, int end) const {
            if (!l.pending) return;
            const double* previous = l.previous.data();
            const __m256d shift = _mm256_setr_pd(l.shift[0], l.shift[1], l.shift[2], 0.0);
            const __m256d scale = _mm256_setr_pd(l.scale[0], l.scale[1], l.scale[2], 0.0);
            for (int i = first; i < end; ++i) {
                double* at = v + 3 * i;
                if (!free[i]) {
                    store_row(at, _mm256_setzero_pd());
                    continue;
                }
                const __m256d moved = _mm256_mul_pd(shift, load_row(previous + 3 * i));
                store_row(at, _mm256_mul_pd(_mm256_sub_pd(load_row(at), moved), scale));
            }
        }
        __attribute__((target("avx"))) void add_rows(const Rows& r,
                                                     const std::array<Eigen::Index, 3>& slot,
                                                     const double* v, const signed char* b_sign,
                                                     int first, int end, int chunk_end,
                                                     double* to_bucket, double* to_component,
                                                     double* to_moment, double* to_probe) const {
            const __m256d active = lanes_of({{slot[0] >= 0, slot[1] >= 0, slot[2] >= 0}});
            __m256d probe = to_probe ? load_row(to_probe) : _mm256_setzero_pd();
            __m256d by_area = _mm256_setzero_pd(), by_field = by_area, by_shape = by_area;
            int run = -1;  // the component whose sums by_area, by_field and by_shape hold
            for (int i = first; i < end; ++i) {
                const auto [b, k, bi] = r.head(i, chunk_end, b_sign, to_bucket);
                if (k != run) {
                    if (run >= 0) {
                        store_row(to_component + 9 * run, by_area);
                        store_row(to_component + 9 * run + 3, by_field);
                        store_row(to_component + 9 * run + 6, by_shape);
                    }
                    if (k >= 0) {
                        by_area = load_row(to_component + 9 * k);
                        by_field = load_row(to_component + 9 * k + 3);
                        by_shape = load_row(to_component + 9 * k + 6);
                    }
                    run = k;
                }
                if (b < 0 && k < 0 && bi == 0) continue;
                const double* n = r.nv + 3 * i;
                const double* vi = v + 3 * i;
                const __m256d nv = _mm256_and_pd(_mm256_mul_pd(load_row(n), load_row(vi)), active);
                if (b >= 0) {
                    double* at = to_bucket + 3 * b;
                    const __m256d sign = _mm256_set1_pd(static_cast<double>(r.sign[i]));
                    store_row(at, _mm256_add_pd(load_row(at), _mm256_mul_pd(sign, nv)));
                }
                if (bi != 0)
                    probe = _mm256_add_pd(probe, _mm256_mul_pd(_mm256_set1_pd(bi), nv));
                if (k < 0) continue;
                const double area = r.area[i];
                by_area = _mm256_add_pd(by_area, _mm256_mul_pd(_mm256_set1_pd(area), nv));
                by_field = _mm256_add_pd(by_field, _mm256_mul_pd(_mm256_set1_pd(r.field[i]), nv));
                by_shape = _mm256_add_pd(
                    by_shape, _mm256_mul_pd(_mm256_set1_pd(r.shape ? r.shape[i] : 1.0), nv));
                const int moment_slot =
                    r.any_drift_cancelled && r.drift_cancelled[k] ? r.component_slot[k] : -1;
                if (moment_slot >= 0) add_moments(slot, area, n, vi, to_moment + 9 * moment_slot);
            }
            if (run >= 0) {
                store_row(to_component + 9 * run, by_area);
                store_row(to_component + 9 * run + 3, by_field);
                store_row(to_component + 9 * run + 6, by_shape);
            }
            if (to_probe) store_row(to_probe, probe);
        }
        __attribute__((target("avx"))) void add_probe(const signed char* b_sign,
                                                      const double* nv, const double* v,
                                                      const std::array<bool, 3>& active,
                                                      int first, int end,
                                                      double* to_probe) const {
            const __m256d on = lanes_of(active);
            __m256d probe = load_row(to_probe);
            for (int i = first; i < end; ++i) {
                const int bi = b_sign[i];
                if (bi == 0) continue;
                const __m256d term = _mm256_mul_pd(
                    _mm256_mul_pd(_mm256_set1_pd(bi), load_row(nv + 3 * i)), load_row(v + 3 * i));
                probe = _mm256_add_pd(probe, _mm256_and_pd(term, on));
            }
            store_row(to_probe, probe);
        }
    };
#endif
    // A column per active column of process l for its current basis vector (-1: inactive).
    std::array<Eigen::Index, 3> open_columns(const Lanczos& l) {
        std::array<Eigen::Index, 3> slot{{-1, -1, -1}};
        for (int c = 0; c < 3; ++c) {
            if (!l.active[c]) continue;
            if (used_ == static_cast<Eigen::Index>(blocks_.size()) * kSketchBlock)
                blocks_.emplace_back(Eigen::MatrixXd::Zero(layout_->rows, kSketchBlock));
            index_[c].push_back(static_cast<int>(used_));
            slot[c] = used_++;
        }
        return slot;
    }
    // A drift-cancelled component's vertex: its part of m_d = sum a n_d n.r.
    static void add_moments(const std::array<Eigen::Index, 3>& slot, double area, const double* n,
                            const double* v, double* to_moment) {
        for (int c = 0; c < 3; ++c) {
            if (slot[c] < 0) continue;
            const double anv_c = area * n[c] * v[c];
            for (int d = 0; d < 3; ++d) to_moment[3 * c + d] += n[d] * anv_c;
        }
    }
    // The chunks' sums added in chunk order into the columns of `slot` and their component
    // parts; returns the probe's sums b n . v per column.
    std::array<double, 3> close_columns(const std::array<Eigen::Index, 3>& slot, int chunks,
                                        std::size_t stride, const double* sums) {
        const int nc = layout_->restoration.components;
        const std::size_t buckets = 3 * static_cast<std::size_t>(layout_->rows);
        const std::size_t slots = layout_->field_sketch.cols();
        std::array<std::vector<double>, 3> by_volume, by_field, by_sum, by_moment;
        std::array<double, 3> probe_sum{{0, 0, 0}};
        for (int c = 0; c < 3; ++c) {
            by_volume[c].assign(slot[c] >= 0 ? nc : 0, 0.0);
            by_moment[c].assign(slot[c] >= 0 && layout_->drift_cancelled ? 3 * slots : 0, 0.0);
        }
        by_field = by_sum = by_volume;
        for (int chunk = 0; chunk < chunks; ++chunk) {
            const double* from_bucket = sums + chunk * stride;
            const double* from_component = from_bucket + buckets;
            const double* from_moment =
                from_component + kComponentSums * static_cast<std::size_t>(nc);
            const double* from_probe = from_moment + kMomentSums;
            for (int c = 0; c < 3; ++c) {
                if (slot[c] < 0) continue;
                double* column = column_data(slot[c]);
                for (int b = 0; b < layout_->rows; ++b) column[b] += from_bucket[3 * b + c];
                for (int k = 0; k < nc; ++k) {
                    by_volume[c][k] += from_component[9 * k + c];
                    by_field[c][k] += from_component[9 * k + 3 + c];
                    by_sum[c][k] += from_component[9 * k + 6 + c];
                }
                if (!by_moment[c].empty())
                    for (std::size_t m = 0; m < slots; ++m)
                        for (int d = 0; d < 3; ++d)
                            by_moment[c][3 * m + d] += from_moment[9 * m + 3 * c + d];
                probe_sum[c] += from_probe[c];
            }
        }
        for (int c = 0; c < 3; ++c) {
            if (slot[c] < 0) continue;
            volume_part_.push_back(std::move(by_volume[c]));
            field_part_.push_back(std::move(by_field[c]));
            sum_part_.push_back(std::move(by_sum[c]));
            moment_part_.push_back(std::move(by_moment[c]));
        }
        return probe_sum;
    }
    // RSS_n after the restoration, from the coefficients y of the basis vectors and the sketch of
    // n.r, and in `gain` the mean factor it multiplies the filtered noise by. Per component,
    // with V = (a . s) / 3 (the volume seen from the centroid) and the step's first-order volume
    // loss a . n.r, the step is read as a shrink by 1 - delta, delta = a . n.r / 3V: the volume
    // left is V (1 - delta)^3 and beta = 1 / (1 - delta). The residual is (1 - beta) s + beta n.r
    // over the component: each component's vertices hash into rows of their own (Layout::owner),
    // whose part of the sketch its beta scales. (With one beta, the count-weighted mean, for the
    // whole sketch, the 26 bones of libcgal-demo's `bones` at half an edge of noise, whose small
    // ones shrink far more than the large ones, had a modelled RSS_n falling with lambda: the
    // umbrella's one-click step was 3.16, 1.65x the best fixed step's error, now 0.48, 1.03x;
    // bench/results/issue11/auto-gap.md section 33.) An offset component moves by
    // t = a . n.r / sum a, to first order, and leaves the noise alone (beta = 1): the residual is
    // n.r - t. Which of the two restore_measure uses, it decides as here, on the volume ratio
    // (1 - delta)^-3.
    //
    // The residual is formed in the sketch's space, beta S(n.r) + (1 - beta) S(s) - t S(1), and
    // only then squared: |S(n.r)|^2 is off by about sqrt(2 / rows) of |n.r|^2, and n.r holds the
    // whole shrink that the restoration takes back. Squaring first and subtracting the shrink's
    // exact terms left that error on a difference of large terms: the 25,602-vertex two-density
    // sphere (one curvature-flow step, a quarter edge of noise along the normals), whose step
    // shrinks it by a quarter of its radius at time step 316, had a sketched RSS_n falling from
    // 0.78 at 79 to 0.22 at 316 and chose 316 (3.2x the best fixed step's error); formed in the
    // sketch's space it chooses what the exact RSS_n chooses (bench/results/issue11/auto-gap.md
    // section 13). The kSketchedComponents largest hold their fields' sketches in columns of
    // their own; the rest of those with rows of their own share one column (Layout::past_slots:
    // their rows are disjoint, so each row takes its owner's multiple). Kept in the squared form,
    // |n.r|^2 + (1 - beta)^2 |s|^2 + 2 beta (1 - beta) s . n.r or |n.r|^2 - 2 t 1 . n.r + t^2 N,
    // their shrink stayed in the sketched |n.r|^2 with its error: on twenty noisy spheres (12,840
    // vertices, tests/engine), four of them so, seven draws of the sketch in twelve chose 2.7-5.7x
    // too weak (one draw's risk lay 0.14-1.4 N sigma^2 above another's from time step 20 on); now
    // all twelve lie within 1.0073x (auto-gap.md section 53). The pooled components keep the
    // squared form: they share rows.
    //
    // Why a shrink and not the linear volume V - a . n.r: a shrinking convex shape keeps more
    // volume than the linear term says (V (1 - 3 delta + 3 delta^2 - ...)), so beta came out too
    // large, and since |s|^2 is about N times the squared size of the shape, (1 - beta)^2 |s|^2
    // overstated the residual: one curvature-flow step (L) on the 3 k-vertex sphere with a tenth
    // of an edge of noise, RSS_n at time step 25 was estimated 0.164 against 0.116 measured on
    // fair()'s result (same normals); now 0.1171, 0.1246 and 0.1312 at 26, 46 and 79 against
    // 0.1170, 0.1242 and 0.1298. The choice moved from 10.5 (error 1.30x the best fixed step's) to
    // 47 (1.01x; bench/results/issue11/auto-gap.md §5).
    //
    // fair() restores after every step of a recomputed operator and decides offset or scaling
    // on each step's own change; with Restoration::restorations the model does too
    // (step_change). Decided on the steps' total, three first-order curvature steps on the
    // study's torus with half an edge of noise switched at time step 2.7 where fair()'s third
    // step switches at 7-7.5, and the choice erred 1.5-1.6x the best step's error
    // (bench/results/issue11/auto-gap.md §26).
    double restored(const Eigen::Ref<const Eigen::VectorXd>& y,
                    const Eigen::Ref<const Eigen::VectorXd>& sketched, double& gain,
                    std::vector<char>* offsets = nullptr) const {
        gain = 1;
        const Layout& l = *layout_;
        if (offsets) offsets->assign(l.restoration.offset.begin(), l.restoration.offset.end());
        if (l.restoration.components == 0) return sketched.squaredNorm();
        double extra = 0, weighted_beta = 0, covered = 0;
        std::vector<double> beta_of(l.restoration.components, 1.0);
        // Layout::past_slots' offset components: -t, the multiple of their indicators' sketch
        // (their fields' is 1 - beta_of, 0 for an offset).
        std::vector<double> past_one(l.past_field_sketch.size() > 0 ? l.restoration.components
                                                                    : 0, 0.0);
        const Eigen::Index fields = l.field_sketch.cols();
        Eigen::VectorXd along_field = Eigen::VectorXd::Zero(fields), along_one = along_field;
        Eigen::VectorXd along_normal =
            Eigen::VectorXd::Zero(l.drift_cancelled ? 3 * fields : 0);
        for (int k = 0; k < l.restoration.components; ++k) {
            if (!(l.volume[k] > 0)) continue;
            double by_volume = 0, by_field = 0, by_sum = 0;
            for (Eigen::Index j = 0; j < used_; ++j) {
                by_volume += volume_part_[j][k] * y(j);
                by_field += field_part_[j][k] * y(j);
                by_sum += sum_part_[j][k] * y(j);
            }
            const double v = l.volume[k] / 3;
            const int offset = l.restoration.offset[k];
            const double left = std::max(1 - by_volume / (3 * v), 0.1);  // 1 - delta
            const double beta = 1 / left;
            const int slot = l.slot[k];
            covered += l.count[k];
            // The drift's translation (Restoration, "tau"): m = sum a n n.r first.
            Eigen::Vector3d m = Eigen::Vector3d::Zero();
            const bool drift_cancelled = slot >= 0 && l.restoration.drift_cancelled[k];
            if (drift_cancelled)
                for (Eigen::Index j = 0; j < used_; ++j)
                    for (int d = 0; d < 3; ++d) m(d) += moment_part_[j][3 * slot + d] * y(j);
            const bool offsets_k =
                offset == 1 || (offset == 2 && std::abs(step_change(beta)) <= kMaxOffsetChange);
            if (offsets) (*offsets)[k] = offsets_k ? 1 : 0;
            if (offsets_k) {
                const double t = by_volume / l.area[k];
                if (slot >= 0) along_one(slot) = -t;
                else if (l.past_slots[k]) past_one[k] = -t;
                else extra += t * t * l.shape2[k] - 2 * t * by_sum;
                if (drift_cancelled)
                    along_normal.segment<3>(3 * slot) =
                        -l.normal_moment[k].solve(m - t * l.sum_normal[k]);
                weighted_beta += l.count[k];
                continue;
            }
            if (drift_cancelled)
                along_normal.segment<3>(3 * slot) =
                    -l.normal_moment[k].solve(beta * m + (1 - beta) * l.field_normal[k]);
            if (slot >= 0) along_field(slot) = 1 - beta;
            else if (!l.past_slots[k])  // past_slots: 1 - beta_of[k], in the sketch's space below
                extra += (1 - beta) * (1 - beta) * l.field2[k] + 2 * beta * (1 - beta) * by_field;
            weighted_beta += beta * l.count[k];
            beta_of[k] = beta;
        }
        if (covered == 0) return sketched.squaredNorm();
        gain = (weighted_beta + (l.total - covered)) / l.total;
        // The pool's rows take its components' mean; rows shared by all, the whole mesh's.
        double pooled_beta = 0, pooled_count = 0;
        for (int k = 0; k < l.restoration.components; ++k) {
            if (!l.pooled[k]) continue;
            pooled_beta += beta_of[k] * l.count[k];
            pooled_count += l.count[k];
        }
        pooled_beta = pooled_count > 0 ? pooled_beta / pooled_count : 1.0;
        const double beta_all = covered == l.total ? weighted_beta / covered : 1.0;
        Eigen::VectorXd residual = sketched;
        for (Eigen::Index b = 0; b < residual.size(); ++b)
            residual(b) *= l.owner[b] >= 0        ? beta_of[l.owner[b]]
                           : l.owner[b] == kPooled ? pooled_beta
                                                   : beta_all;
        residual += l.field_sketch * along_field + l.one_sketch * along_one;
        for (Eigen::Index b = 0; b < l.past_field_sketch.size(); ++b) {
            const int k = l.owner[b];
            if (k >= 0 && l.past_slots[k])
                residual(b) += l.past_field_sketch(b) * (1 - beta_of[k]) +
                               l.past_one_sketch(b) * past_one[k];
        }
        if (l.drift_cancelled) residual += l.normal_sketch * along_normal;
        return extra + residual.squaredNorm();
    }

    // The largest volume change of the restorations that make up beta^3 (the steps' total), as
    // restore_measure measures each: their geometric mean times kLaterStepsLoseMore, since the
    // later steps, on a smoother mesh, lose more. On that torus at time step 7 the three changes
    // were 6.4, 9.3 and 9.7 %, the last 1.15x their mean; 1.3 leaves a margin, since a step past
    // the switch is rescaled and the torus's error jumps 4-9x (7.5 and 8).
    static constexpr double kLaterStepsLoseMore = 1.3;
    double step_change(double beta) const {
        const int restorations = layout_->restoration.restorations;
        if (restorations == 1) return beta * beta * beta - 1;
        return kLaterStepsLoseMore * (std::pow(beta, 3.0 / restorations) - 1);
    }

    // What a sketch's rows and restoration are: buckets, signs, the restoration's fields and
    // their sketches; fixed once made, so that sketches of the same rows can share it.
    struct Layout {
        Restoration restoration;
        // Per component: a . s, sum a w (w the offset's shape, 1 without), |s|^2, N and |w|^2.
        std::vector<double> volume, area, field2, count, shape2;
        // Per drift-cancelled component: P = sum a n n^T (factored), q_s = sum a n s and
        // q_1 = sum a w n.
        std::vector<Eigen::LDLT<Eigen::Matrix3d>> normal_moment;
        std::vector<Eigen::Vector3d> field_normal, sum_normal;
        bool drift_cancelled = false;  // for some sketched component (Restoration)
        Eigen::MatrixXd normal_sketch;  // then: n_d of each slot's vertices, 3 columns per slot
        // The kSketchedComponents largest components' slots (-1: not sketched) and the sketches
        // of their fields s and indicators 1, one column per slot.
        std::vector<int> slot;
        Eigen::MatrixXd field_sketch, one_sketch;
        // On a sketch that is not exact, the components past the slotted ones that still own rows
        // of their own (not pooled): per component whether it is one, and the sketches of their
        // fields s and w, one column for all (their rows are disjoint). Empty when there are none.
        std::vector<char> past_slots;
        Eigen::VectorXd past_field_sketch, past_one_sketch;
        double total = 0;  // data vertices
        int rows = 0;
        bool exact = false;
        std::vector<int> bucket;  // per vertex, -1 off the data
        std::vector<float> sign;
        // Per row: the restored component whose vertices alone it holds, kPooled for the pool
        // of the components past the own_rows() largest, -1 for the vertices no restoration
        // covers (or for all, when the groups overrun the rows; rows_of()).
        std::vector<int> owner;
        std::vector<char> pooled;  // per component: its rows are the pool's
    };
    static constexpr int kPooled = -2;
    // Components that get rows of their own past 8192 data vertices: the largest, up to a quarter
    // of the rows, with a row's share of the vertices at least. The rest share a pool, which their
    // mean beta scales: the small ones, which collapse first, alike in size and so in shrink.
    // (With one factor for all rows, the umbrella's estimate on 2,500 noisy icosahedra beside a
    // sphere, 30 k vertices, ran to its cap of 296 Lanczos steps, 3.4 s against 0.03 s for the
    // step, and on 1,500 beside a 164 k-vertex sphere 4.5 s against 0.16 s; pooled: 11 steps and
    // 0.05 s, 21 steps and 0.29 s. ManySmallComponentsPoolTheirRows.)
    static int own_rows(int rows) { return std::max(1, rows / 4 - 2); }
    // Rows per group of data vertices: in proportion to its vertices, at least one for a group
    // that has any. Empty when the groups' one row each would overrun the rows (they then share
    // all rows; own_rows() keeps the groups to a quarter of the rows).
    static std::vector<int> rows_of(const std::vector<double>& count, double total, int rows) {
        const int groups = static_cast<int>(count.size());
        std::vector<int> width(groups, 0);
        int used = 0, largest = 0;
        for (int g = 0; g < groups; ++g) {
            if (!(count[g] > 0)) continue;
            width[g] = std::max(1, static_cast<int>(rows * count[g] / total));
            used += width[g];
            if (width[g] > width[largest]) largest = g;
        }
        if (width[largest] + rows - used < 1) return {};
        width[largest] += rows - used;  // the rounding's rows (at most one per group off)
        return width;
    }
    static std::shared_ptr<const Layout> layout(const Context& ctx, int data_count,
                                                Restoration restoration) {
        auto made = std::make_shared<Layout>();
        Layout& l = *made;
        l.restoration = std::move(restoration);
        const Restoration& r = l.restoration;
        const int nc = r.components;
        l.volume.assign(nc, 0.0);
        l.area.assign(nc, 0.0);
        l.field2.assign(nc, 0.0);
        l.count.assign(nc, 0.0);
        l.shape2.assign(nc, 0.0);
        for (std::size_t i = 0; i < r.component.size(); ++i) {
            const int k = r.component[i];
            if (k < 0) continue;
            const double w = r.shape.empty() ? 1.0 : r.shape[i];
            l.volume[k] += r.area[i] * r.field[i];
            l.area[k] += r.area[i] * w;
            l.field2[k] += r.field[i] * r.field[i];
            l.count[k] += 1;
            l.shape2[k] += w * w;
        }
        l.total = data_count;
        l.exact = data_count <= kSketch;
        l.rows = l.exact ? data_count : kSketch;
        l.bucket.assign(ctx.n, -1);
        l.sign.assign(ctx.n, 1.0f);
        l.owner.assign(l.rows, -1);
        // The restored components by size (ties: the lower index).
        std::vector<int> by_size(nc);
        for (int k = 0; k < nc; ++k) by_size[k] = k;
        std::stable_sort(by_size.begin(), by_size.end(),
                         [&](int a, int b) { return l.count[a] > l.count[b]; });
        l.pooled.assign(nc, 0);
        if (!l.exact)  // the largest, each of at least a row's share of the vertices, own theirs
            for (int s = 0; s < nc; ++s)
                l.pooled[by_size[s]] =
                    s >= own_rows(l.rows) || l.count[by_size[s]] * l.rows < l.total;
        // Groups: component k < nc, the pool (nc), the vertices no restoration covers (nc + 1).
        const auto group = [&](int i) {
            if (static_cast<std::size_t>(i) >= r.component.size() || r.component[i] < 0)
                return nc + 1;
            return l.pooled[r.component[i]] ? nc : r.component[i];
        };
        // Each component hashes into rows of its own, so that restored() can scale its part of
        // the sketch by its own beta (one row per vertex when exact).
        std::vector<double> group_count(nc + 2, 0.0);
        for (int k = 0; k < nc; ++k) group_count[l.pooled[k] ? nc : k] += l.count[k];
        group_count[nc + 1] = std::max(0.0, l.total - std::accumulate(l.count.begin(),
                                                                      l.count.end(), 0.0));
        const std::vector<int> width = l.exact ? std::vector<int>()
                                               : rows_of(group_count, l.total, l.rows);
        const bool own_rows_kept = !width.empty();
        std::vector<int> start(width.size() + 1, 0);
        for (std::size_t g = 0; g < width.size(); ++g) start[g + 1] = start[g] + width[g];
        int next = 0;
        for (int i = 0; i < ctx.n; ++i) {
            if (!ctx.data[i]) continue;
            const std::uint64_t h = splitmix64(static_cast<std::uint64_t>(i) + 0x5bd1e995ull);
            const int g = group(i);
            if (l.exact) {
                l.bucket[i] = next++;
            } else if (width.empty()) {
                l.bucket[i] = static_cast<int>(h % static_cast<std::uint64_t>(l.rows));
            } else {
                l.bucket[i] =
                    start[g] + static_cast<int>(h % static_cast<std::uint64_t>(width[g]));
            }
            if (!l.exact) l.sign[i] = (h >> 40) & 1 ? 1.0f : -1.0f;
            if ((l.exact || !width.empty()) && g <= nc)
                l.owner[l.bucket[i]] = g < nc ? g : kPooled;
        }
        // The largest restored components, whose fields are sketched.
        l.slot.assign(nc, -1);
        const int sketched = std::min(nc, kSketchedComponents);
        for (int s = 0; s < sketched; ++s) l.slot[by_size[s]] = s;
        l.field_sketch = Eigen::MatrixXd::Zero(l.rows, sketched);
        l.one_sketch = Eigen::MatrixXd::Zero(l.rows, sketched);
        for (int k = 0; k < nc; ++k)
            l.drift_cancelled =
                l.drift_cancelled ||
                (l.slot[k] >= 0 && !r.drift_cancelled.empty() && r.drift_cancelled[k]);
        std::vector<Eigen::Matrix3d> moments(l.drift_cancelled ? nc : 0, Eigen::Matrix3d::Zero());
        l.field_normal.assign(nc, Eigen::Vector3d::Zero());
        l.sum_normal.assign(nc, Eigen::Vector3d::Zero());
        if (l.drift_cancelled) l.normal_sketch = Eigen::MatrixXd::Zero(l.rows, 3 * sketched);
        for (std::size_t i = 0; i < r.component.size(); ++i) {
            const int k = r.component[i];
            if (k < 0 || l.slot[k] < 0 || l.bucket[i] < 0) continue;
            l.field_sketch(l.bucket[i], l.slot[k]) += static_cast<double>(l.sign[i]) * r.field[i];
            const double w = r.shape.empty() ? 1.0 : r.shape[i];
            l.one_sketch(l.bucket[i], l.slot[k]) += static_cast<double>(l.sign[i]) * w;
            if (!l.drift_cancelled || !r.drift_cancelled[k]) continue;
            const Eigen::Vector3d n = r.normals->row(i).transpose();
            for (int d = 0; d < 3; ++d)
                l.normal_sketch(l.bucket[i], 3 * l.slot[k] + d) +=
                    static_cast<double>(l.sign[i]) * n(d);
            moments[k] += r.area[i] * n * n.transpose();
            l.field_normal[k] += r.area[i] * r.field[i] * n;
            l.sum_normal[k] += r.area[i] * w * n;
        }
        for (const Eigen::Matrix3d& p : moments) l.normal_moment.emplace_back(p);
        l.past_slots.assign(nc, 0);
        bool any_past = false;
        for (int k = 0; k < nc && own_rows_kept; ++k) {
            l.past_slots[k] = l.slot[k] < 0 && !l.pooled[k] && l.count[k] > 0;
            any_past = any_past || l.past_slots[k];
        }
        if (any_past) {
            l.past_field_sketch = Eigen::VectorXd::Zero(l.rows);
            l.past_one_sketch = Eigen::VectorXd::Zero(l.rows);
            for (std::size_t i = 0; i < r.component.size(); ++i) {
                const int k = r.component[i];
                if (k < 0 || !l.past_slots[k] || l.bucket[i] < 0) continue;
                const double sign = static_cast<double>(l.sign[i]);
                l.past_field_sketch(l.bucket[i]) += sign * r.field[i];
                l.past_one_sketch(l.bucket[i]) += sign * (r.shape.empty() ? 1.0 : r.shape[i]);
            }
        }
        return made;
    }
    explicit Sketch(std::shared_ptr<const Layout> layout) : layout_(std::move(layout)) {}

    std::shared_ptr<const Layout> layout_;
    std::vector<std::vector<double>> volume_part_, field_part_, sum_part_;  // per column, component
    // Per column, 3 per sketched component (its m_d; 0 unless drift_cancelled); empty when none is.
    std::vector<std::vector<double>> moment_part_;
    std::vector<double> chunk_sums_;  // add()'s sums per chunk (scratch, kept between steps)
    // The sketched basis vectors, layout_->rows x kSketchBlock each: blocks rather than one
    // matrix grown by doubling, whose copy held the old and the new matrix at once (1.5x the final
    // size: 150 bytes per vertex on the 1 M-face torus, whose processes run 212 steps).
    std::vector<Eigen::MatrixXd> blocks_;
    double* column_data(Eigen::Index column) {
        return blocks_[static_cast<std::size_t>(column / kSketchBlock)].col(column % kSketchBlock).data();
    }
    Eigen::Index used_ = 0;
    std::array<std::vector<int>, 3> index_;  // [c][j]: column of basis vector j of process c
};

struct Curves {
    std::vector<double> rss, trace;  // rss NaN where not evaluated
    std::vector<double> gain;        // the restoration's factor on the filtered noise
    std::size_t first = 0;           // below: the filter keeps over 98 % (not evaluated)
    std::size_t reach = 0;           // [first, reach) converged since the last checkpoint
    std::size_t near = 0;  // at the next checkpoint, points below: two checkpoints judge them,
                           // points above: three (kNear)
};

struct Search {
    std::vector<double> grid;
    double minimizer = 0;     // of the risk over the converged points
    double converged_to = 0;  // largest converged lambda
    double count = 0;
    bool capped = true;  // stopped by kMaxSteps before the minimizer settled
    // Stopped because the risk cannot fall below StrengthProblem::chosen_below; risk_bound is
    // the checkpoint's bound on the excess risk (header, "An estimate that cannot win").
    bool out_of_reach = false;
    double risk_bound = 0;
};

// How far past the last checkpoint's converged points a checkpoint judges. A point counts as
// converged when its values moved by less than the tolerance since the last checkpoint, so a
// checkpoint can judge only points the last one evaluated. Up to kNear grid points (1.2 decades
// of lambda) past the last checkpoint's converged ones, agreement with the last checkpoint
// settles a point; from there up to kFar, it must also have agreed with the one before (three
// checkpoints in a row). Judging to kNear alone (the rule until session 11) let the converged
// range advance 12 points every other checkpoint at most: the 1 M-face torus's umbrella and
// scale-dependent L^2 steps needed 212-296 Lanczos steps at every noise level where the
// three-checkpoint rule settles at 78-152, and 160 automatic runs of the study's meshes took
// 7,764 steps against 6,068 with kFar (and kMargin 2), their errors within -1.5 % and +0.9 % of
// each other's. Two checkpoints' agreement out to 24 points stopped on plateaus (the 1 M-face
// torus 2.4-20x off; auto-gap.md section 10).
constexpr std::size_t kNear = 12;
constexpr std::size_t kFar = 24;

// The risk curve at a checkpoint: traces everywhere, RSS_n from where the filter starts to act
// up to a few points past those that have converged since the last checkpoint.
Curves checkpoint(const Context& ctx, const Lanczos& u, const Lanczos& z, const Perturbation* mc,
                  const Sketch& sketch, const Search& s, const Curves& last, const Curves& before,
                  int steps) {
    Curves now;
    now.trace = mc ? divergences(ctx, u, *mc, s.count, s.grid) : traces(ctx, z, s.count, s.grid);
    while (now.first + 1 < s.grid.size() && now.trace[now.first + 1] > 0.98 * s.count)
        ++now.first;
    // Evaluate up to kFar points past the last checkpoint's converged ones (the points the last
    // checkpoint evaluated can be judged now, see kNear).
    now.near = std::min(s.grid.size(), std::max(last.reach, now.first) + kNear);
    const std::size_t end = std::min(s.grid.size(), std::max(last.reach, now.first) + kFar);
    // Every point is evaluated afresh, also those that had converged: two checkpoints can agree
    // while both are off. The 51 k-face sphere with a quarter edge of noise in all directions
    // (two first-order curvature-flow steps) agreed within 2 % at time step 25 after 15 and 21
    // Lanczos steps (RSS_n 1.009 and 1.028 N sigma^2) and fell to 0.953 by 40 steps. Kept at
    // their first converged values (until session 27, to save the sketch's product), the
    // points there put the minimizer at 7.9 and the final grid's risk, evaluated afresh, fell to
    // its top edge (19.9, 1.215x the best fixed step's error); re-judged, they settle at 78
    // Lanczos steps on 54 (1.019x; bench/results/issue11/auto-gap.md section 27).
    now.rss = sketch.rss(ctx, u, s.grid, now.first, end, &now.gain);
    const bool slow = ctx.c.order >= 2 && !ctx.p.explicit_integration;
    // Geometric from kConvergedSquaredSpectrum at kStrictSteps towards kConverged at kRelaxedSteps.
    const double past = std::max(0.0, std::log(static_cast<double>(steps) / kStrictSteps) /
                                          std::log(static_cast<double>(kRelaxedSteps) / kStrictSteps));
    const double converged =
        slow ? std::min(kConverged, kConvergedSquaredSpectrum *
                                        std::pow(kConverged / kConvergedSquaredSpectrum, past))
             : kConverged;
    now.reach = now.first;
    for (std::size_t g = now.first; g < end; ++g) {
        const auto agree = [&](const Curves& later, const Curves& earlier) {
            return g < earlier.rss.size() && std::isfinite(earlier.rss[g]) &&
                   std::abs(later.rss[g] - earlier.rss[g]) <= converged * later.rss[g] &&
                   std::abs(later.trace[g] - earlier.trace[g]) <=
                       converged * std::max(s.count - later.trace[g], 1e-3 * s.count);
        };
        const bool settled = agree(now, last) && (g < last.near || agree(last, before));
        if (!settled) break;
        now.reach = g + 1;
    }
    return now;
}

// The movement on the later steps' operator alone (StrengthProblem::residual_on_later_steps):
// its own process and sketch, stepped beside the others.
// Always paired: it steps in step_group with the movement and the perturbed movement, its
// weights (s w_mean - w_first) / (s - 1) formed in the pass (its operator keeps its masses only).
struct LaterSteps {
    SparseOperator op;
    StrengthProblem problem;
    std::unique_ptr<Context> ctx;
    Lanczos u;
    std::unique_ptr<Sketch> sketch;
    Blend blend;
};

// A bound on the final excess risk from a checkpoint's curves (header, "An estimate that cannot
// win"). Between two converged grid points the residual, the divergence and the restoration's
// gain on it each move one way (the gain steps up where a component's restoration switches to
// scaling, and the risk can dip just below that switch: the sponge's scale-dependent steps at
// half an edge, 0.016 of N sigma^2 under both grid points' values), so the risk there is at
// least the lesser residual plus the least product of a gain and a divergence at the two ends.
// Past the last converged point it is at least the residual there.
double excess_risk_bound(const Curves& now, double count, double sigma) {
    const double s2 = sigma * sigma;
    double least = now.rss[now.reach - 1];
    for (std::size_t g = now.first; g + 1 < now.reach; ++g) {
        const double a = now.gain[g], b = now.gain[g + 1];
        const double c = now.trace[g], d = now.trace[g + 1];
        const double filtered = std::min({a * c, a * d, b * c, b * d});
        least = std::min(least, std::min(now.rss[g], now.rss[g + 1]) + 2 * s2 * filtered);
    }
    return least / (count * s2) - 1;
}

// Runs both Lanczos processes, with the sketched risk at checkpoints, until the risk's
// minimizer has settled inside the converged part of the curves. `later` (optional) steps
// along, as many steps as the movement; from kLaterRuleSteps steps its residual's risk also
// has to settle before the search stops.
Search search(Context& ctx, Lanczos& u, Lanczos& z, Perturbation* mc, Sketch& sketch,
              const Positions& normals, double count, double sigma, LaterSteps* later = nullptr) {
    Search s;
    s.count = count;
    const double top = ctx.p.explicit_integration ? std::min(ctx.p.max_time_step, 1e7) : 1e7;
    for (double l = 1e-4; l < top; l *= std::pow(10.0, kGridDecades)) s.grid.push_back(l);
    if (ctx.p.explicit_integration) s.grid.push_back(top);
    Curves last, before;
    double previous_minimizer = 0;
    bool previous_at_edge = false;
    int next_check = 6;
    Positions product;  // the processes' products, one at a time (unpaired)
    // The movement's product shares its pass over the operator with the probes' (linear
    // operator) or the perturbed movement's (Monte-Carlo divergence).
    Context* partner_ctx = mc ? mc->ctx.get() : &ctx;
    Lanczos& partner = mc ? mc->u : z;
    const bool paired = mc ? mc->paired : pairable(ctx, ctx);
    const char* free = ctx.p.free->data();
    for (int j = 0; j < kMaxSteps; ++j) {
        const bool u_active = u.active[0] || u.active[1] || u.active[2];
        const bool z_active = !mc && (z.active[0] || z.active[1] || z.active[2]);
        const bool mc_active = mc && (mc->u.active[0] || mc->u.active[1] || mc->u.active[2]);
        const bool partner_active = mc ? mc_active : z_active;
        // The pass of the sketch forms the pending basis vectors of u and of the second process
        // (Lanczos::pending): paired, both of step_pair's; else the perturbed movement's.
        Lanczos* second = paired ? &partner : mc_active ? &mc->u : nullptr;
        // The later steps' process goes into its own sketch in the same pass.
        const bool later_active =
            later && (later->u.active[0] || later->u.active[1] || later->u.active[2]);
        if (u_active || (second && partner_active))
            sketch.add(u, normals, free, ctx.p.op->threads, mc ? &mc->sign : nullptr,
                       mc ? &mc->w : nullptr, second, mc && second ? &mc->w_perturbed : nullptr,
                       later_active ? later->sketch.get() : nullptr,
                       later_active ? &later->u : nullptr);
        else if (later_active)
            later->sketch->add(later->u, normals, free, ctx.p.op->threads);
        // Paired, both products come from step_pair even when one process has broken down
        // (the perturbed operator has given its pattern back: apply_dot cannot run on it).
        if (paired && later && (u_active || partner_active || later_active)) {
            step_group<3, true>({{&ctx, partner_ctx, later->ctx.get()}},
                                {{&u, &partner, &later->u}}, j, later->blend);
        } else if (paired && (u_active || partner_active)) {
            step_pair(ctx, u, *partner_ctx, partner, j);
        } else {
            if (u_active) step(ctx, u, j, product, true);
            if (z_active) step(ctx, z, j, product);
            if (mc_active) step(*mc->ctx, mc->u, j, product, true);
        }
        if (ctx.p.progress) ctx.p.progress(0.7 * (1 - 16.0 / (16.0 + j)));
        const bool exhausted =
            !(u.active[0] || u.active[1] || u.active[2] ||
              (mc ? mc->u.active[0] || mc->u.active[1] || mc->u.active[2]
                  : z.active[0] || z.active[1] || z.active[2]));
        if (j + 1 < next_check && !exhausted) continue;
        next_check = std::min(kMaxSteps,
                              std::max(j + 2, static_cast<int>(kCheckpointGrowth * (j + 1))));
        Curves now = checkpoint(ctx, u, z, mc, sketch, s, last, before, j + 1);
        if (exhausted) {  // T is exact: every evaluated point holds
            now.reach = now.first;
            while (now.reach < now.rss.size() && std::isfinite(now.rss[now.reach])) ++now.reach;
        }
        before = last;
        last = now;
        if (now.reach == now.first) continue;
        std::vector<double> risk;
        for (std::size_t g = now.first; g < now.reach; ++g)
            risk.push_back(now.rss[g] + 2 * sigma * sigma * now.gain[g] * now.trace[g]);
        const std::size_t best = now.first + argmin(risk);
        if (!later) {
            const double bound = excess_risk_bound(now, count, sigma) - kBoundSlack;
            if (bound > ctx.p.chosen_below) {
                s.out_of_reach = true;
                s.risk_bound = bound;
                s.capped = false;
                break;
            }
        }
        s.minimizer = s.grid[best];
        s.converged_to = s.grid[now.reach - 1];
        // A minimizer at the end of the converged points is only a bound (the risk was still
        // falling there): an interior one past it at the next checkpoint confirms it. Waiting
        // for a second interior one cost 40 % more Lanczos steps (bunny Loop x2, 1.2 M faces:
        // 78 against 56; the chosen time steps moved by up to 15 %, 140 automatic runs of the
        // study's errors by at most 1 %: bench/results/issue11/auto-gap.md).
        const bool settled = std::abs(s.minimizer / previous_minimizer - 1) < 0.3 ||
                             (previous_at_edge && s.minimizer >= previous_minimizer);
        previous_minimizer = s.minimizer;
        previous_at_edge = best + 1 == now.reach;
        const bool complete = exhausted || now.reach == s.grid.size();
        // (1.0001: the grid's products round, so k points apart is k steps to a few ulps)
        const double short_by = kMargin * s.minimizer / s.converged_to;
        const double short_limit = std::pow(10.0, kGridDecades * kShortGridPoints) * 1.0001;
        if (settled && short_by > 1 && short_by <= short_limit)
            next_check = std::min(next_check,
                                  std::max(j + 2, static_cast<int>(kShortGrowth * (j + 1))));
        // The risk's rise from the minimum at `at` to the last point of r (kSketchFlat).
        const auto rise = [&](const std::vector<double>& r, std::size_t at) {
            return (r.back() - r[at]) / (count * sigma * sigma);
        };
        // risen: the rise at the last point judged; may_run_on: the converged points end there.
        const auto enough = [&](double risen, bool may_run_on) {
            if (may_run_on && !sketch.exact() && risen < kSketchFlat) return false;
            return s.converged_to >= kMargin * s.minimizer;
        };
        if (!complete && !(settled && enough(rise(risk, best - now.first), true))) continue;
        if (later && ctx.p.steps >= kLaterRuleSteps) {
            // The risk the choice minimizes (risk_minimum): the later steps' residual with the
            // mean's divergence, over the converged points up to kLaterReach x the mean's
            // minimizer; the search runs on until it too has kMargin of converged points.
            std::size_t top = best + 1;
            while (top < now.reach && s.grid[top] <= kLaterReach * s.grid[best]) ++top;
            const std::vector<double> rss =
                later->sketch->rss(*later->ctx, later->u, s.grid, now.first, top);
            risk.clear();
            for (std::size_t g = now.first; g < top; ++g)
                risk.push_back(rss[g] + 2 * sigma * sigma * now.gain[g] * now.trace[g]);
            const std::size_t later_best = argmin(risk);
            s.minimizer = s.grid[now.first + later_best];
            // Past kLaterReach the converged points do not count: there it cannot run on.
            if (!complete && !enough(rise(risk, later_best), top == now.reach)) continue;
        }
        s.capped = false;
        break;
    }
    if (s.converged_to == 0) {  // nothing converged within the cap: take what there is
        s.converged_to = s.grid.front();
        s.minimizer = s.grid.front();
    }
    return s;
}

}  // namespace

// The rule and its reach: auto_strength.h.
void choose(StrengthEstimate& e, bool strongest_within_error, double reach) {
    const int m = static_cast<int>(e.grid.size());
    std::vector<double> risk(m);
    const double s2 = e.noise_level * e.noise_level;
    for (int g = 0; g < m; ++g) risk[g] = e.rss[g] + 2 * s2 * e.trace[g];
    const int best = argmin(risk);
    e.excess_risk = risk[best] / (e.data_count * s2) - 1;
    if (strongest_within_error) {
        int strongest = best;
        for (int g = best + 1; g < m && e.grid[g] <= reach * e.grid[best]; ++g)
            if (risk[g] <= risk[best] + s2 * std::sqrt(2 * std::abs(e.trace[best] - e.trace[g])))
                strongest = g;
        if (strongest != best) {
            e.time_step = e.grid[strongest];
            e.trace_fraction = e.trace[strongest] / e.data_count;
            return;
        }
    }
    double log_lambda = std::log(e.grid[best]);
    if (best > 0 && best + 1 < m) {
        const double a = risk[best - 1], b = risk[best], c = risk[best + 1];
        const double h = std::log(e.grid[best + 1] / e.grid[best]);
        const double curvature = a - 2 * b + c;
        if (curvature > 0) log_lambda += std::max(-1.0, std::min(1.0, 0.5 * (a - c) / curvature)) * h;
    }
    e.time_step = std::exp(log_lambda);
    e.trace_fraction = e.trace[best] / e.data_count;
}

// The restoration's fields (see Sketch::Restoration) for the components fair() restores.
Sketch::Restoration restoration(const StrengthProblem& p, const Positions& normals) {
    Sketch::Restoration r;
    const int n = p.data_vertices;
    r.component.assign(n, -1);
    r.field.assign(n, 0.0);
    r.area.assign(n, 0.0);
    if (p.restored.empty()) return r;
    for (const Triangle& t : p.mesh->faces()) {
        const Vec3 a = row(*p.x, t[0]);
        const double area = 0.5 * (row(*p.x, t[1]) - a).cross(row(*p.x, t[2]) - a).norm();
        for (int k = 0; k < 3; ++k) r.area[t[k]] += area / 3;
    }
    // The centroid restore_measure scales about: the enclosed solid's. (The vertices' area-weighted
    // centroid lay 7 % of the radius off it on the 3 k-vertex two-density sphere with half an edge
    // of noise, and the estimated residual of a rescaled step fell 1-5 % short of fair()'s.)
    std::vector<Eigen::RowVector3d> centroid(p.offset.size(), Eigen::RowVector3d::Zero());
    std::vector<char> found(p.offset.size(), 0);
    for (const Component& component : p.mesh->components()) {
        if (component.vertices.empty() || component.vertices.front() >= n) continue;
        const int k = p.restored[component.vertices.front()];
        if (k < 0 || found[k]) continue;
        centroid[k] = component_centroid(*p.mesh, component, *p.x).transpose();
        found[k] = std::isfinite(centroid[k].squaredNorm());
    }
    for (int i = 0; i < n; ++i) {
        const int k = p.restored[i];
        if (k < 0 || !(*p.free)[i] || !found[k]) continue;
        r.component[i] = k;
        r.field[i] = normals.row(i).dot(p.x->row(i) - centroid[k]);
    }
    if (p.offset_shape) {
        r.shape.assign(n, 1.0);
        for (int i = 0; i < n; ++i)
            if (r.component[i] >= 0) r.shape[i] = (*p.offset_shape)[i];
    }
    r.offset = p.offset;
    r.restorations = std::max(1, p.restorations);
    r.components = static_cast<int>(p.offset.size());
    r.drift_cancelled.assign(p.offset.size(), 0);
    for (std::size_t k = 0; k < p.offset.size(); ++k)
        r.drift_cancelled[k] = k < p.cancel_drift.size() && p.cancel_drift[k] && found[k];
    r.normals = &normals;
    return r;
}

// Umbrella passes (half steps) smoothing the copy the normals are taken from.
constexpr int kSmoothingPasses = 4;

StrengthEstimate risk_minimum(const StrengthProblem& p, const Positions& normals, StrengthEstimate e,
                              bool model_weights = true, SparseOperator* assembled = nullptr,
                              const SparseOperator* first_op = nullptr,
                              SparseOperator* later_op = nullptr);

Positions strength_normals(const StrengthProblem& p) {
    return robust_normals(*p.mesh, smoothed_copy(*p.op, *p.x, p.data_vertices, kSmoothingPasses));
}

double noise_level(const StrengthProblem& p, const Positions& normals) {
    std::vector<char> use(p.data_vertices, 0);
    for (int i = 0; i < p.data_vertices; ++i) use[i] = (*p.free)[i];
    return estimate_noise(*p.op, *p.mesh, *p.x, normals, use);
}

StrengthEstimate estimate_strength(const StrengthProblem& p) {
    StrengthEstimate e;
    Positions computed;
    if (!p.normals) computed = strength_normals(p);
    const Positions& normals = p.normals ? *p.normals : computed;
    e.noise_level = p.noise_level > 0 ? p.noise_level : noise_level(p, normals);
    if (!(e.noise_level > 0)) return e;
    if (!p.pilot || !p.assemble_at) return risk_minimum(p, normals, e);
    SparseOperator model = *p.op, later_op;
    model_steps(p, *p.x, model, &later_op);
    bool usable = model.size() == p.op->size();
    for (int i = 0; i < model.size() && usable; ++i) usable = !(*p.free)[i] || model.mass[i] > 0;
    StrengthProblem q = p;
    q.op = usable ? &model : p.op;  // else (a row lost its mass) the first step's operator
    q.pilot = usable;
    // L^2 steps of the curvature flow: the residual from the later steps' operator alone
    // (header, "Several steps").
    const bool later = usable && p.residual_on_later_steps && p.order >= 2 &&
                       !p.explicit_integration && !p.weight && later_op.size() > 0;
    if (!later) later_op = SparseOperator();
    return risk_minimum(q, normals, e, true, nullptr, later ? p.op : nullptr,
                        later ? &later_op : nullptr);
}

// The later steps' process for problem p (its operator the steps' mean, `first` the first
// step's) on `op`, the later steps' operator (model_steps), which it takes over, or nothing where
// it cannot run paired (step_group) or its operator loses a mass. Started before the perturbed
// problem is assembled, so that `op` keeps only its masses through that assembly's peak. Its
// sketch (later_sketch) shares the rows and restoration of the movement's.
std::unique_ptr<LaterSteps> later_steps(const StrengthProblem& p, const Context& ctx,
                                        const SparseOperator& first, SparseOperator& op) {
    if (p.steps < 2 || !weights_of(*p.op) || !weights_of(first) ||
        first.column != p.op->column || first.row_start != p.op->row_start)
        return nullptr;
    auto later = std::make_unique<LaterSteps>();
    later->op = std::move(op);
    SparseOperator& taken = later->op;
    if (taken.size() != p.op->size()) return nullptr;
    for (int i = 0; i < taken.size(); ++i)
        if ((*p.free)[i] && !(taken.mass[i] > 0)) return nullptr;
    taken.threads = p.op->threads;
    later->problem = p;
    later->problem.op = &taken;
    later->ctx.reset(new Context{later->problem, ctx.c, ctx.data, Positions(), ctx.n, ctx.squared,
                                 {}, Positions()});
    later->ctx->c.op = &taken;
    if (!pairable(ctx, *later->ctx)) return nullptr;  // also: the same rows and columns as p's
    start_movement(*later->ctx, later->u);
    // step_group reads the columns from p's operator and forms the weights from the mean's and
    // the first step's: the later operator keeps its masses only.
    const double s = p.steps;
    later->blend = Blend{weights_of(*p.op), weights_of(first), s / (s - 1), -1 / (s - 1)};
    std::vector<int>().swap(taken.row_start);
    std::vector<int>().swap(taken.column);
    std::vector<double>().swap(taken.weight);
    return later;
}

// The risk curve of problem p (noise level in e) and its minimizer. With soft weights, L^2 runs
// on the model of Context::weight_root unless !model_weights; `assembled` goes to perturb().
// With `first_op` (p's operator the steps' mean of it and the later steps', model_steps; L^2
// without soft weights) and `later_op` (the later steps' operator, taken and released) the
// residual comes from the later steps' operator alone, the divergence from p's (header, "Several
// steps").
StrengthEstimate risk_minimum(const StrengthProblem& p, const Positions& normals, StrengthEstimate e,
                              bool model_weights, SparseOperator* assembled,
                              const SparseOperator* first_op, SparseOperator* later_op) {
    const StrengthEstimate given = e;
    Context ctx{p, LinearSystem{}, {}, Positions(), p.op->size(), false, {}, Positions()};
    ctx.c.op = p.op;
    ctx.c.free = *p.free;
    ctx.c.lambda_dt = p.length_unit;
    ctx.c.order = p.order;
    ctx.squared = p.order >= 2 && !p.explicit_integration;
    ctx.data.assign(ctx.n, 0);
    double count = 0;  // data rows
    for (int i = 0; i < ctx.n; ++i) {
        if (!(*p.free)[i] || i >= p.data_vertices) continue;
        ctx.data[i] = 1;
        ++count;
    }
    if (count == 0) return e;
    bool weighted = false;  // soft weights: Context::weight_root
    for (int i = 0; i < ctx.n && ctx.squared && !weighted; ++i)
        weighted = (*p.free)[i] && !(d_of(p, i) == p.op->mass[i]);
    if (weighted && !model_weights) ctx.squared = false;  // the processes run on G itself
    bool uniform = true;  // the model is exact
    if (weighted && model_weights) {
        ctx.weight_root.assign(ctx.n, 1.0);
        double first = 0;
        for (int i = 0; i < ctx.n; ++i) {
            if (!(*p.free)[i]) continue;
            ctx.weight_root[i] = std::pow(p.op->mass[i] / d_of(p, i), -0.5 / p.order);
            if (first == 0) first = ctx.weight_root[i];
            uniform = uniform && std::abs(ctx.weight_root[i] - first) <= 1e-12 * first;
        }
    }
    if (ctx.squared) {
        ctx.c.order = 1;
        ctx.c.lambda_dt = p.order == 2 ? std::sqrt(p.length_unit)
                                       : std::pow(p.length_unit, 1.0 / p.order);
    }
    e.data_count = count;

    Lanczos u, z;
    start_movement(ctx, u);
    std::unique_ptr<LaterSteps> later =
        first_op && later_op && ctx.squared && ctx.weight_root.empty()
            ? later_steps(p, ctx, *first_op, *later_op)
            : nullptr;
    if (later_op) *later_op = SparseOperator();
    const std::unique_ptr<Perturbation> mc = perturb(ctx, normals, e.noise_level, assembled);
    if (mc) z.active = {{false, false, false}};  // the divergence replaces the probes
    else start_probes(ctx, z, count);
    Sketch sketch(ctx, static_cast<int>(count), restoration(p, normals));
    if (!mc || !mc->paired) later.reset();  // it steps only in step_group, beside the others
    if (later) later->sketch = Sketch::like(sketch);
    const Search found =
        search(ctx, u, z, mc.get(), sketch, normals, count, e.noise_level, later.get());
    e.lanczos_steps = static_cast<int>(
        std::max({u.alpha[0].size(), u.alpha[1].size(), u.alpha[2].size()}));
    e.capped = found.capped;
    if (found.out_of_reach) {
        e.out_of_reach = true;
        e.excess_risk = found.risk_bound;
        return e;
    }
    // The final grid around the minimizer, within the converged part.
    const double hi = std::min(found.converged_to, 2.5 * found.minimizer);
    const double lo = std::min(found.minimizer / 2.5, hi / 2);
    for (int g = 0; g < kGrid; ++g) e.grid.push_back(lo * std::pow(hi / lo, g / (kGrid - 1.0)));
    std::vector<double> gain;
    e.rss = sketch.rss(ctx, u, e.grid, 0, e.grid.size(), &gain);
    // The later steps' residual replaces the mean's, whose pass gave the restoration's gain.
    if (later) e.rss = later->sketch->rss(*later->ctx, later->u, e.grid, 0, e.grid.size());
    e.trace = mc ? divergences(ctx, u, *mc, count, e.grid) : traces(ctx, z, count, e.grid);
    for (std::size_t g = 0; g < e.grid.size(); ++g) e.trace[g] *= gain[g];
    // Several recomputed first-order steps: their mean-operator model keeps the first step's
    // damage in every step and so overstates what strong steps cost on smooth shapes (header,
    // "Several steps"), where the risk is also flat about its minimum. The rule corrects that
    // on the study's first-order rows with each of three Monte-Carlo probes (its ten meshes x
    // four noises, auto / best fixed step's error; cases past 10 %, geometric mean): curvature
    // L x4 4-6 -> 1-3, 1.033-1.046 -> 1.024-1.027; scale-dependent L x4 3-4 -> 0-1,
    // 1.036-1.039 -> 1.018-1.019; on fresh noise draws of the spheres, the torus and three scans
    // as well (bench/results/issue11/auto-gap.md, section 14). The curvature flow's L^2 steps,
    // whose residual comes from the later steps' operator, chose weaker than their best fixed
    // step on almost every mesh; with the rule, on the study's three draws (seeds 1, 2, 8; 27
    // meshes x four noises, default L^2 x4) the geometric mean of auto / best fell 1.035 ->
    // 1.025, the cases past 10 % 10 -> 8, and on the held-out scans (seeds 11, 13, 17) 12 -> 10
    // (section 35). The umbrella's filter is linear in the data, its risk exact up to the trace's
    // probes; its minimizer is the best step for the error along the normals, but on featured
    // and detailed scans the distance to the surface forgives what stronger steps do at creases
    // and fine detail (section 1), and there the minimizer was weaker than the best fixed step.
    // With the rule, the umbrella's default (L^2 x4) on the study's three draws and the
    // held-out scans (108 scan cases): auto / best 1.0221 -> 1.0181 in geometric mean, the
    // scans where one click ties or beats the best peer at its best 9 -> 16; on the spheres,
    // the torus and the flat patch (56 cases) 1.0071 -> 1.0173, worst 1.034 -> 1.075 (section
    // 36). The scale-dependent steps' L^2 keep the minimizer: their default got worse with it
    // (section 14), and so did single recomputed steps.
    // The curvature flow's L^2 steps reach at most kLaterRuleReach times the minimizer (section
    // 42).
    const bool linear = !p.assemble_at;
    choose(e, !p.explicit_integration && (linear || (p.pilot && (p.order == 1 || later))),
           later ? kLaterRuleReach : std::numeric_limits<double>::infinity());
    if (p.restorations == 1 && !p.restored.empty())
        sketch.rss(ctx, u, {e.time_step}, 0, 1, nullptr, &e.restoration);
    if (!ctx.weight_root.empty() && !uniform && e.trace_fraction < kWeightModelKeeps &&
        count <= kWeightedDirectVertices) {
        SparseOperator perturbed;
        if (mc) perturbed = std::move(mc->op);
        StrengthEstimate direct = risk_minimum(p, normals, given, false, &perturbed);
        direct.lanczos_steps += e.lanczos_steps;
        if (!direct.capped) return direct;
        e.lanczos_steps = direct.lanczos_steps;  // the model's choice stands
    }
    return e;
}

}  // namespace detail
}  // namespace fairing
