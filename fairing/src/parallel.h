// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Deterministic building blocks for the mesh passes that run inside one OpenMP parallel region
// (not installed): HalfEdgeMesh::build and the operator assembly.
//
// Conventions:
// - Every function here is called by every thread of the enclosing region (or outside any
//   region, on one thread); the work is split in contiguous ranges by thread number, so thread t
//   owns items that come after those of threads < t.
// - Results never depend on the number of threads: integer counts are exact whatever the order
//   they are added in, and nothing here adds floating-point numbers.
#pragma once

#include "kernels.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace fairing {
namespace detail {

// This thread's place in the enclosing parallel region (0 of 1 outside any region).
struct Team {
    int id = 0;
    int size = 1;
    // [begin, end) of this thread's contiguous share of `count` items.
    int begin(int count) const {
        return static_cast<int>(static_cast<long long>(count) * id / size);
    }
    int end(int count) const {
        return static_cast<int>(static_cast<long long>(count) * (id + 1) / size);
    }
};

inline Team this_team() {
    Team team;
#ifdef _OPENMP
    team.id = omp_get_thread_num();
    team.size = omp_get_num_threads();
#endif
    return team;
}

inline void barrier() { FAIRING_PRAGMA(omp barrier) }

// A counting sort of items into buckets, with one histogram per thread: each thread counts the
// items of its own range, and in every bucket its items then go after those of the threads
// before it. A bucket so lists its items in increasing order, as one thread would, at the
// price of threads x buckets counters.
class BucketFill {
public:
    // Room for `threads` histograms of up to `buckets` counters.
    BucketFill(int buckets, int threads)
        : capacity_(buckets),
          counters_(new int[static_cast<std::size_t>(buckets) * threads]),
          chunk_(threads + 1, 0) {}

    // This thread's histogram over `buckets` buckets, cleared (the number of buckets may change
    // from one sort to the next, within the capacity).
    int* clear(const Team& team, int buckets) {
        buckets_ = buckets;
        int* h = histogram(team.id);
        std::fill(h, h + buckets, 0);
        return h;
    }
    int* histogram(int thread) const {
        return counters_.get() + static_cast<std::size_t>(capacity_) * thread;
    }

    // Called by every thread once all have counted: start[b] becomes the first position of bucket
    // b (start has buckets + 1 entries) and each histogram entry the position where its thread
    // writes its next item of that bucket. Barriers before and after.
    void to_positions(const Team& team, int* start) {
        barrier();
        const int b0 = team.begin(buckets_), b1 = team.end(buckets_);
        int total = 0;
        for (int b = b0; b < b1; ++b)
            for (int t = 0; t < team.size; ++t) total += histogram(t)[b];
        chunk_[team.id] = total;
        barrier();
        int position = 0;
        for (int t = 0; t < team.id; ++t) position += chunk_[t];
        for (int b = b0; b < b1; ++b) {
            start[b] = position;
            for (int t = 0; t < team.size; ++t) {
                const int count = histogram(t)[b];
                histogram(t)[b] = position;
                position += count;
            }
        }
        if (team.id == team.size - 1) start[buckets_] = position;
        barrier();
    }

private:
    int capacity_;
    int buckets_ = 0;
    std::unique_ptr<int[]> counters_;  // not value-initialized: each thread clears its own
    std::vector<int> chunk_;
};

}  // namespace detail
}  // namespace fairing
