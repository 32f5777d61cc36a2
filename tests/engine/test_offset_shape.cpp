// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Options::shaped_offset (src/offset_shape.h): the curvature flow's volume restoration puts the
// volume back where the flow took it. On a torus the flow of eq. 14 shrinks the outer rim, whose
// mean curvature (1/r + cos b / (R + r cos b)) / 2 is 3.9 times the inner rim's, fastest; on a
// sphere it shrinks every vertex alike and the offset must stay uniform.
#include "meshes.h"
#include "offset_shape.h"

#include "fairing/invariants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

using fairing::Operator;
using fairing::Options;
using fairing::Result;
using fairing::TriangleMesh;
using meshes::Positions;
using meshes::Vec3;

namespace {

constexpr double kMajor = 1.0, kMinor = 0.4;  // the denoising study's torus
// The automatic time step, and a given one about the automatic choice on these tori.
const fairing::OptionalDouble kAutomaticAndGiven[] = {fairing::OptionalDouble(), 60.0};

// The angle b around the tube (0 on the outer rim, pi on the inner one) and the tube's outward
// normal at p.
double tube_angle(const Vec3& p) {
    return std::atan2(p.z(), std::hypot(p.x(), p.y()) - kMajor);
}
Vec3 tube_normal(const Vec3& p) {
    const double a = std::atan2(p.y(), p.x());
    return (p - kMajor * Vec3(std::cos(a), std::sin(a), 0)).normalized();
}

// Gaussian noise of sigma_edges mean edges along the normals, as the study's.
TriangleMesh noisy_torus(double sigma_edges, std::uint64_t seed) {
    TriangleMesh m = meshes::torus_grid(90, 36, kMajor, kMinor);
    const double sigma = sigma_edges * meshes::mean_edge_length(m.positions, m.triangles);
    meshes::Rng rng(seed);
    for (int i = 0; i < m.positions.rows(); ++i) {
        const Vec3 p = meshes::row(m.positions, i);
        meshes::set_row(m.positions, i, p + sigma * rng.normal() * tube_normal(p));
    }
    return m;
}

// RMS distance of the vertices to the true torus.
double torus_error(const Positions& x) {
    double sum = 0;
    for (int i = 0; i < x.rows(); ++i) {
        const Vec3 p = meshes::row(x, i);
        const double d = std::hypot(std::hypot(p.x(), p.y()) - kMajor, p.z()) - kMinor;
        sum += d * d;
    }
    return std::sqrt(sum / x.rows());
}

// The error of a run at a given time step for a sweep, or infinity where the steps collapse the
// tube so far that restoring its volume would more than double the torus (refused: Run::restore).
double swept_error(const TriangleMesh& m, const Options& o) {
    try {
        return torus_error(fairing::fair(m, {}, o).positions);
    } catch (const fairing::Error& e) {
        EXPECT_NE(std::string(e.what()).find("flattened every component"), std::string::npos)
            << e.what();
        return std::numeric_limits<double>::infinity();
    }
}

// The curvature flow's one-click settings (L^2, four steps), automatic strength unless given.
Options curvature_flow(bool shaped, fairing::OptionalDouble time_step = {}) {
    Options o;
    o.op = Operator::CurvatureFlow;
    o.order = 2;
    o.steps = 4;
    o.time_step = time_step;
    o.shaped_offset = shaped;
    return o;
}

// The shape of a mesh of one closed component, as fair() computes it before its steps.
fairing::detail::OffsetShape shape_of(const TriangleMesh& m, double noise_level) {
    const int n = static_cast<int>(m.positions.rows());
    const fairing::HalfEdgeMesh he = fairing::HalfEdgeMesh::build(m.positions, m.triangles);
    const fairing::SparseOperator op =
        fairing::assemble(Operator::CurvatureFlow, he, m.positions);
    const std::vector<char> free(n, 1);
    const double volume = meshes::volume(m.positions, m.triangles);
    fairing::detail::OffsetShapeProblem p;
    p.mesh = &he;
    p.op = &op;
    p.x = &m.positions;
    p.free = &free;
    p.data_vertices = n;
    p.mean_edge = meshes::mean_edge_length(m.positions, m.triangles);
    p.noise_level = noise_level;
    p.component_of.assign(n, 0);
    p.components = 1;
    p.assemble_at = [&](const Positions& at) {
        return fairing::assemble(Operator::CurvatureFlow, he, at);
    };
    p.restore = [&](Positions& x) {
        fairing::restore_measure(he, he.components()[0], free, volume, x);
        return true;
    };
    return fairing::detail::curvature_offset_shape(p);
}

}  // namespace

TEST(OffsetShape, FollowsTheMeanCurvatureOnATorus) {
    const TriangleMesh m = noisy_torus(0.25, 1);
    const double sigma = 0.25 * meshes::mean_edge_length(m.positions, m.triangles);
    const fairing::detail::OffsetShape shape = shape_of(m, sigma);
    ASSERT_EQ(shape.weight.size(), static_cast<std::size_t>(m.positions.rows()));
    ASSERT_EQ(shape.kept_share.size(), 1u);
    EXPECT_GT(shape.kept_share[0], 0.9);  // the torus's curvature varies far more than the noise's
    double outer = 0, inner = 0, mean = 0;
    int outer_count = 0, inner_count = 0;
    for (int i = 0; i < m.positions.rows(); ++i) {
        const double w = shape.weight[i];
        EXPECT_GE(w, 0.0);
        mean += w;
        const double b = tube_angle(meshes::row(m.positions, i));
        if (std::cos(b) > 0.9) outer += w, ++outer_count;
        if (std::cos(b) < -0.9) inner += w, ++inner_count;
    }
    EXPECT_NEAR(mean / m.positions.rows(), 1.0, 1e-12);
    // The exact mean curvatures are 1.61 and 0.42 (ratio 3.9); the pilot step and the smoothing
    // blur them (2.0 on this torus).
    EXPECT_GT(outer / outer_count, 1.5 * (inner / inner_count));
}

TEST(OffsetShape, NoNoiseNoShape) {
    const fairing::detail::OffsetShape shape = shape_of(noisy_torus(0.25, 1), 0.0);
    EXPECT_TRUE(shape.weight.empty());
}

// A sphere's curvature is the same everywhere: what varies is noise and sampling, which the
// second draw shows, and the offset stays uniform bit for bit at every noise level.
TEST(OffsetShape, UniformOnANoisyTwoDensitySphere) {
    const TriangleMesh sphere = meshes::two_density_sphere(4);
    const double h = meshes::mean_edge_length(sphere.positions, sphere.triangles);
    for (double sigma_edges : {0.1, 0.25, 0.5}) {
        const TriangleMesh m = meshes::gaussian_radial_noise(sphere, sigma_edges * h, 11);
        const fairing::detail::OffsetShape shape = shape_of(m, sigma_edges * h);
        EXPECT_TRUE(shape.weight.empty()) << sigma_edges;
        const Result shaped = fairing::fair(m, {}, curvature_flow(true));
        const Result uniform = fairing::fair(m, {}, curvature_flow(false));
        EXPECT_EQ(shaped.time_step, uniform.time_step) << sigma_edges;
        EXPECT_TRUE(shaped.positions == uniform.positions) << sigma_edges;
    }
}

TEST(OffsetShape, KeepsTheVolumeExactly) {
    const TriangleMesh m = noisy_torus(0.25, 2);
    for (const fairing::OptionalDouble time_step : kAutomaticAndGiven) {
        const Result r = fairing::fair(m, {}, curvature_flow(true, time_step));
        ASSERT_EQ(r.components.size(), 1u);
        EXPECT_EQ(r.components[0].restoration, fairing::Restoration::NormalOffset);
        EXPECT_NEAR(r.volume_after / r.volume_before - 1, 0.0, 1e-12);
        EXPECT_NEAR(meshes::volume(r.positions, m.triangles) / r.volume_before - 1, 0.0, 1e-12);
    }
}

// The restored torus lies closer to the true one, at a given time step (by 5 % or more) and at
// the automatic one of the one-click L^2 flow, which is the uniform offset's (for L^2 steps the
// estimate models the uniform offset: auto-gap.md section 24) and where the shape gains less on
// this regular torus (4-5 %).
TEST(OffsetShape, RestoresCloserToTheTrueTorus) {
    for (std::uint64_t seed : {3, 4}) {
        const TriangleMesh m = noisy_torus(0.25, seed);
        for (const fairing::OptionalDouble time_step : kAutomaticAndGiven) {
            const Result shaped = fairing::fair(m, {}, curvature_flow(true, time_step));
            const Result uniform = fairing::fair(m, {}, curvature_flow(false, time_step));
            EXPECT_EQ(shaped.time_step, uniform.time_step);
            EXPECT_LT(torus_error(shaped.positions),
                      (time_step.has_value() ? 0.95 : 0.98) * torus_error(uniform.positions))
                << "seed " << seed << (time_step.has_value() ? ", time step 60" : ", automatic");
        }
    }
}

// The first-order curvature flow loses its mean curvature, which the shape follows, so the
// automatic strength models the shaped offset there (auto-gap.md section 25) and chooses for it:
// stronger steps than the uniform offset's at 0.1 and a quarter edge (measured 0.68-0.82 of its
// error, 1.00-1.09 of the best fixed step's on a grid of ratio 1.25).
TEST(OffsetShape, FirstOrderAutomaticStrengthModelsTheShape) {
    for (std::uint64_t seed : {3, 4})
        for (double sigma_edges : {0.1, 0.25})
            for (int steps : {1, 4}) {
                SCOPED_TRACE(testing::Message() << "seed " << seed << ", noise " << sigma_edges
                                                << ", steps " << steps);
                const TriangleMesh m = noisy_torus(sigma_edges, seed);
                Options shaped = curvature_flow(true), uniform = curvature_flow(false);
                shaped.order = uniform.order = 1;
                shaped.steps = uniform.steps = steps;
                const Result chosen = fairing::fair(m, {}, shaped);
                const Result chosen_uniform = fairing::fair(m, {}, uniform);
                EXPECT_GT(chosen.time_step, chosen_uniform.time_step);
                const double error = torus_error(chosen.positions);
                EXPECT_LT(error, 0.85 * torus_error(chosen_uniform.positions));
                double best = std::numeric_limits<double>::infinity();
                for (double time_step = 0.5; time_step < 200; time_step *= 1.25) {
                    shaped.time_step = time_step;
                    best = std::min(best, swept_error(m, shaped));
                }
                EXPECT_LT(error, 1.15 * best);
            }
}

// The first-order choice that models the shape, with a selection, soft weights, several steps
// and a second closed component (a sphere, whose own offset stays uniform): a finite positive
// step, every closed component's volume kept, the selection where it was, the torus closer to the
// true one than the input and than the uniform offset at its own choice (measured 0.71-0.95 of
// its error).
TEST(OffsetShape, FirstOrderModelledShapeWithEveryConstraint) {
    const TriangleMesh torus = noisy_torus(0.25, 6);
    const int n = static_cast<int>(torus.positions.rows());
    const fairing::Constraints selection = meshes::every_nth_fixed(n, 7);
    const fairing::Constraints weights = meshes::ramped_weights(n);
    const TriangleMesh sphere = meshes::translated(
        meshes::gaussian_radial_noise(meshes::two_density_sphere(3, 0.5), 0.01, 12), Vec3(4, 0, 0));
    const TriangleMesh both = meshes::merge(torus, sphere);
    for (int variant = 0; variant < 4; ++variant) {
        SCOPED_TRACE(testing::Message() << "variant " << variant);
        Options o = curvature_flow(true);
        o.order = 1;
        o.steps = variant == 2 ? 3 : 1;
        const bool two = variant == 3;
        fairing::Constraints c = variant == 0 ? selection : variant == 1 ? weights
                                                                         : fairing::Constraints{};
        const Result r = fairing::fair(two ? both : torus, c, o);
        ASSERT_TRUE(r.positions.allFinite());
        EXPECT_GT(r.time_step, 0);
        ASSERT_EQ(r.components.size(), two ? 2u : 1u);
        for (const fairing::ComponentReport& k : r.components)
            EXPECT_NEAR(k.measure_after / k.measure_before - 1, 0.0, 1e-10);
        const double error = torus_error(r.positions.topRows(n));
        EXPECT_LT(error, 0.8 * torus_error(torus.positions));
        Options uniform = o;
        uniform.shaped_offset = false;
        const Result u = fairing::fair(two ? both : torus, c, uniform);
        EXPECT_LT(error, torus_error(u.positions.topRows(n)));
        for (int i = 0; i < n && variant == 0; ++i) {
            if (selection.fixed[i]) {
                ASSERT_EQ(r.positions.row(i), torus.positions.row(i));
            }
        }
    }
}

TEST(OffsetShape, AnExplicitTimeStepIsUsedAsGiven) {
    const Result r = fairing::fair(noisy_torus(0.25, 5), {}, curvature_flow(true, 37.5));
    EXPECT_FALSE(r.automatic_time_step);
    EXPECT_EQ(r.time_step, 37.5);
}

// Only the curvature flow's normal offset is shaped: the other operators, the rescaling and
// open components are as before.
TEST(OffsetShape, OnlyTheCurvatureFlowsNormalOffset) {
    const TriangleMesh m = noisy_torus(0.25, 6);
    for (Operator op : {Operator::Umbrella, Operator::ScaleDependent}) {
        Options shaped = curvature_flow(true, 1.0), uniform = curvature_flow(false, 1.0);
        shaped.op = uniform.op = op;
        EXPECT_TRUE(fairing::fair(m, {}, shaped).positions ==
                    fairing::fair(m, {}, uniform).positions);
    }
    Options shaped = curvature_flow(true, 60.0), uniform = curvature_flow(false, 60.0);
    shaped.restoration = uniform.restoration = fairing::VolumeRestoration::Scale;
    EXPECT_TRUE(fairing::fair(m, {}, shaped).positions == fairing::fair(m, {}, uniform).positions);
}

// The shape's two pilot solves report progress (the first tenth of the range), and the whole
// run's progress stays monotone and ends at 1.
TEST(OffsetShape, ProgressIsMonotone) {
    std::vector<double> seen;
    Options o = curvature_flow(true);
    o.progress = [&seen](double f) { seen.push_back(f); };
    fairing::fair(noisy_torus(0.25, 7), {}, o);
    ASSERT_FALSE(seen.empty());
    EXPECT_GT(seen.front(), 0.0);
    EXPECT_LE(seen.front(), 0.1);
    for (std::size_t k = 1; k < seen.size(); ++k) EXPECT_GT(seen[k], seen[k - 1]);
    EXPECT_EQ(seen.back(), 1.0);
}

// Several first-order steps of the curvature flow each restore the volume (fair() restores after
// every step of a recomputed operator), and a step whose volume changes by more than
// kMaxOffsetChange is rescaled, not offset, which cost the study's torus 4-9x its error. The
// estimate places that switch per step: on the steps' total it held these choices at a third to
// a half of the best step (1.41-1.57x its error; 1.02-1.12x per step; auto-gap.md section 26).
TEST(OffsetShape, SeveralFirstOrderStepsSwitchPerStep) {
    for (std::uint64_t seed : {3, 4})
        for (int steps : {2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << ", steps " << steps);
            const TriangleMesh m = noisy_torus(0.5, seed);
            Options o = curvature_flow(true);
            o.order = 1;
            o.steps = steps;
            const Result chosen = fairing::fair(m, {}, o);
            const double error = torus_error(chosen.positions);
            double best = std::numeric_limits<double>::infinity();
            for (double time_step = 0.5; time_step < 40; time_step *= 1.1) {
                o.time_step = time_step;
                best = std::min(best, swept_error(m, o));
            }
            EXPECT_LT(error, 1.2 * best);
        }
}
