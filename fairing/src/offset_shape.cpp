// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "offset_shape.h"

#include "fairing/solver.h"
#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fairing {
namespace detail {
namespace {

// Unit area-weighted vertex normals (0 where undefined).
Positions area_normals(const HalfEdgeMesh& mesh, const Positions& x) {
    Positions normals = area_normal_sums(mesh, x);
    normalize_rows(normals);
    return normals;
}

// A standard normal deviate per vertex, from its index alone (Box-Muller on two splitmix64
// draws).
double gaussian(int i) {
    const auto uniform = [i](std::uint64_t salt) {  // in (0, 1]
        return (static_cast<double>(splitmix64(static_cast<std::uint64_t>(i) ^ salt) >> 11) + 1) *
               0x1.0p-53;
    };
    const double u = uniform(0x5be0cd19137e2179ull), v = uniform(0x1f83d9abfb41bd6bull);
    return std::sqrt(-2 * std::log(u)) * std::cos(6.283185307179586 * v);
}

// Whether an operator assembled at other positions has the rows of fair()'s and a mass on every
// free one.
bool keeps_masses(const OffsetShapeProblem& p, const SparseOperator& op) {
    if (op.size() != p.op->size()) return false;
    for (int i = 0; i < op.size(); ++i)
        if ((*p.free)[i] && !(op.mass[i] > 0)) return false;
    return true;
}

// The mean curvature field of a pilot step from positions x on `given` (the operator at x), or,
// when null, on the operator assembled at x, released before the pilot's own (at most two
// operators beside fair()'s are alive). Empty when the step cannot be taken (not converged, the
// restoration failed, or an operator loses a free row's mass).
// `part` (0 or 1): which half of the shape's progress the pilot's solve reports.
std::vector<double> curvature_field(const OffsetShapeProblem& p, const SparseOperator* given,
                                    Positions x, int part) {
    const int n = p.data_vertices;
    {
        SparseOperator assembled;
        if (!given) {
            assembled = p.assemble_at(x);
            if (!keeps_masses(p, assembled)) return {};
        }
        const SparseOperator& op = given ? *given : assembled;
        LinearSystem system;
        system.op = &op;
        system.free = *p.free;
        system.lambda_dt = kPilotTimeStep * p.mean_edge * p.mean_edge;
        system.order = 1;
        system.diagonal.assign(op.size(), 1.0);
        for (int i = 0; i < op.size(); ++i)
            if (system.free[i])
                system.diagonal[i] = op.mass[i] / (i < n && p.weight ? (*p.weight)[i] : 1.0);
        SolveSettings settings;
        settings.tolerance = p.tolerance;
        settings.max_iterations = p.max_iterations;
        if (p.progress)
            settings.progress = [&p, part](double f) {
                p.progress(0.5 * (part + std::min(f, 1.0)));
            };
        if (!solve(system, x, settings).converged || !p.restore(x)) return {};
    }
    const SparseOperator at = p.assemble_at(x);
    if (!keeps_masses(p, at)) return {};
    Positions lx;
    at.apply_l(x, lx);
    const Positions normals = area_normals(*p.mesh, x);
    std::vector<double> field(n, 0.0), next(n, 0.0);
    for (int i = 0; i < n; ++i)
        if (p.component_of[i] >= 0) field[i] = -normals.row(i).dot(lx.row(i));
    // Half steps to the one-ring mean; the pattern joins vertices of one component only.
    for (int pass = 0; pass < kShapeSmoothingPasses; ++pass) {
        for (int i = 0; i < n; ++i) {
            next[i] = field[i];
            if (p.component_of[i] < 0) continue;
            double sum = 0;
            int count = 0;
            for (int k = at.row_start[i]; k < at.row_start[i + 1]; ++k)
                if (at.column[k] < n) {
                    sum += field[at.column[k]];
                    ++count;
                }
            if (count > 0) next[i] = 0.5 * field[i] + 0.5 * sum / count;
        }
        field.swap(next);
    }
    return field;
}

}  // namespace

OffsetShape curvature_offset_shape(const OffsetShapeProblem& p) {
    const int n = p.data_vertices;
    OffsetShape shape;
    shape.kept_share.assign(p.components, 0.0);
    if (p.components == 0 || !(p.noise_level > 0)) return shape;
    const std::vector<double> first = curvature_field(p, p.op, *p.x, 0);
    if (first.empty()) return shape;
    Positions redrawn = *p.x;
    const Positions normals = area_normals(*p.mesh, *p.x);
    for (int i = 0; i < n; ++i)
        if ((*p.free)[i]) redrawn.row(i) += p.noise_level * gaussian(i) * normals.row(i);
    const std::vector<double> second = curvature_field(p, nullptr, std::move(redrawn), 1);
    if (second.empty()) return shape;

    // Per component: the field's mean and variance, and the variance the noise accounts for.
    const std::size_t m = static_cast<std::size_t>(p.components);
    std::vector<double> count(m, 0.0), mean(m, 0.0), difference_mean(m, 0.0);
    for (int i = 0; i < n; ++i) {
        const int k = p.component_of[i];
        if (k < 0) continue;
        count[k] += 1;
        mean[k] += first[i];
        difference_mean[k] += second[i] - first[i];
    }
    for (std::size_t k = 0; k < m; ++k)
        if (count[k] > 0) {
            mean[k] /= count[k];
            difference_mean[k] /= count[k];
        }
    std::vector<double> variance(m, 0.0), noise_variance(m, 0.0);
    for (int i = 0; i < n; ++i) {
        const int k = p.component_of[i];
        if (k < 0) continue;
        variance[k] += (first[i] - mean[k]) * (first[i] - mean[k]);
        const double d = second[i] - first[i] - difference_mean[k];
        noise_variance[k] += d * d;
    }
    bool shaped = false;
    for (std::size_t k = 0; k < m; ++k) {
        const double kept = variance[k] > 0 ? 1 - noise_variance[k] / variance[k] : 0.0;
        shape.kept_share[k] = std::isfinite(kept) && kept >= kLeastShare ? kept : 0.0;
        shaped = shaped || shape.kept_share[k] > 0;
    }
    if (!shaped) return shape;

    shape.weight.assign(n, 1.0);
    std::vector<double> sum(m, 0.0);
    for (int i = 0; i < n; ++i) {
        const int k = p.component_of[i];
        if (k < 0 || shape.kept_share[k] == 0) continue;
        // A component oriented inwards has inward normals and a negative mean curvature.
        const double outwards = mean[k] < 0 ? -1.0 : 1.0;
        shape.weight[i] = std::max(
            0.0, outwards * (mean[k] + shape.kept_share[k] * (first[i] - mean[k])));
        sum[k] += shape.weight[i];
    }
    for (int i = 0; i < n; ++i) {
        const int k = p.component_of[i];
        if (k < 0 || shape.kept_share[k] == 0) continue;
        shape.weight[i] = sum[k] > 0 ? shape.weight[i] * count[k] / sum[k] : 1.0;
    }
    return shape;
}

}  // namespace detail
}  // namespace fairing
