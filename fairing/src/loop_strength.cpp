// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "loop_strength.h"

#include "direct_solve.h"
#include "geometry.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace fairing {
namespace detail {
namespace {

// The time steps: from 10^kLowest to 10^kHighest, kPerDecade per decade near the minimum. The
// best loop steps measured on libcgal-demo's open meshes lay between 0.003 and 30 (auto-gap.md,
// section 30); the range reaches three decades past either side.
constexpr int kLowest = -5, kHighest = 5, kPerDecade = 4;
constexpr double kProbe = 1e-2;  // the Monte-Carlo probe's size, in noise levels
// A time step whose factored loop solve (the data's or a probe's) leaves more than this relative
// residual is not evaluated: the probe's divergence divides the solves' rounding by kProbe times
// the noise. On libcgal-demo's open turbine blade at half an edge (umbrella, L^4) the residual
// grew from 7e-7 at time step 10 to 5e-5 at 1000 and 1e-2 at 1e5, where the risk read -22
// against 22 to 30 elsewhere, and the loops took 1e5 (1.48x the error of the Lanczos model's
// choice). At order 2 only the dragon's three-vertex sliver holes pass it, on two of its noisy
// copies: their loop step went from 1e5 to 102 and from 4.7e4 to 8069, and the one-click errors
// moved by at most 1e-5 of themselves (auto-gap.md, section 41).
constexpr double kRiskResidual = 1e-5;

// One direction of the loops' error: a unit direction per free loop vertex, the noise level along
// it, and its Monte-Carlo probe: the data moved by eps along +-direction and the loop system
// assembled there.
struct Channel {
    Eigen::MatrixXd direction;
    double noise = 0;
    double eps = 0;
    Eigen::VectorXd sign;
    DirectSystem probed;
    Eigen::MatrixXd probed_y;
    Eigen::SimplicialLDLT<SparseMatrix> ldlt;
    Eigen::MatrixXd moved, rhs;
};

void probe(const LoopStrengthProblem& p, const std::vector<int>& rows,
           const std::vector<int>& index, std::uint64_t salt, Channel& c) {
    const int n = static_cast<int>(rows.size());
    c.sign.resize(n);
    for (int a = 0; a < n; ++a)
        c.sign(a) = splitmix64(static_cast<std::uint64_t>(rows[a]) ^ salt) & 1 ? 1.0 : -1.0;
    if (!(c.noise > 0)) return;
    c.eps = kProbe * c.noise;
    Positions x = *p.x;
    c.probed_y.resize(n, 3);
    for (int a = 0; a < n; ++a) {
        x.row(rows[a]) += c.eps * c.sign(a) * c.direction.row(a);
        c.probed_y.row(a) = x.row(rows[a]);
    }
    const SparseOperator op = p.assemble_at ? p.assemble_at(x) : *p.op;
    c.probed = direct_system(op, x, rows, index, p.weight, p.order);
}

// The median of v (v is reordered).
double median(std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

double loop_time_step(const LoopStrengthProblem& p) {
    const SparseOperator& op = *p.op;
    const Positions& x = *p.x;
    const Positions& normals = *p.normals;
    std::vector<int> rows, index(op.size(), -1);
    for (int i = 0; i < op.size(); ++i)
        if ((*p.free)[i] && op.mass[i] > 0 && (!p.weight || (*p.weight)[i] > 0)) {
            index[i] = static_cast<int>(rows.size());
            rows.push_back(i);
        }
    const int n = static_cast<int>(rows.size());
    if (n == 0 || !(p.noise_level > 0)) return 0;

    // Per free loop vertex with its two loop neighbours: b, and its offset along b from the chord
    // of the neighbours (interpolated by arc length, divided by the offset's noise gain).
    Channel along, across;  // n and b
    along.direction.resize(n, 3);
    across.direction = Eigen::MatrixXd::Zero(n, 3);
    std::vector<double> offset(n, std::numeric_limits<double>::quiet_NaN());
    Eigen::MatrixXd y(n, 3);
    for (int a = 0; a < n; ++a) {
        const int i = rows[a];
        y.row(a) = x.row(i);
        along.direction.row(a) = normals.row(i);
        if (op.row_start[i + 1] - op.row_start[i] != 2) continue;
        const Eigen::RowVector3d prev = x.row(op.column[op.row_start[i]]);
        const Eigen::RowVector3d next = x.row(op.column[op.row_start[i] + 1]);
        const Eigen::Vector3d b = (next - prev).transpose().cross(normals.row(i).transpose());
        const double ep = (x.row(i) - prev).norm(), en = (x.row(i) - next).norm();
        if (!(b.norm() > 0) || !(ep + en > 0)) continue;
        across.direction.row(a) = b.normalized().transpose();
        const Eigen::RowVector3d chord = (en * prev + ep * next) / (ep + en);
        const double gain = std::sqrt(1 + (ep * ep + en * en) / ((ep + en) * (ep + en)));
        offset[a] = across.direction.row(a).dot(x.row(i) - chord) / gain;
    }
    along.noise = p.noise_level;
    // The noise across a loop, in the surface: the robust spread of the offsets about their
    // loop's median (a round hole's curvature). Zero when the noise lies along the normals, up
    // to their tilt; sigma with noise in all directions.
    std::vector<double> spread;
    for (const std::vector<int>& loop : p.mesh->boundary_loops()) {
        std::vector<double> in_loop;
        for (int v : loop) {
            const int a = v < op.size() ? index[v] : -1;
            if (a >= 0 && !std::isnan(offset[a])) in_loop.push_back(offset[a]);
        }
        if (in_loop.empty()) continue;
        std::vector<double> copy = in_loop;
        const double centre = median(copy);
        for (double o : in_loop) spread.push_back(std::abs(o - centre));
    }
    across.noise = spread.size() >= 8 ? 1.4826 * median(spread) : 0.0;

    DirectSystem base = direct_system(op, x, rows, index, p.weight, p.order);
    probe(p, rows, index, 0x9e3779b97f4a7c15ull, along);
    probe(p, rows, index, 0x7f4a7c159e3779b9ull, across);
    Eigen::SimplicialLDLT<SparseMatrix> ldlt;
    {
        SparseMatrix pattern = base.c;
        for (Eigen::Index i = 0; i < n; ++i) pattern.coeffRef(i, i) += 1;
        ldlt.analyzePattern(pattern);
        along.ldlt.analyzePattern(pattern);
        across.ldlt.analyzePattern(pattern);
    }
    // The risk at t = 10^(k / kPerDecade), or nothing where a system did not factor.
    Eigen::MatrixXd moved, rhs;
    const auto risk_at = [&](int k) -> std::pair<bool, double> {
        const double t = std::pow(10.0, static_cast<double>(k) / kPerDecade);
        const double lambda = t * p.length_unit;
        if (!take_direct_steps(base, lambda, p.steps, y, ldlt, moved, rhs) ||
            !(relative_residual(rhs - base.a * moved, rhs) <= kRiskResidual))
            return {false, 0.0};
        const Eigen::MatrixXd r = moved - y;
        double total = 0;
        for (Channel* c : {&along, &across}) {
            // Stein's unbiased risk of the channel (auto_strength.h), the divergence by the probe.
            double rss = 0;
            for (int a = 0; a < n; ++a) {
                const double rd = c->direction.row(a).dot(r.row(a));
                rss += rd * rd;
            }
            total += rss;
            if (!(c->noise > 0)) continue;
            if (!take_direct_steps(c->probed, lambda, p.steps, c->probed_y, c->ldlt, c->moved,
                                   c->rhs) ||
                !(relative_residual(c->rhs - c->probed.a * c->moved, c->rhs) <= kRiskResidual))
                return {false, 0.0};
            double divergence = n;
            for (int a = 0; a < n; ++a)
                divergence += c->sign(a) *
                              c->direction.row(a).dot(c->moved.row(a) - c->probed_y.row(a) -
                                                      r.row(a)) /
                              c->eps;
            total += c->noise * c->noise * (2 * divergence - n);
        }
        return {true, total};
    };
    // Coarse to fine: every decade, then every quarter decade within one of the coarse minimum
    // (17 time steps instead of 41: on a sheet with 10,000 one-cell holes, 41 k loop vertices,
    // the loops' estimate took 1.6 s with 41 and 0.5 s with 17; auto-gap.md, section 30).
    std::map<int, double> risk;
    const auto evaluate = [&](int k) {
        if (risk.count(k)) return;
        const std::pair<bool, double> r = risk_at(k);
        if (r.first) risk[k] = r.second;
    };
    using Entry = std::pair<const int, double>;
    const auto lowest = [&risk]() {
        const auto below = [](const Entry& a, const Entry& b) { return a.second < b.second; };
        return std::min_element(risk.begin(), risk.end(), below)->first;
    };
    for (int k = kLowest * kPerDecade; k <= kHighest * kPerDecade; k += kPerDecade) evaluate(k);
    if (risk.empty())
        throw Error("the boundary loops' systems did not factor at any time step");
    const int coarse = lowest();
    for (int k = coarse - kPerDecade + 1; k < coarse + kPerDecade; ++k)
        if (k >= kLowest * kPerDecade && k <= kHighest * kPerDecade) evaluate(k);
    const int best = lowest();
    double shift = 0;  // a parabola through the minimum and its neighbours, in quarter decades
    if (risk.count(best - 1) && risk.count(best + 1)) {
        const double r0 = risk[best - 1], r1 = risk[best], r2 = risk[best + 1];
        const double curvature = r0 - 2 * r1 + r2;
        if (curvature > 0) shift = 0.5 * (r0 - r2) / curvature;  // |shift| <= 1/2
    }
    return std::pow(10.0, (best + shift) / kPerDecade);
}

}  // namespace detail
}  // namespace fairing
