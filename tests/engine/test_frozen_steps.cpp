// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Section 4.3: s steps with a frozen operator are one linear filter, taken at once
// (src/frozen_steps.h) where that is cheaper (fairing.cpp). Each result is checked against
// the steps one by one with dense solves (and the volume restoration after every step), so the
// shortcut must be the same filter; the cases fair() leaves to the steps one by one are checked
// to be left, and the general process (first order, soft weights) directly.
#include "meshes.h"

#include "fairing/half_edge.h"
#include "fairing/invariants.h"
#include "fairing/operators.h"
#include "fairing/solver.h"
#include "frozen_steps.h"

#include <gtest/gtest.h>

#include <vector>

namespace {

using fairing::HalfEdgeMesh;
using fairing::Operator;
using fairing::Options;
using fairing::Positions;
using fairing::SparseOperator;
using fairing::TriangleMesh;

constexpr Operator kOperators[] = {Operator::Umbrella, Operator::ScaleDependent,
                                   Operator::CurvatureFlow};

// A lumpy sphere: asymmetric, so smoothing moves its centroid and the restoration's translation
// matters.
TriangleMesh lumpy_sphere() { return meshes::radial_noise(meshes::icosphere(2), 0.08, 21); }

// The lumpy sphere and a smaller noisy one beside it: two closed components.
TriangleMesh two_lumpy_spheres() {
    const TriangleMesh small = meshes::scaled(meshes::radial_noise(meshes::icosphere(2), 0.1, 8), 0.5);
    return meshes::merge(lumpy_sphere(), meshes::translated(small, fairing::Vec3(3, 0.5, 0)));
}

Options frozen(Operator op, int order, double time_step, int steps) {
    Options o;
    o.op = op;
    o.order = order;
    o.time_step = time_step;
    o.steps = steps;
    o.freeze_operator = true;
    o.preserve_volume = false;
    // The reference steps below restore the volume only; the curvature flow's drift translation
    // is checked in test_volume.cpp.
    o.cancel_drift = false;
    o.tolerance = 1e-12;
    o.max_iterations = 20000;
    return o;
}

// The steps one by one on the first operator, each followed (restore) by the rescaling of every
// closed component to its initial volume about its centroid.
Positions dense_steps(const HalfEdgeMesh& he, const SparseOperator& k0, const Positions& x0,
                      double ldt, int order, int steps, bool restore,
                      const std::vector<double>& weights = {}, const std::vector<char>& free = {}) {
    const std::vector<char> all(x0.rows(), 1);
    std::vector<double> target;
    for (const fairing::Component& c : he.components())
        target.push_back(fairing::component_volume(he, c, x0));
    Positions x = x0;
    for (int s = 0; s < steps; ++s) {
        x = meshes::dense_implicit_step(k0, x, ldt, order, weights, free);
        if (!restore) continue;
        for (std::size_t c = 0; c < he.components().size(); ++c)
            fairing::restore_measure(he, he.components()[c], all, target[c], x,
                                     fairing::VolumeRestoration::Scale);
    }
    return x;
}

// The run took its steps at once: one report covering all of them.
void expect_at_once(const fairing::Result& r, int steps) {
    ASSERT_EQ(r.solves.size(), 1u);
    EXPECT_EQ(r.solves[0].frozen_steps, steps);
    EXPECT_TRUE(r.solves[0].converged);
    EXPECT_EQ(r.steps, steps);
    EXPECT_GT(r.total_iterations, 0);
}

// Both components of two_lumpy_spheres() restored by `how` to their volume.
void expect_two_components_kept(const fairing::Result& r, fairing::Restoration how) {
    ASSERT_EQ(r.components.size(), 2u);
    for (const auto& c : r.components) {
        EXPECT_EQ(c.restoration, how);
        EXPECT_NEAR(c.measure_after, c.measure_before, 1e-12 * c.measure_before);
    }
}

}  // namespace

// The run took its steps one by one: one report per step.
void expect_one_by_one(const fairing::Result& r, int steps) {
    ASSERT_EQ(r.solves.size(), static_cast<std::size_t>(steps));
    for (const auto& s : r.solves) EXPECT_EQ(s.frozen_steps, 0);
}

TEST(FrozenSteps, EqualTheStepsOneByOne) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            const Options o = frozen(op, order, order == 1 ? 2.0 : 4.0, 4);
            const fairing::Result r = fairing::fair(m, {}, o);
            expect_at_once(r, 4);
            const SparseOperator k0 = fairing::assemble(op, he, m.positions);
            const Positions x = dense_steps(he, k0, m.positions, r.lambda_dt, order, 4, false);
            EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-9);
            // Not one step of four times the strength: the steps compose.
            const Positions one = meshes::dense_implicit_step(k0, m.positions, 4 * r.lambda_dt, order);
            EXPECT_GT(meshes::max_row_distance(r.positions, one), 1e-4);
        }
}

// The paper's rescaling after every step: the filter keeps constants, so the rescalings commute
// with it, but the centroid of the lumpy solid moves as it is smoothed, so the translation
// needs every intermediate result. Restoring once at the end about the final centroid is
// shown to be measurably different.
TEST(FrozenSteps, VolumeRestoredAfterEveryStep) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    for (Operator op : kOperators)
        for (int order : {2}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = frozen(op, order, 4.0, 5);
            o.preserve_volume = true;
            o.restoration = fairing::VolumeRestoration::Scale;
            const fairing::Result r = fairing::fair(m, {}, o);
            expect_at_once(r, 5);
            EXPECT_EQ(r.components[0].restoration, fairing::Restoration::Scale);
            EXPECT_NEAR(r.volume_after, r.volume_before, 1e-12 * r.volume_before);
            const SparseOperator k0 = fairing::assemble(op, he, m.positions);
            const Positions x = dense_steps(he, k0, m.positions, r.lambda_dt, order, 5, true);
            EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-9);
            Positions at_end = dense_steps(he, k0, m.positions, r.lambda_dt, order, 5, false);
            fairing::restore_measure(he, he.components()[0], std::vector<char>(m.positions.rows(), 1),
                                     r.volume_before, at_end, fairing::VolumeRestoration::Scale);
            EXPECT_GT(meshes::max_row_distance(at_end, x), 1e-7);
        }
}

// First-order steps with a rescaled component are cheaper one by one (fairing.cpp,
// take_frozen_steps): left to the steps, with the same result.
TEST(FrozenSteps, FirstOrderWithVolumeRestorationOneByOne) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    Options o = frozen(Operator::CurvatureFlow, 1, 2.0, 3);
    o.preserve_volume = true;
    o.restoration = fairing::VolumeRestoration::Scale;
    const fairing::Result r = fairing::fair(m, {}, o);
    expect_one_by_one(r, 3);
    const SparseOperator k0 = fairing::assemble(Operator::CurvatureFlow, he, m.positions);
    const Positions x = dense_steps(he, k0, m.positions, r.lambda_dt, 1, 3, true);
    EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-9);
}

// Fixed boundary vertices make each step affine (their coupling moves to the right-hand side);
// the open component restores nothing by default.
TEST(FrozenSteps, FixedBoundaryOfAnOpenMesh) {
    const TriangleMesh m = meshes::noisy_open_grid(12, 0.2, 0.3);
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    std::vector<char> free(m.positions.rows(), 1);
    for (int v = 0; v < he.num_vertices(); ++v) free[v] = he.is_boundary_vertex(v) ? 0 : 1;
    for (Operator op : kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = frozen(op, order, 3.0, 3);
            o.preserve_volume = true;  // nothing to restore on an open component (None)
            const fairing::Result r = fairing::fair(m, {}, o);
            expect_at_once(r, 3);
            const SparseOperator k0 = fairing::assemble(op, he, m.positions);
            const Positions x = dense_steps(he, k0, m.positions, r.lambda_dt, order, 3, false, {}, free);
            EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-9);
            for (int v = 0; v < he.num_vertices(); ++v)
                if (!free[v]) {
                    EXPECT_EQ(r.positions.row(v), m.positions.row(v));
                }
        }
}

// With the paper's rescaling, the area of an open component with fixed vertices is restored by
// a normal offset after every step, which is not linear: the steps are then taken one by one.
TEST(FrozenSteps, NormalOffsetAfterEveryStepFallsBackToOneByOne) {
    const TriangleMesh m = meshes::noisy_open_grid(12, 0.2, 0.3);
    Options o = frozen(Operator::CurvatureFlow, 2, 3.0, 3);
    o.preserve_volume = true;
    o.restoration = fairing::VolumeRestoration::Scale;
    o.open_invariant = fairing::OpenInvariant::Area;
    const fairing::Result r = fairing::fair(m, {}, o);
    ASSERT_EQ(r.solves.size(), 3u);
    for (const auto& s : r.solves) EXPECT_EQ(s.frozen_steps, 0);
    EXPECT_EQ(r.components[0].restoration, fairing::Restoration::NormalOffset);
}

Positions centred(const Positions& x) {
    return x.rowwise() - 0.5 * (x.colwise().minCoeff() + x.colwise().maxCoeff());
}

// Soft constraints (section 2.7): D = M / w. First order: the same process. The L^2 system no
// longer factors over the complex numbers, the Krylov space would be the L^2 operator's, and
// fair() takes those steps one by one; the process itself is checked on them below.
TEST(FrozenSteps, SoftWeights) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    fairing::Constraints constraints;
    for (int i = 0; i < m.positions.rows(); ++i)
        constraints.weights.push_back(i % 7 == 0 ? 0.0 : 0.2 + 0.8 * ((i * 37) % 11) / 10.0);
    for (int order : {1, 2, 3, 4}) {
        SCOPED_TRACE(testing::Message() << "order " << order);
        const Options o = frozen(Operator::CurvatureFlow, order, 2.0, 3);
        const fairing::Result r = fairing::fair(m, constraints, o);
        if (order == 1) expect_at_once(r, 3);
        else expect_one_by_one(r, 3);
        const SparseOperator k0 = fairing::assemble(Operator::CurvatureFlow, he, m.positions);
        const Positions x =
            dense_steps(he, k0, m.positions, r.lambda_dt, order, 3, false, constraints.weights);
        EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-9);
    }
}

// The process on its own, on the systems fair() leaves to the steps one by one too (soft
// weights with L^2), fixed rows (weight 0) included.
TEST(FrozenSteps, GeneralProcessWithSoftWeights) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    const Positions x0 = centred(m.positions);
    std::vector<double> weights;
    for (int i = 0; i < x0.rows(); ++i)
        weights.push_back(i % 7 == 0 ? 0.0 : 0.2 + 0.8 * ((i * 37) % 11) / 10.0);
    for (Operator op : {Operator::Umbrella, Operator::CurvatureFlow})
        for (int order : {1, 2, 3, 4})
            for (bool soft : {false, true}) {
                SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                << " soft " << soft);
                const SparseOperator k0 = fairing::assemble(op, he, x0);
                fairing::LinearSystem system;
                system.op = &k0;
                system.order = order;
                system.lambda_dt = op == Operator::Umbrella ? 1.0 : order == 1 ? 0.05 : 0.002;
                system.free.assign(x0.rows(), 1);
                system.diagonal = k0.mass;
                for (int i = 0; i < x0.rows() && soft; ++i) {
                    system.free[i] = weights[i] > 0;
                    if (weights[i] > 0) system.diagonal[i] = k0.mass[i] / weights[i];
                    else system.diagonal[i] = 1;
                }
                fairing::detail::FrozenProblem problem;
                problem.system = &system;
                problem.steps = 3;
                problem.tolerance = 1e-12;
                problem.max_iterations = 20000;
                problem.mesh = &he;
                Positions x = x0;
                const fairing::detail::FrozenOutcome outcome =
                    fairing::detail::take_frozen_steps(problem, x);
                ASSERT_TRUE(outcome.taken);
                const Positions expected = dense_steps(he, k0, x0, system.lambda_dt, order, 3,
                                                       false, soft ? weights : std::vector<double>());
                EXPECT_LT(meshes::max_row_distance(x, expected), 1e-9);
                EXPECT_GT(meshes::max_row_distance(x, x0), 1e-3);
            }
}

// At the default tolerance the result is as close to the exact steps as the steps one by one
// at that tolerance are.
TEST(FrozenSteps, DefaultToleranceIsKept) {
    const TriangleMesh m = lumpy_sphere();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    Options o = frozen(Operator::CurvatureFlow, 2, 22.5, 10);
    o.tolerance = Options().tolerance;
    o.preserve_volume = true;
    o.restoration = fairing::VolumeRestoration::Scale;
    const fairing::Result r = fairing::fair(m, {}, o);
    expect_at_once(r, 10);
    EXPECT_LE(r.max_residual, o.tolerance);
    const SparseOperator k0 = fairing::assemble(Operator::CurvatureFlow, he, m.positions);
    const Positions x = dense_steps(he, k0, m.positions, r.lambda_dt, 2, 10, true);
    // One solve to 1e-8 leaves an error of at most 1e-8 of the positions' size (radius 1).
    EXPECT_LT(meshes::max_row_distance(r.positions, x), 1e-7);
}

TEST(FrozenSteps, ProgressIsMonotoneAndEndsAtOne) {
    const TriangleMesh m = lumpy_sphere();
    Options o = frozen(Operator::CurvatureFlow, 2, 22.5, 10);
    o.preserve_volume = true;
    std::vector<double> seen;
    o.progress = [&](double f) { seen.push_back(f); };
    const fairing::Result r = fairing::fair(m, {}, o);
    expect_at_once(r, 10);
    ASSERT_GT(seen.size(), 2u);
    for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
    EXPECT_GE(seen.front(), 0.0);
    EXPECT_EQ(seen.back(), 1.0);
}

// Every sum is blocked (kernels.h): two threads give the same bits as one.
TEST(FrozenSteps, TwoThreadsGiveTheSameBits) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(7), 0.002);
    ASSERT_GE(m.positions.rows(), 50000);
    for (Operator op : {Operator::Umbrella, Operator::CurvatureFlow}) {
        SCOPED_TRACE(testing::Message() << fairing::to_string(op));
        Options o = frozen(op, 2, 22.5, 3);
        o.tolerance = 1e-8;
        o.preserve_volume = true;
        o.threads = 1;
        const fairing::Result one = fairing::fair(m, {}, o);
        expect_at_once(one, 3);
        o.threads = 2;
        const fairing::Result two = fairing::fair(m, {}, o);
        EXPECT_EQ(meshes::max_row_distance(one.positions, two.positions), 0.0);
        EXPECT_EQ(one.total_iterations, two.total_iterations);
    }
}

// Virtual-vertex boundaries (section 5.3): the hidden vertices are unknowns of the same system,
// so the steps are still one filter. Checked against the steps one by one, which the Jacobi
// preconditioner asks for (the frozen path is the automatic solver's).
TEST(FrozenSteps, VirtualVerticesAgreeWithTheStepsOneByOne) {
    const TriangleMesh m = meshes::noisy_open_grid(12, 0.2, 0.3);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        Options o = frozen(op, 2, 3.0, 3);
        o.boundary = fairing::BoundaryMode::VirtualVertex;
        const fairing::Result at_once = fairing::fair(m, {}, o);
        expect_at_once(at_once, 3);
        o.preconditioner = fairing::Preconditioner::Jacobi;
        const fairing::Result one_by_one = fairing::fair(m, {}, o);
        expect_one_by_one(one_by_one, 3);
        EXPECT_LT(meshes::max_row_distance(at_once.positions, one_by_one.positions), 1e-9);
        EXPECT_GT(meshes::max_row_distance(at_once.positions, m.positions), 1e-3);
    }
}

// The smooth boundary curve is a second system solved before each step: one by one.
TEST(FrozenSteps, SmoothBoundaryCurveOneByOne) {
    const TriangleMesh m = meshes::noisy_open_grid(12, 0.2, 0.3);
    Options o = frozen(Operator::CurvatureFlow, 2, 3.0, 3);
    o.boundary = fairing::BoundaryMode::SmoothCurve;
    const fairing::Result r = fairing::fair(m, {}, o);
    ASSERT_EQ(r.solves.size(), 6u);  // curve and surface, three times
    for (const auto& s : r.solves) EXPECT_EQ(s.frozen_steps, 0);
}

// Two closed components, each rescaled about its own centroid after every step.
TEST(FrozenSteps, TwoComponentsKeepTheirOwnVolume) {
    const TriangleMesh m = two_lumpy_spheres();
    Options o = frozen(Operator::CurvatureFlow, 2, 6.0, 4);
    o.preserve_volume = true;
    o.restoration = fairing::VolumeRestoration::Scale;
    const fairing::Result at_once = fairing::fair(m, {}, o);
    expect_at_once(at_once, 4);
    expect_two_components_kept(at_once, fairing::Restoration::Scale);
    o.preconditioner = fairing::Preconditioner::Jacobi;
    const fairing::Result one_by_one = fairing::fair(m, {}, o);
    expect_one_by_one(one_by_one, 4);
    EXPECT_LT(meshes::max_row_distance(at_once.positions, one_by_one.positions), 1e-9);
}

// The default normal offset follows a frozen operator's steps once, after the last (fairing.h,
// Options::preserve_volume): at once, one by one (Jacobi) and the dense steps followed by one
// offset agree, and each component keeps its volume.
TEST(FrozenSteps, NormalOffsetOnceAfterTheLastStep) {
    const TriangleMesh m = two_lumpy_spheres();
    const HalfEdgeMesh he = HalfEdgeMesh::build(m.positions, m.triangles);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        Options o = frozen(op, 2, 0.1, 4);  // a loss below kMaxOffsetChange: offset, not scaled
        o.preserve_volume = true;
        const fairing::Result at_once = fairing::fair(m, {}, o);
        expect_at_once(at_once, 4);
        expect_two_components_kept(at_once, fairing::Restoration::NormalOffset);
        const SparseOperator k0 = fairing::assemble(op, he, m.positions);
        Positions x = dense_steps(he, k0, m.positions, at_once.lambda_dt, 2, 4, false);
        const std::vector<char> all(m.positions.rows(), 1);
        for (std::size_t c = 0; c < he.components().size(); ++c)
            EXPECT_EQ(fairing::restore_measure(he, he.components()[c], all,
                                               fairing::component_volume(he, he.components()[c],
                                                                         m.positions),
                                               x),
                      fairing::Restoration::NormalOffset);
        EXPECT_LT(meshes::max_row_distance(at_once.positions, x), 1e-9);
        o.preconditioner = fairing::Preconditioner::Jacobi;
        const fairing::Result one_by_one = fairing::fair(m, {}, o);
        expect_one_by_one(one_by_one, 4);
        EXPECT_LT(meshes::max_row_distance(at_once.positions, one_by_one.positions), 1e-9);
    }
}
