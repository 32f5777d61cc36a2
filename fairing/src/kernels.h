// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Row-parallel loops of the engine (not installed). OpenMP is optional: without it, or below
// kParallelRows rows, every loop runs on the calling thread.
#pragma once

#include "fairing/operators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#ifdef _OPENMP
#include <omp.h>
#define FAIRING_PRAGMA(x) _Pragma(#x)
#else
#define FAIRING_PRAGMA(x)
#endif

namespace fairing {
namespace detail {

// The solvers' guard: a value of the iteration that stopped being finite ends the solve.
inline void check_finite(double v, int iteration) {
    if (!std::isfinite(v))
        throw Error("the linear solve produced a non-finite value at iteration " +
                    std::to_string(iteration) +
                    "; the input is too degenerate for this operator (try the umbrella "
                    "operator, or repair the mesh first)");
}

// A hint that `address` will soon be written (a no-op where the compiler has no such builtin).
inline void prefetch_for_write(const void* address) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(address, 1);
#else
    (void)address;
#endif
}

// Below this many rows a second thread costs more than it brings (starting a team, and with
// OpenMP's default active wait, idle threads spinning against the host's own threads).
constexpr int kParallelRows = 50000;

// Threads for a loop over `rows` rows: `requested` (0 = as many as OpenMP offers) above the
// threshold, else one.
inline int threads_for(int rows, int requested) {
#ifdef _OPENMP
    if (rows < kParallelRows) return 1;
    return requested > 0 ? requested : omp_get_max_threads();
#else
    (void)rows;
    (void)requested;
    return 1;
#endif
}

// Calls fn(i) for every row i < n, split over `threads` threads (fn only writes row i).
template <class Fn>
void for_each_row(int n, int threads, Fn fn) {
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int i = 0; i < n; ++i) fn(i);
}

// K's weights for the kernels below: null when they are all 1 (SparseOperator::unit_weights).
inline const double* weights_of(const SparseOperator& op) {
    return op.unit_weights ? nullptr : op.weight.data();
}

// The weights of an operator whose every w_ij is 1, indexed like its weight array: a kernel
// written for `Weights w` (w[k]) and called with both reads no weight for the umbrella, with the
// same bits (1 * d = d, folded by the compiler).
struct UnitWeights {
    double operator[](int) const { return 1.0; }
};

// Calls fn(w) with K's weights (w[k]), or UnitWeights when they are all 1 (weight null:
// weights_of), so that one kernel serves both.
template <class Fn>
inline void with_weights(const double* weight, Fn fn) {
    if (weight) fn(weight);
    else fn(UnitWeights{});
}

// (s0, s1, s2) = (K x)_i = sum_j w_ij (x_j - x_i).
template <class Weights>
inline void k_row_with(int i, const double* xs, const int* start, const int* column,
                       const Weights& weight, double& s0, double& s1, double& s2) {
    const double xi0 = xs[3 * i], xi1 = xs[3 * i + 1], xi2 = xs[3 * i + 2];
    s0 = s1 = s2 = 0;
    for (int k = start[i]; k < start[i + 1]; ++k) {
        const double w = weight[k];
        const double* xj = xs + 3 * column[k];
        s0 += w * (xj[0] - xi0);
        s1 += w * (xj[1] - xi1);
        s2 += w * (xj[2] - xi2);
    }
}

#if defined(__GNUC__) && defined(__x86_64__)
#define FAIRING_AVX 1
// A row's three entries in one register, lane 3 zero: a masked load, which reads no byte past
// them.
__attribute__((target("avx"))) inline __m256d load_row(const double* at) {
    return _mm256_maskload_pd(at, _mm256_set_epi64x(0, -1, -1, -1));
}
// Lanes 0-2 stored as the row's three entries: two plain stores, none past them. (Masked stores
// are slow on the AMD EPYC measured: the sketch's pass written with them ran 1.2-1.3x slower,
// auto-gap.md section 54.)
__attribute__((target("avx"))) inline void store_row(double* at, __m256d row) {
    _mm_storeu_pd(at, _mm256_castpd256_pd128(row));
    _mm_store_sd(at + 2, _mm256_extractf128_pd(row, 1));
}
// k_row_with with AVX: a row's three entries in one register (load_row), the same operations in
// the same order per entry, so the same bits (the target is AVX alone: no fused multiply-add).
// Called from a pass compiled for AVX (FAIRING_AVX_TARGET), where it is inlined.
struct AvxGather {
    // (K x)_i in lanes 0-2, given xi = load_row(xs + 3 i).
    template <class Weights>
    __attribute__((target("avx"))) __m256d sum(int i, const double* xs, const int* start,
                                               const int* column, const Weights& weight,
                                               __m256d xi) const {
        __m256d s = _mm256_setzero_pd();
        for (int k = start[i]; k < start[i + 1]; ++k) {
            const __m256d xj = load_row(xs + 3 * column[k]);
            s = _mm256_add_pd(s, _mm256_mul_pd(_mm256_set1_pd(weight[k]), _mm256_sub_pd(xj, xi)));
        }
        return s;
    }
};
#define FAIRING_AVX_TARGET __attribute__((target("avx"), flatten))
#endif

// Whether the AVX passes may run: true unless a test switches them off to compare their bits with
// the scalar passes' (tests/engine/test_auto_strength.cpp).
inline bool& avx_passes_allowed() {
    static bool allowed = true;
    return allowed;
}

// Whether to run the AVX passes: this processor runs AVX (checked once) and they are allowed.
inline bool has_avx() {
#ifdef FAIRING_AVX
    static const bool avx = __builtin_cpu_supports("avx");
    return avx && avx_passes_allowed();
#else
    return false;
#endif
}

// k_row_with for K's weights, null when they are all 1 (weights_of).
inline void k_row(int i, const double* xs, const int* start, const int* column,
                  const double* weight, double& s0, double& s1, double& s2) {
    with_weights(weight, [&](const auto& w) { k_row_with(i, xs, start, column, w, s0, s1, s2); });
}

// Row i of A x = D x + scale (K v)_i into yi, given (s0, s1, s2) = (K v)_i and D_i = di, and on a
// free row its share x_i . (A x)_i added to a[0..2]: the row of LinearSystem::apply_dot, which
// the strength estimate's paired product (auto_strength.cpp, multiply_pair) repeats bit for bit.
inline void system_row(double di, double scale, const double* xi, double s0, double s1, double s2,
                       bool free_row, double* yi, double* a) {
    yi[0] = di * xi[0] + scale * s0;
    yi[1] = di * xi[1] + scale * s1;
    yi[2] = di * xi[2] + scale * s2;
    if (!free_row) return;
    a[0] += xi[0] * yi[0];
    a[1] += xi[1] * yi[1];
    a[2] += xi[2] * yi[2];
}

// Rows per block of the deterministic sums below. Each block is summed in row order and the
// blocks' partial sums are then added in block order, so a sum has the same bits whatever the
// number of threads (OpenMP's reduction clause adds per-thread partials, whose split depends on
// it). The results of fair() are so bit-identical on any thread count.
constexpr int kSumBlock = 4096;

// Fixed-order reduction over rows [0, n): fn(i, a) adds row i's share to a[0..N-1] (a starts at
// zero in every block); combine(total, part) folds one block's partials into the total, in
// block order.
template <int N, class RowFn, class Combine>
std::array<double, N> blocked_reduce(int n, int threads, RowFn fn, Combine combine) {
    const int blocks = (n + kSumBlock - 1) / kSumBlock;
    std::vector<std::array<double, N>> partial(static_cast<std::size_t>(blocks));
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int b = 0; b < blocks; ++b) {
        std::array<double, N> a{};
        const int end = std::min(n, (b + 1) * kSumBlock);
        for (int i = b * kSumBlock; i < end; ++i) fn(i, a.data());
        partial[static_cast<std::size_t>(b)] = a;
    }
    std::array<double, N> total{};
    for (const auto& part : partial) combine(total, part);
    return total;
}

// The same sums with a block's rows handed over at once: fn(first, end, a) adds the shares of
// rows [first, end) to a[0..N-1] (zero on entry), each sum's rows in row order, and may so keep
// a few sums at a time in registers (a pass over several processes, one process at a time);
// the bits are those of blocked_sum with the same rows.
template <int N, class BlockFn>
std::array<double, N> blocked_sum_by_block(int n, int threads, BlockFn fn) {
    const int blocks = (n + kSumBlock - 1) / kSumBlock;
    std::vector<std::array<double, N>> partial(static_cast<std::size_t>(blocks));
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int b = 0; b < blocks; ++b) {
        std::array<double, N> a{};
        fn(b * kSumBlock, std::min(n, (b + 1) * kSumBlock), a.data());
        partial[static_cast<std::size_t>(b)] = a;
    }
    std::array<double, N> total{};
    for (const auto& part : partial)
        for (int k = 0; k < N; ++k) total[k] += part[k];
    return total;
}

// The same with every entry summed.
template <int N, class RowFn>
std::array<double, N> blocked_sum(int n, int threads, RowFn fn) {
    return blocked_reduce<N>(n, threads, fn,
                             [](std::array<double, N>& total, const std::array<double, N>& part) {
                                 for (int k = 0; k < N; ++k) total[k] += part[k];
                             });
}

// Norm per column over the free rows, sums in a fixed order (blocked_reduce).
inline std::array<double, 3> column_norms(const Positions& v, const std::vector<char>& free,
                                          ResidualNorm norm, int threads) {
    const double* d = v.data();
    const char* f = free.data();
    const int n = static_cast<int>(v.rows());
    if (norm == ResidualNorm::LInfinity)
        return blocked_reduce<3>(
            n, threads,
            [=](int i, double* a) {
                if (!f[i]) return;
                for (int c = 0; c < 3; ++c) a[c] = std::max(a[c], std::abs(d[3 * i + c]));
            },
            [](std::array<double, 3>& total, const std::array<double, 3>& part) {
                for (int c = 0; c < 3; ++c) total[c] = std::max(total[c], part[c]);
            });
    const std::array<double, 3> s = blocked_sum<3>(n, threads, [=](int i, double* a) {
        if (!f[i]) return;
        for (int c = 0; c < 3; ++c) a[c] += d[3 * i + c] * d[3 * i + c];
    });
    return {std::sqrt(s[0]), std::sqrt(s[1]), std::sqrt(s[2])};
}

// Calls fn(i, s0, s1, s2, a) for every row i with (s0, s1, s2) = (K x)_i, rows split over
// op.threads threads; fn only writes row i of its outputs and may add row i's share of a sum to
// a[0..2] (fresh zeros per row), whose totals are returned (fusing a dot product into the product saves a pass over
// the vectors). The sums are in a fixed order (blocked_sum).
template <class RowFn>
std::array<double, 3> sum_over_k_rows(const SparseOperator& op, const Positions& x, RowFn fn) {
    const double* xs = x.data();
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    return blocked_sum<3>(op.size(), op.threads, [&](int i, double* a) {
        double s0, s1, s2;
        k_row(i, xs, start, column, weight, s0, s1, s2);
        double row[3] = {0, 0, 0};
        fn(i, s0, s1, s2, row);
        a[0] += row[0];
        a[1] += row[1];
        a[2] += row[2];
    });
}

// The same without a sum: fn(i, s0, s1, s2).
template <class RowFn>
void for_each_k_row(const SparseOperator& op, const Positions& x, RowFn fn) {
    const double* xs = x.data();
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    for_each_row(op.size(), op.threads, [&](int i) {
        double s0, s1, s2;
        k_row(i, xs, start, column, weight, s0, s1, s2);
        fn(i, s0, s1, s2);
    });
}

}  // namespace detail
}  // namespace fairing
