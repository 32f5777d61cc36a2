// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Issue 6, item 2: a solve that cannot converge within the iteration cap is reported with its
// residual and leaves the mesh unchanged; with accept_unconverged the last iterate is written
// and a warning carries the residual. The refusals switch off Options::direct_fallback, which
// would otherwise solve such a solve directly (the last tests here).
#include "robust.h"

#include <cmath>
#include <cstdlib>
#include <string>

using namespace robust;

namespace {

// The residual printed in a message: the number after "residual ".
double residual_in(const std::string& msg) {
    const std::size_t at = msg.find("residual ");
    if (at == std::string::npos) return -1;
    return std::strtod(msg.c_str() + at + 9, nullptr);
}

}  // namespace

TEST(NonConverging, IterationCapOneIsRefusedWithResidual) {
    const TriangleMesh m = noisy_sphere(3);
    for (Operator op : meshes::kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = defaults(op);
            o.order = order;
            o.max_iterations = 1;
            o.direct_fallback = false;
            const std::string msg = expect_refused(
                m, {}, o, {"did not converge in 1 iterations", "residual", "tolerance 1e-08",
                           "the mesh was left unchanged", "Raise the iteration cap"});
            EXPECT_GT(residual_in(msg), o.tolerance) << msg;
        }
}

TEST(NonConverging, AcceptUnconvergedWritesWithWarning) {
    const TriangleMesh m = noisy_sphere(3);
    for (Operator op : meshes::kOperators) {
        Options o = defaults(op);
        o.max_iterations = 1;
        o.accept_unconverged = true;  // the last iterate asked for: no direct solve
        const Result r = expect_result(m, {}, o);
        ASSERT_EQ(r.solves.size(), 1u);
        EXPECT_FALSE(r.solves[0].converged);
        EXPECT_EQ(r.solves[0].iterations, 1);
        EXPECT_GT(r.max_residual, o.tolerance);
        EXPECT_TRUE(has_warning(r, "did not converge in 1 iterations")) << warnings(r);
        EXPECT_TRUE(has_warning(r, "unconverged result was kept")) << warnings(r);
        bool residual_named = false;
        for (const std::string& w : r.warnings)
            residual_named = residual_named ||
                             std::abs(residual_in(w) / r.max_residual - 1) < 1e-5;
        EXPECT_TRUE(residual_named) << warnings(r);
        EXPECT_GT(r.vertices_moved, 0);
        // volume still restored on the unconverged iterate
        EXPECT_NEAR(volume_of(r.positions, m.triangles), volume_of(m.positions, m.triangles),
                    1e-9 * volume_of(m.positions, m.triangles));
    }
}

TEST(NonConverging, FailureInALaterStepStillLeavesTheMeshUnchanged) {
    // Step 1 converges, a later one cannot: nothing of the earlier steps escapes. Jacobi: the
    // automatic preconditioner would hand the stalled solve to the multigrid V-cycle.
    const TriangleMesh m = noisy_sphere(3);
    Options o = defaults(Operator::CurvatureFlow);
    o.steps = 3;
    o.preconditioner = fairing::Preconditioner::Jacobi;
    const Result ok = expect_result(m, {}, o);
    int most = 0;
    for (const auto& s : ok.solves) most = std::max(most, s.iterations);
    ASSERT_GT(most, 2);
    o.max_iterations = most - 1;
    o.direct_fallback = false;
    expect_refused(m, {}, o, {"did not converge", "residual"});
}

TEST(NonConverging, SmoothBoundaryCurveSolveIsReportedToo) {
    const TriangleMesh m = meshes::noisy_open_grid(16, 0.3, 0.3);
    Options o = defaults(Operator::ScaleDependent);
    o.boundary = fairing::BoundaryMode::SmoothCurve;
    o.max_iterations = 1;
    o.direct_fallback = false;
    expect_refused(m, {}, o, {"did not converge", "residual"});
}

// A surface solve that stops short of the tolerance is solved again directly
// (Options::direct_fallback): the run succeeds with the result of the converged iterative solves
// (to their tolerance), and each step's report says how it was solved.
TEST(NonConverging, StoppedSolveIsSolvedDirectly) {
    const TriangleMesh m = noisy_sphere(3);
    for (Operator op : meshes::kOperators)
        for (int order : {1, 2, 3, 4}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            Options o = defaults(op);
            o.order = order;
            o.steps = 2;
            o.preconditioner = fairing::Preconditioner::Jacobi;  // no frozen or Lanczos steps
            o.freeze_operator = false;
            const Result converged = expect_result(m, {}, o);
            o.max_iterations = 1;
            const Result r = expect_result(m, {}, o);
            ASSERT_EQ(r.solves.size(), 2u);
            for (const fairing::SolveReport& s : r.solves) {
                EXPECT_TRUE(s.direct);
                EXPECT_TRUE(s.converged);
                EXPECT_EQ(s.iterations, 1);
                EXPECT_LT(s.residual, 1e-12);
            }
            EXPECT_TRUE(r.warnings.empty()) << warnings(r);
            const double size = meshes::bbox_diagonal(m.positions);
            EXPECT_LT((r.positions - converged.positions).cwiseAbs().maxCoeff(), 1e-6 * size);
            EXPECT_GT((r.positions - m.positions).cwiseAbs().maxCoeff(), 1e-3 * size);
        }
}

// A vertex whose star is 1e-4 times its neighbours' size has 1e-8 of the mean area, and M^-1
// enters an order-p system p - 1 times: a failed L^3 solve names that ratio and a frozen
// operator or a lower order as the way out; a first-order solve, which has no M^-1, does not.
TEST(NonConverging, ShrunkVertexStarIsNamed) {
    TriangleMesh m = noisy_sphere(3);
    const int centre = m.triangles[0][0];
    std::vector<char> in_star(m.positions.rows(), 0);
    for (const auto& t : m.triangles)
        if (t[0] == centre || t[1] == centre || t[2] == centre)
            for (int v : t) in_star[v] = 1;
    for (int v = 0; v < m.positions.rows(); ++v)
        if (in_star[v] && v != centre)
            m.positions.row(v) = m.positions.row(centre) +
                                 1e-4 * (m.positions.row(v) - m.positions.row(centre));
    for (int order : {1, 3}) {
        SCOPED_TRACE(testing::Message() << "order " << order);
        Options o = defaults(Operator::CurvatureFlow);
        o.order = order;
        o.time_step = 1;
        o.max_iterations = 1;
        o.direct_fallback = false;
        const std::string msg = expect_refused(m, {}, o, {"did not converge", "residual"});
        const bool named = msg.find("the smallest vertex mass") != std::string::npos;
        EXPECT_EQ(named, order == 3) << msg;
        if (order == 3) {
            EXPECT_NE(msg.find("order-3 system"), std::string::npos) << msg;
            EXPECT_NE(msg.find("freeze the operator"), std::string::npos) << msg;
        }
    }
}

// Recomputed L^3 and L^4 curvature steps can shrink vertex stars until a later step's system is
// out of reach (one click at order 4 on several of libcgal-demo's scans). From that step on,
// the steps keep the last operator that solved: here step 4 keeps step 3's, so the run equals
// two recomputed steps followed by two on the operator frozen at their result (section 4.3).
// Order 4: at order 3 this mesh's third step now counts as blown up (it threw a spike's vertex
// 10.6 times the sphere's RMS radius; RecomputedHighOrderStepThatBlowsUpKeepsTheLastOperator).
TEST(NonConverging, RecomputedHighOrderStepsKeepTheLastOperatorThatSolved) {
    TriangleMesh m = meshes::gaussian_radial_noise(meshes::icosphere(3), 0.02, 1);
    meshes::Rng rng(1);
    for (int k = 0; k < 20; ++k) {  // spikes five radii long, whose stars the steps shrink
        const int v = static_cast<int>(rng.uniform() * m.positions.rows()) % m.positions.rows();
        m.positions.row(v) *= 5;
    }
    Options o = defaults(Operator::CurvatureFlow);
    o.order = 4;
    o.steps = 4;
    o.time_step = 100;
    o.preserve_volume = false;  // restored once per run: the runs below compare like with like
    o.cancel_drift = false;
    o.direct_fallback = false;  // a factorization about the centroid solves that step here
    const Result r = expect_result(m, {}, o);
    EXPECT_TRUE(has_warning(r, "step 4 kept the operator of step 3 (frozen, section 4.3)"))
        << warnings(r);
    EXPECT_TRUE(has_warning(r, "its smallest vertex area was")) << warnings(r);
    EXPECT_EQ(r.steps, 4);
    ASSERT_EQ(r.solves.size(), 4u);
    for (const fairing::SolveReport& s : r.solves) EXPECT_TRUE(s.converged);

    o.steps = 2;
    const Result two = expect_result(m, {}, o);
    TriangleMesh halfway = m;
    halfway.positions = two.positions;
    o.freeze_operator = true;
    // The same lambda_dt: the time step is relative to the run's input mean edge (^(2 order)).
    const double edge_ratio = meshes::mean_edge_length(m.positions, m.triangles) /
                              meshes::mean_edge_length(halfway.positions, m.triangles);
    o.time_step = 100 * std::pow(edge_ratio, 2 * o.order);
    const Result frozen = expect_result(halfway, {}, o);
    const double size = meshes::bbox_diagonal(m.positions);
    EXPECT_LT((r.positions - frozen.positions).cwiseAbs().maxCoeff(), 1e-6 * size);
    EXPECT_GT((r.positions - two.positions).cwiseAbs().maxCoeff(), 1e-3 * size);
}

// A recomputed L^4 step can also solve well and still blow up: on tiny noisy open patches whose
// loops a strong step draws in first, the later steps' solves converged and threw vertices up to
// 1e12 times the patch's size (and on libcgal-demo's b9_mesh, one click at order 4, vertices of a
// 1,703-vertex part up to 1,540 mean edges). A step that throws a vertex more than ten times its
// part's RMS radius is taken again on the last operator that solved, as one that could not be.
TEST(NonConverging, RecomputedHighOrderStepThatBlowsUpKeepsTheLastOperator) {
    int retaken = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(testing::Message() << "seed " << seed);
        TriangleMesh m = meshes::grid(3, 3, 3.0, 3.0);  // 16 vertices, cells of 1
        meshes::Rng rng(seed);
        for (int i = 0; i < m.positions.rows(); ++i)
            for (int c = 0; c < 3; ++c) m.positions(i, c) += (c == 2 ? 0.5 : 0.15) * rng.normal();
        Options o = defaults(Operator::CurvatureFlow);
        o.order = 4;
        o.steps = 4;
        o.time_step = 1000;
        o.boundary = fairing::BoundaryMode::SmoothCurve;
        const Result r = expect_result(m, {}, o);
        const double size = meshes::bbox_diagonal(m.positions);
        EXPECT_LT(meshes::max_row_distance(r.positions, m.positions), size);
        if (has_warning(r, "times its part's RMS radius")) {
            ++retaken;
            EXPECT_TRUE(has_warning(r, "kept the operator of step")) << warnings(r);
        }
    }
    EXPECT_GT(retaken, 0);
}
