// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Block Gauss-Seidel sweeps over K's rows (not installed): the rows split into blocks of
// kSweepBlock rows (one block below kParallelRows), each swept in row order on one thread, using
// only the couplings inside its block, so a sweep's result does not depend on the number of
// threads. K's rows must list their columns in increasing order (assemble sorts them); a row
// then splits into runs before, inside and after its block (row_runs).
#pragma once

#include "kernels.h"

#include <algorithm>
#include <array>
#include <vector>

namespace fairing {
namespace detail {

// Rows per block of the sweeps from kParallelRows rows on (below, one block). A multiple of
// kSumBlock, so that a sweep's sums group rows as blocked_sum does. Measured on the 1.2 M-face
// bunny (complex solve of curvature L^2 22.5, Z-order): 59 iterations with 4 to 16 blocks, 57
// with 2, 50 with one block, 61 with 64; blocks of 8,192 rows (74) took 60 and split evenly over
// threads.
constexpr int kSweepBlock = 2 * 4096;

static_assert(kSweepBlock % kSumBlock == 0, "a sweep block holds whole sum blocks");

// Calls fn(i, begin, end, a) for the rows of every sweep block [begin, end) of `block` rows (a
// multiple of kSumBlock, or all rows), in increasing order when Forward, else decreasing, the
// blocks split over `threads` threads; a collects row i's share of N sums (fresh zeros per sum
// block), combined in block order as blocked_reduce does. (Sweeping two or four blocks on one
// thread a row of each in turn, to overlap the chains of rows that depend on the row before,
// was slower: 1.2 M-face bunny, curvature L^2 22.5, 3.53 s with one, 3.68 s with two, 4.05 s
// with four.)
template <bool Forward, int N, class RowFn, class Combine>
std::array<double, N> sweep_sum(int n, int block, int threads, RowFn fn, Combine combine) {
    const int sweeps = (n + block - 1) / block;
    std::vector<std::array<double, N>> partial(static_cast<std::size_t>((n + kSumBlock - 1) /
                                                                        kSumBlock));
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int g = 0; g < sweeps; ++g) {
        const int begin = g * block, end = std::min(n, begin + block);
        const int first = Forward ? begin : (end - 1) / kSumBlock * kSumBlock;
        for (int b = first; b >= begin && b < end; b += Forward ? kSumBlock : -kSumBlock) {
            std::array<double, N> a{};
            const int last = std::min(end, b + kSumBlock);
            if (Forward)
                for (int i = b; i < last; ++i) fn(i, begin, end, a.data());
            else
                for (int i = last - 1; i >= b; --i) fn(i, begin, end, a.data());
            partial[static_cast<std::size_t>(b / kSumBlock)] = a;
        }
    }
    std::array<double, N> total{};
    for (const auto& part : partial) combine(total, part);
    return total;
}

template <int N, class RowFn, class Combine>
std::array<double, N> forward_sweep(int n, int block, int threads, RowFn fn, Combine combine) {
    return sweep_sum<true, N>(n, block, threads, fn, combine);
}

template <int N, class RowFn, class Combine>
std::array<double, N> backward_sweep_sum(int n, int block, int threads, RowFn fn,
                                         Combine combine) {
    return sweep_sum<false, N>(n, block, threads, fn, combine);
}

// Calls fn(i, begin, end) for the rows of every sweep block in decreasing order.
template <class RowFn>
void backward_sweep(int n, int block, int threads, RowFn fn) {
    sweep_sum<false, 1>(
        n, block, threads, [&fn](int i, int begin, int end, double*) { fn(i, begin, end); },
        [](std::array<double, 1>&, const std::array<double, 1>&) {});
}

// A row of K sorted by column (assemble) in four runs, for the sweep block [begin, end) that
// holds row i: [first, in_block) before the block, [in_block, diagonal) inside it before i,
// [diagonal, after) inside it after i, [after, last) after the block.
struct RowRuns {
    int first, in_block, diagonal, after, last;
};
inline RowRuns row_runs(const int* start, const int* column, int i, int begin, int end) {
    RowRuns r{start[i], start[i], start[i], start[i + 1], start[i + 1]};
    while (r.in_block < r.last && column[r.in_block] < begin) ++r.in_block;
    r.diagonal = r.in_block;
    while (r.diagonal < r.last && column[r.diagonal] < i) ++r.diagonal;
    while (r.after > r.diagonal && column[r.after - 1] >= end) --r.after;
    return r;
}

// sum += sum_{e in [from, to)} w_e v_{column[e]} (W doubles per row).
template <int W, class Weights>
inline void add_run(const double* vs, const int* column, const Weights& w, int from, int to,
                    double sum[W]) {
    for (int e = from; e < to; ++e) {
        const double* vj = vs + W * column[e];
        for (int c = 0; c < W; ++c) sum[c] += w[e] * vj[c];
    }
}

// The same from the run's end down: the backward sweep adds its newest neighbour (the lowest
// column above i, often i + 1) last, so that the chain of rows waits on one addition per row
// instead of the whole run.
template <int W, class Weights>
inline void add_run_down(const double* vs, const int* column, const Weights& w, int from, int to,
                         double sum[W]) {
    for (int e = to - 1; e >= from; --e) {
        const double* vj = vs + W * column[e];
        for (int c = 0; c < W; ++c) sum[c] += w[e] * vj[c];
    }
}

// Gauss-Seidel needs every row of op to list its columns in increasing order (assemble's do)
// and pays only when most couplings lie inside the sweep blocks (else it is Jacobi at a higher
// price per iteration): on a 40,962-vertex icosphere numbered level by level, blocks of 8,192
// rows took 30 / 74 / 68 iterations against complex Jacobi's 30 / 84 / 77 (umbrella /
// scale-dependent / curvature), one block 17 / 38 / 34. Meshes of kReorderVertices vertices or
// more are renumbered breadth-first when their edges are long in index (vertex_order.h); below
// kParallelRows the sweeps run on one thread and take the whole mesh as one block.
constexpr double kInBlockCouplings = 0.75;

inline int sweep_block_rows(int n) { return n < kParallelRows ? std::max(n, 1) : kSweepBlock; }

inline bool gauss_seidel_applies(const SparseOperator& op) {
    const int block = sweep_block_rows(op.size());
    long long inside = 0;
    for (int i = 0; i < op.size(); ++i) {
        const int begin = i / block * block;
        for (int e = op.row_start[i]; e < op.row_start[i + 1]; ++e) {
            if (e > op.row_start[i] && !(op.column[e - 1] < op.column[e])) return false;
            inside += op.column[e] >= begin && op.column[e] < begin + block;
        }
    }
    return inside >= kInBlockCouplings * static_cast<double>(op.column.size());
}

}  // namespace detail
}  // namespace fairing
