// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Google Benchmark micro-benchmarks of the engine's hot paths on generated jittered tori of
// about 10k, 100k and 1M faces (bench/common/bench_mesh.h). Whatever engine is built is measured:
// nothing here configures threads; set OMP_NUM_THREADS or the engine's own switch from outside.
//
//   half_edge_build        HalfEdgeMesh::build
//   assemble/<op>          assemble(op) (umbrella, scale-dependent, curvature)
//   apply_k                one 3-column sparse product y = K x (curvature operator)
//   system_apply/<order>   LinearSystem::apply (order 1: 1 product; order 2: 2 products)
//   solve/<order>/<its>    solve() (Jacobi PCG) capped at 1 and 11 iterations: (t11 - t1) / 10
//                          = one CG iteration (product + preconditioner + dots + updates)
//   fair_step/<op>/<order> fair() with steps = 1 at the filters' default strength
//   fair_strength/x16      fair() curvature order 1 at time_step 6 and 96 (16x)
#include "bench_mesh.h"

#include "fairing/fairing.h"
#include "fairing/half_edge.h"
#include "fairing/operators.h"
#include "fairing/solver.h"

#include <benchmark/benchmark.h>

#include <map>

namespace {

struct Fixture {
    fairing::TriangleMesh mesh;
    fairing::HalfEdgeMesh he;
};

const Fixture& fixture(long faces) {
    static std::map<long, Fixture> cache;
    auto it = cache.find(faces);
    if (it != cache.end()) return it->second;
    const bench::Mesh m = bench::add_normal_noise(bench::torus_faces(faces), 0.0);
    Fixture f;
    f.mesh.positions.resize(long(m.v.size()), 3);
    for (size_t i = 0; i < m.v.size(); ++i)
        for (int k = 0; k < 3; ++k) f.mesh.positions(long(i), k) = m.v[i][k];
    f.mesh.triangles.assign(m.f.begin(), m.f.end());
    f.he = fairing::HalfEdgeMesh::build(f.mesh.positions, f.mesh.triangles);
    return cache.emplace(faces, std::move(f)).first->second;
}

void counters(benchmark::State& state, const Fixture& f) {
    state.counters["vertices"] = double(f.mesh.positions.rows());
    state.counters["faces"] = double(f.mesh.triangles.size());
    state.counters["ns_per_vertex"] = benchmark::Counter(
        double(f.mesh.positions.rows()) * 1e-9,
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

fairing::Operator op_of(long k) {
    return k == 0 ? fairing::Operator::Umbrella
         : k == 1 ? fairing::Operator::ScaleDependent
                  : fairing::Operator::CurvatureFlow;
}

void BM_half_edge_build(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    for (auto _ : state) {
        auto he = fairing::HalfEdgeMesh::build(f.mesh.positions, f.mesh.triangles);
        benchmark::DoNotOptimize(he.num_faces());
    }
    counters(state, f);
}

void BM_assemble(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    for (auto _ : state) {
        auto op = fairing::assemble(op_of(state.range(1)), f.he, f.mesh.positions);
        benchmark::DoNotOptimize(op.weight.data());
    }
    counters(state, f);
}

void BM_apply_k(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    const auto op = fairing::assemble(fairing::Operator::CurvatureFlow, f.he, f.mesh.positions);
    fairing::Positions y(f.mesh.positions.rows(), 3);
    for (auto _ : state) {
        op.apply_k(f.mesh.positions, y);
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    counters(state, f);
}

fairing::LinearSystem make_system(const fairing::SparseOperator& op, int order, double h) {
    fairing::LinearSystem s;
    s.op = &op;
    s.order = order;
    s.lambda_dt = order == 1 ? 6.0 * h * h : 22.5 * h * h * h * h;
    s.free.assign(op.size(), 1);
    s.diagonal = op.mass;
    return s;
}

double mean_edge(const Fixture& f) { return fairing::mean_edge_length(f.he, f.mesh.positions); }

void BM_system_apply(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    const auto op = fairing::assemble(fairing::Operator::CurvatureFlow, f.he, f.mesh.positions);
    const auto sys = make_system(op, int(state.range(1)), mean_edge(f));
    fairing::Positions y(f.mesh.positions.rows(), 3), scratch(f.mesh.positions.rows(), 3);
    for (auto _ : state) {
        sys.apply(f.mesh.positions, y, scratch);
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    counters(state, f);
}

void BM_solve(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    const auto op = fairing::assemble(fairing::Operator::CurvatureFlow, f.he, f.mesh.positions);
    const auto sys = make_system(op, int(state.range(1)), mean_edge(f));
    fairing::SolveSettings settings;
    settings.tolerance = 1e-14;  // never converges within the cap: exactly `cap` iterations
    settings.max_iterations = int(state.range(2));
    // Plain Jacobi PCG: (t11 - t1) / 10 is then one CG iteration (the product with the p.q dot
    // fused into it, the preconditioner, the updates), never the factored preconditioner's inner
    // solves, which Automatic may switch to for order 2.
    settings.preconditioner = fairing::Preconditioner::Jacobi;
    fairing::Positions x;
    int its = 0;
    for (auto _ : state) {
        state.PauseTiming();
        x = f.mesh.positions;
        state.ResumeTiming();
        its = fairing::solve(sys, x, settings).iterations;
        benchmark::DoNotOptimize(x.data());
    }
    state.counters["cg_iterations"] = its;
    counters(state, f);
}

void BM_fair_step(benchmark::State& state) {
    const Fixture& f = fixture(state.range(0));
    fairing::Options o;
    o.op = op_of(state.range(1));
    o.order = int(state.range(2));
    o.time_step = state.range(3) > 0 ? double(state.range(3))
                : o.op == fairing::Operator::Umbrella ? 10.0
                : o.op == fairing::Operator::ScaleDependent ? 2.5 : 22.5;
    o.steps = 1;
    int its = 0;
    for (auto _ : state) {
        auto r = fairing::fair(f.mesh, fairing::Constraints{}, o);
        its = r.total_iterations;
        benchmark::DoNotOptimize(r.positions.data());
    }
    state.counters["cg_iterations"] = its;
    counters(state, f);
}

const std::vector<int64_t> kSizes = {10000, 100000, 1000000};

void sizes(benchmark::internal::Benchmark* b) {
    for (auto s : kSizes) b->Args({s});
}
void sizes_ops(benchmark::internal::Benchmark* b) {
    for (auto s : kSizes)
        for (int op = 0; op < 3; ++op) b->Args({s, op});
}
void sizes_orders(benchmark::internal::Benchmark* b) {
    for (auto s : kSizes)
        for (int o = 1; o <= 2; ++o) b->Args({s, o});
}
void sizes_orders_caps(benchmark::internal::Benchmark* b) {
    for (auto s : kSizes)
        for (int o = 1; o <= 2; ++o)
            for (int cap : {1, 11}) b->Args({s, o, cap});
}
void sizes_steps(benchmark::internal::Benchmark* b) {
    for (auto s : kSizes) {
        for (int op = 0; op < 3; ++op)
            for (int o = 1; o <= 2; ++o) b->Args({s, op, o, 0});
        b->Args({s, 2, 1, 6});   // curvature order 1, unit step (t = 1 mean edge^2)
        b->Args({s, 2, 1, 96});  // 16x stronger
    }
}

}  // namespace

BENCHMARK(BM_half_edge_build)->Apply(sizes)->Unit(benchmark::kMillisecond)->ArgNames({"faces"});
BENCHMARK(BM_assemble)->Apply(sizes_ops)->Unit(benchmark::kMillisecond)->ArgNames({"faces", "op"});
BENCHMARK(BM_apply_k)->Apply(sizes)->Unit(benchmark::kMillisecond)->ArgNames({"faces"});
BENCHMARK(BM_system_apply)->Apply(sizes_orders)->Unit(benchmark::kMillisecond)->ArgNames({"faces", "order"});
BENCHMARK(BM_solve)->Apply(sizes_orders_caps)->Unit(benchmark::kMillisecond)->ArgNames({"faces", "order", "cap"});
BENCHMARK(BM_fair_step)->Apply(sizes_steps)->Unit(benchmark::kMillisecond)
    ->ArgNames({"faces", "op", "order", "time_step"});

BENCHMARK_MAIN();
