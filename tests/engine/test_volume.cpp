// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Sections 3.1-3.2: exact volume preservation, per closed component, by the paper's scaling
// about the component's (solid) centroid (VolumeRestoration::Scale) or by the default normal
// offset; open components: area or nothing.
//
// What is asserted about centroids: after one step, each closed component of the restored
// result is exactly the unrestored result (same options with preserve_volume = false) scaled
// by beta = (V0 / Vn)^(1/3) about that component's solid centroid (fairing.h, invariants.h).
// So the solid centroid of every component is the one the smoothing step produced, and the
// restoration never drags a component toward or away from the world origin (the components sit
// far from it). The normal offset moves every vertex by one distance along its normal, and less
// in all than the scaling. Volumes are recomputed here with eq. 10 on the output positions.
#include "meshes.h"

#include "fairing/invariants.h"

#include <gtest/gtest.h>

#include <cmath>

using fairing::Operator;
using fairing::OpenInvariant;
using fairing::Options;
using fairing::Restoration;
using fairing::Triangle;
using fairing::TriangleMesh;
using meshes::Positions;
using meshes::Vec3;

namespace {

using meshes::kOperators;

Options options(Operator op, int order, int steps, double time_step = 2.0) {
    Options o;
    o.restoration = fairing::VolumeRestoration::Scale;
    o.op = op;
    o.order = order;
    o.steps = steps;
    o.time_step = time_step;
    o.preserve_volume = true;
    o.cancel_drift = false;  // the restoration alone; the translation: the last test
    o.max_iterations = 20000;
    return o;
}

// The faces of `m` whose vertices are in [first, last).
std::vector<Triangle> faces_in(const TriangleMesh& m, int first, int last) {
    std::vector<Triangle> out;
    for (const Triangle& t : m.triangles)
        if (t[0] >= first && t[0] < last) out.push_back(t);
    return out;
}

const fairing::ComponentReport* component_with_faces(const fairing::Result& r, int faces) {
    for (const auto& c : r.components)
        if (c.faces == faces) return &c;
    return nullptr;
}

}  // namespace

TEST(Volume, ExactAfterEveryStepAllOperators) {
    const TriangleMesh shapes[] = {meshes::radial_noise(meshes::icosphere(2), 0.1, 5),
                                   meshes::box_noise(meshes::box(4, 1.0, 0.6, 0.4), 0.02, 6)};
    for (const TriangleMesh& m : shapes) {
        const double v0 = meshes::volume(m.positions, m.triangles);
        ASSERT_GT(v0, 0);
        for (Operator op : kOperators)
            for (int order : {1, 2})
                for (int steps : {1, 2, 3}) {
                    SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order
                                                    << " steps " << steps);
                    const fairing::Result r = fairing::fair(m, {}, options(op, order, steps));
                    ASSERT_TRUE(r.positions.allFinite());
                    EXPECT_EQ(r.steps, steps);
                    EXPECT_NEAR(meshes::volume(r.positions, m.triangles), v0, 1e-12 * v0);
                    EXPECT_NEAR(r.volume_before, v0, 1e-12 * v0);
                    EXPECT_NEAR(r.volume_after, v0, 1e-12 * v0);
                    ASSERT_EQ(r.components.size(), 1u);
                    EXPECT_TRUE(r.components[0].closed);
                    EXPECT_FALSE(r.components[0].has_fixed);
                    EXPECT_EQ(r.components[0].restoration, Restoration::Scale);
                    EXPECT_NEAR(r.components[0].measure_before, v0, 1e-12 * v0);
                    EXPECT_NEAR(r.components[0].measure_after, v0, 1e-12 * v0);
                    // The shape did change: this is not a no-op.
                    EXPECT_GT(meshes::max_row_distance(r.positions, m.positions), 1e-3);
                }
    }
}

TEST(Volume, PerComponentAndScaledAboutSolidCentroid) {
    // A noisy sphere (radius 1) and a noisy box (0.5 x 0.4 x 0.3), far from the origin and from
    // each other.
    const TriangleMesh a = meshes::radial_noise(meshes::icosphere(2, 1.0, Vec3(40, -10, 5)), 0.1,
                                                12, Vec3(40, -10, 5));
    const TriangleMesh b = meshes::translated(
        meshes::box_noise(meshes::box(3, 0.5, 0.4, 0.3), 0.02, 13), Vec3(-30, 20, -7));
    const TriangleMesh m = meshes::merge(a, b);
    const int na = static_cast<int>(a.positions.rows()), n = static_cast<int>(m.positions.rows());
    const std::vector<Triangle> fa = faces_in(m, 0, na), fb = faces_in(m, na, n);
    const double va = meshes::volume(m.positions, fa), vb = meshes::volume(m.positions, fb);

    for (Operator op : kOperators) {
        for (int order : {1, 2}) {
            SCOPED_TRACE(testing::Message() << fairing::to_string(op) << " order " << order);
            for (int steps : {1, 3}) {
                const fairing::Result r = fairing::fair(m, {}, options(op, order, steps));
                EXPECT_NEAR(meshes::volume(r.positions, fa), va, 1e-12 * va);
                EXPECT_NEAR(meshes::volume(r.positions, fb), vb, 1e-12 * vb);
                EXPECT_NEAR(r.volume_before, va + vb, 1e-12 * (va + vb));
                EXPECT_NEAR(r.volume_after, va + vb, 1e-12 * (va + vb));
                ASSERT_EQ(r.components.size(), 2u);
                const auto* ca = component_with_faces(r, static_cast<int>(fa.size()));
                const auto* cb = component_with_faces(r, static_cast<int>(fb.size()));
                ASSERT_TRUE(ca && cb);
                EXPECT_EQ(ca->restoration, Restoration::Scale);
                EXPECT_EQ(cb->restoration, Restoration::Scale);
                EXPECT_NEAR(ca->measure_after, va, 1e-12 * va);
                EXPECT_NEAR(cb->measure_after, vb, 1e-12 * vb);
            }

            // One step: restored = unrestored scaled about each component's solid centroid.
            Options plain = options(op, order, 1);
            plain.preserve_volume = false;
            const fairing::Result raw = fairing::fair(m, {}, plain);
            const fairing::Result kept = fairing::fair(m, {}, options(op, order, 1));
            for (int part = 0; part < 2; ++part) {
                const std::vector<Triangle>& f = part == 0 ? fa : fb;
                const int first = part == 0 ? 0 : na, last = part == 0 ? na : n;
                const double v0 = part == 0 ? va : vb;
                const double vn = meshes::volume(raw.positions, f);
                ASSERT_LT(vn, v0);  // the step shrank it
                const Vec3 c = meshes::solid_centroid(raw.positions, f);
                const double beta = std::cbrt(v0 / vn);
                const double size = part == 0 ? 2.0 : 0.7;
                double worst = 0;
                for (int i = first; i < last; ++i) {
                    const Vec3 expected = c + beta * (meshes::row(raw.positions, i) - c);
                    worst = std::max(worst, (meshes::row(kept.positions, i) - expected).norm());
                }
                EXPECT_LT(worst, 1e-11 * size) << "component " << part;
                EXPECT_LT((meshes::solid_centroid(kept.positions, f) - c).norm(), 1e-11 * size);
            }
        }
    }
}

TEST(Volume, OpenComponentAreaOrNothing) {
    const TriangleMesh m = meshes::noisy_open_grid(10, 0.0, 0.4, 31);
    const double a0 = meshes::area(m.positions, m.triangles);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        // Nothing restored: the surface area decreases (smoothing removes the noise).
        Options none = options(op, 2, 2);
        none.open_invariant = OpenInvariant::None;
        const fairing::Result rn = fairing::fair(m, {}, none);
        ASSERT_EQ(rn.components.size(), 1u);
        EXPECT_FALSE(rn.components[0].closed);
        EXPECT_EQ(rn.components[0].restoration, Restoration::None);
        EXPECT_LT(meshes::area(rn.positions, m.triangles), a0);
        EXPECT_EQ(rn.volume_before, 0.0);  // no closed component
        EXPECT_EQ(rn.volume_after, 0.0);

        // Area, boundary Fixed: the free vertices are offset along their normals.
        Options fixed = none;
        fixed.open_invariant = OpenInvariant::Area;
        fixed.boundary = fairing::BoundaryMode::Fixed;
        const fairing::Result rf = fairing::fair(m, {}, fixed);
        EXPECT_TRUE(rf.components[0].has_fixed);
        EXPECT_EQ(rf.components[0].restoration, Restoration::NormalOffset);
        EXPECT_NEAR(meshes::area(rf.positions, m.triangles), a0, 1e-12 * a0);
        EXPECT_NEAR(rf.components[0].measure_before, a0, 1e-12 * a0);
        EXPECT_NEAR(rf.components[0].measure_after, a0, 1e-12 * a0);
        for (const auto& loop : meshes::boundary_loops(m.triangles))
            for (int v : loop) EXPECT_TRUE(rf.positions.row(v) == m.positions.row(v));

        // Area, free boundary curve: no fixed vertex, scaled about the surface's centroid.
        Options curve = fixed;
        curve.boundary = fairing::BoundaryMode::SmoothCurve;
        const fairing::Result rc = fairing::fair(m, {}, curve);
        EXPECT_FALSE(rc.components[0].has_fixed);
        EXPECT_EQ(rc.components[0].restoration, Restoration::Scale);
        EXPECT_NEAR(meshes::area(rc.positions, m.triangles), a0, 1e-12 * a0);
    }
}

TEST(Volume, ClosedAndOpenComponentsTogether) {
    const TriangleMesh sphere = meshes::radial_noise(meshes::icosphere(2), 0.1, 41);
    const TriangleMesh sheet =
        meshes::translated(meshes::noisy_open_grid(6, 0.0, 0.4, 42), Vec3(5, 0, 0));
    const TriangleMesh m = meshes::merge(sphere, sheet);
    const int ns = static_cast<int>(sphere.positions.rows()), n = static_cast<int>(m.positions.rows());
    const std::vector<Triangle> fs = faces_in(m, 0, ns), fo = faces_in(m, ns, n);
    const double v0 = meshes::volume(m.positions, fs), a0 = meshes::area(m.positions, fo);
    Options o = options(Operator::CurvatureFlow, 2, 2);
    o.open_invariant = OpenInvariant::Area;
    o.boundary = fairing::BoundaryMode::SmoothCurve;
    const fairing::Result r = fairing::fair(m, {}, o);
    EXPECT_NEAR(meshes::volume(r.positions, fs), v0, 1e-12 * v0);
    EXPECT_NEAR(meshes::area(r.positions, fo), a0, 1e-12 * a0);
    EXPECT_NEAR(r.volume_before, v0, 1e-12 * v0);  // closed components only
    const auto* cs = component_with_faces(r, static_cast<int>(fs.size()));
    const auto* co = component_with_faces(r, static_cast<int>(fo.size()));
    ASSERT_TRUE(cs && co);
    EXPECT_TRUE(cs->closed);
    EXPECT_FALSE(co->closed);
    EXPECT_NEAR(co->measure_after, a0, 1e-12 * a0);
}

TEST(Volume, OffSwitchLetsItShrink) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(2), 0.1, 5);
    Options o = options(Operator::CurvatureFlow, 2, 2);
    o.preserve_volume = false;
    const fairing::Result r = fairing::fair(m, {}, o);
    const double v0 = meshes::volume(m.positions, m.triangles);
    EXPECT_LT(meshes::volume(r.positions, m.triangles), 0.999 * v0);
    ASSERT_EQ(r.components.size(), 1u);
    EXPECT_EQ(r.components[0].restoration, Restoration::None);
}

// The normal offset (the default): the restored result is the unrestored one with every vertex
// moved by one common distance along its area-weighted unit normal, the volume is exact, and on
// a torus, whose outer rim is far from its centroid, the correction is much smaller than the
// paper's scaling (by the area-weighted norm that the offset minimizes to first order).
TEST(Volume, NormalOffsetIsOneDistanceAlongTheNormals) {
    const TriangleMesh m = meshes::box_noise(meshes::torus_grid(48, 16), 0.05, 17);
    const double v0 = meshes::volume(m.positions, m.triangles);
    for (Operator op : kOperators) {
        SCOPED_TRACE(fairing::to_string(op));
        Options o = options(op, 2, 1);
        o.shaped_offset = false;  // the uniform offset (test_offset_shape.cpp: the shaped one)
        o.preserve_volume = false;
        const fairing::Result raw = fairing::fair(m, {}, o);
        o.preserve_volume = true;
        o.restoration = fairing::VolumeRestoration::NormalOffset;
        const fairing::Result off = fairing::fair(m, {}, o);
        o.restoration = fairing::VolumeRestoration::Scale;
        const fairing::Result scaled = fairing::fair(m, {}, o);
        ASSERT_EQ(off.components.size(), 1u);
        EXPECT_EQ(off.components[0].restoration, Restoration::NormalOffset);
        EXPECT_EQ(scaled.components[0].restoration, Restoration::Scale);
        EXPECT_NEAR(meshes::volume(off.positions, m.triangles), v0, 1e-12 * v0);
        EXPECT_NEAR(off.volume_after, v0, 1e-12 * v0);

        // Area-weighted unit normals of the unrestored result.
        Positions normal = Positions::Zero(m.positions.rows(), 3);
        for (const Triangle& t : m.triangles) {
            const Vec3 a = meshes::row(raw.positions, t[0]);
            const Vec3 n = (meshes::row(raw.positions, t[1]) - a).cross(meshes::row(raw.positions, t[2]) - a);
            for (int v : t) normal.row(v) += n.transpose();
        }
        normal.rowwise().normalize();
        const Positions d = off.positions - raw.positions;
        const double t0 = d.row(0).dot(normal.row(0));
        EXPECT_GT(t0, 0);  // the step shrank the torus: the offset is outwards
        for (int i = 0; i < d.rows(); ++i) {
            EXPECT_NEAR(d.row(i).dot(normal.row(i)), t0, 1e-9 * std::abs(t0));
            EXPECT_LT((d.row(i) - t0 * normal.row(i)).norm(), 1e-9 * std::abs(t0));
        }
        const double moved_offset = d.norm(), moved_scale = (scaled.positions - raw.positions).norm();
        EXPECT_LT(moved_offset, 0.5 * moved_scale);
    }
}

// A gross loss (a strong first-order step collapsing much of the sphere) would fold an offset
// surface over itself: past kMaxOffsetChange the default scales, and says so.
TEST(Volume, GrossLossIsScaledEvenWithTheNormalOffset) {
    const TriangleMesh m = meshes::radial_noise(meshes::icosphere(2), 0.1, 5);
    const double v0 = meshes::volume(m.positions, m.triangles);
    for (double time_step : {0.01, 100.0}) {
        SCOPED_TRACE(time_step);
        Options o = options(Operator::CurvatureFlow, 1, 1, time_step);
        o.preserve_volume = false;
        const double lost = 1 - meshes::volume(fairing::fair(m, {}, o).positions, m.triangles) / v0;
        o.preserve_volume = true;
        o.restoration = fairing::VolumeRestoration::NormalOffset;
        const fairing::Result r = fairing::fair(m, {}, o);
        EXPECT_NEAR(meshes::volume(r.positions, m.triangles), v0, 1e-12 * v0);
        if (time_step < 1) {
            EXPECT_LT(lost, 0.5 * fairing::kMaxOffsetChange);
            EXPECT_EQ(r.components[0].restoration, Restoration::NormalOffset);
        } else {
            EXPECT_GT(lost, 2 * fairing::kMaxOffsetChange);
            EXPECT_EQ(r.components[0].restoration, Restoration::Scale);
        }
    }
}

// The translation t minimizing sum_f A_f (n_f . (d_f - t))^2, d_f the mean displacement of face
// f's vertices from `from` to `to`, A_f n_f its area vector (on `to`).
Vec3 normal_translation(const Positions& from, const Positions& to,
                        const std::vector<Triangle>& f) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Vec3 b = Vec3::Zero();
    for (const Triangle& t : f) {
        const Vec3 a = meshes::row(to, t[0]);
        const Vec3 av = 0.5 * (meshes::row(to, t[1]) - a).cross(meshes::row(to, t[2]) - a);
        const double area = av.norm();
        const Vec3 n = av / area;
        Vec3 d = Vec3::Zero();
        for (int k = 0; k < 3; ++k) d += (meshes::row(to, t[k]) - meshes::row(from, t[k])) / 3;
        m += area * n * n.transpose();
        b += area * n * n.dot(d);
    }
    return m.ldlt().solve(b);
}

// Options::cancel_drift: the curvature flow's result is the same as without it but for one
// translation per closed component without fixed vertices, after which the component's
// displacement from the input has no translation left along its normals (least squares); its
// volume stays restored. A component with a fixed vertex, the other operators and
// preserve_volume = false are left exactly as without it.
TEST(Volume, CancelDriftTakesTheTranslationOutOfTheCurvatureFlow) {
    // A noisy two-density sphere (radius 1), a noisy box, and a noisy sphere with one fixed
    // vertex, all far from the origin.
    const Vec3 ca(40, -10, 5), cc(-5, 30, 12);
    const TriangleMesh a = meshes::translated(
        meshes::gaussian_radial_noise(meshes::two_density_sphere(2), 0.02, 21), ca);
    const TriangleMesh b = meshes::translated(
        meshes::box_noise(meshes::box(3, 0.5, 0.4, 0.3), 0.02, 13), Vec3(-30, 20, -7));
    const TriangleMesh c = meshes::radial_noise(meshes::icosphere(2, 1.0, cc), 0.05, 17, cc);
    const TriangleMesh m = meshes::merge(meshes::merge(a, b), c);
    const int na = static_cast<int>(a.positions.rows());
    const int nb = na + static_cast<int>(b.positions.rows());
    const int n = static_cast<int>(m.positions.rows());
    const std::vector<Triangle> fa = faces_in(m, 0, na), fb = faces_in(m, na, nb);
    fairing::Constraints fixed;
    fixed.fixed.assign(n, 0);
    fixed.fixed[nb] = 1;
    for (auto how : {fairing::VolumeRestoration::NormalOffset, fairing::VolumeRestoration::Scale}) {
        for (int order : {1, 2}) {
            for (int steps : {1, 3}) {
                const bool scale = how == fairing::VolumeRestoration::Scale;
                SCOPED_TRACE(testing::Message()
                             << "order " << order << " steps " << steps << " scale " << scale);
                const double time_step = order == 1 ? 4.0 : 400.0;
                Options o = options(Operator::CurvatureFlow, order, steps, time_step);
                o.restoration = how;
                o.cancel_drift = false;
                const fairing::Result plain = fairing::fair(m, fixed, o);
                o.cancel_drift = true;
                const fairing::Result kept = fairing::fair(m, fixed, o);
                for (int part = 0; part < 2; ++part) {
                    const std::vector<Triangle>& f = part == 0 ? fa : fb;
                    const int first = part == 0 ? 0 : na, last = part == 0 ? na : nb;
                    const double size = part == 0 ? 2.0 : 0.7;
                    EXPECT_LT(normal_translation(m.positions, kept.positions, f).norm(),
                              1e-11 * size);
                    EXPECT_NEAR(meshes::volume(kept.positions, f), meshes::volume(m.positions, f),
                                1e-12 * meshes::volume(m.positions, f));
                    // One translation per component.
                    const Vec3 shift =
                        meshes::row(kept.positions, first) - meshes::row(plain.positions, first);
                    double worst = 0;
                    for (int i = first; i < last; ++i)
                        worst = std::max(worst, (meshes::row(kept.positions, i) -
                                                 meshes::row(plain.positions, i) - shift).norm());
                    EXPECT_LT(worst, 1e-12 * size) << "component " << part;
                }
                // The noisy two-density sphere drifts without it (steps keep its area-weighted
                // centroid, which the noise moves towards the denser half).
                EXPECT_GT(normal_translation(m.positions, plain.positions, fa).norm(), 1e-5);
                for (int i = nb; i < n; ++i)
                    ASSERT_EQ(kept.positions.row(i), plain.positions.row(i));
                ASSERT_EQ(kept.positions.row(nb), m.positions.row(nb));
            }
        }
    }
    for (Operator op : {Operator::Umbrella, Operator::ScaleDependent}) {
        Options o = options(op, 2, 2);
        o.cancel_drift = false;
        const fairing::Result plain = fairing::fair(m, {}, o);
        o.cancel_drift = true;
        EXPECT_EQ(fairing::fair(m, {}, o).positions, plain.positions) << fairing::to_string(op);
    }
    Options o = options(Operator::CurvatureFlow, 2, 2, 400.0);
    o.preserve_volume = false;
    o.cancel_drift = false;
    const fairing::Result plain = fairing::fair(m, {}, o);
    o.cancel_drift = true;
    EXPECT_EQ(fairing::fair(m, {}, o).positions, plain.positions);
}
