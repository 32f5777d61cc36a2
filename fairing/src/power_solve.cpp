// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "power_solve.h"

#include "complex_factor.h"
#include "kernels.h"

#include <cmath>
#include <complex>
#include <string>
#include <vector>

namespace fairing {
namespace detail {
namespace {

using Column3 = std::array<double, 3>;
using Complex = std::complex<double>;
using ComplexPositions = Eigen::Matrix<Complex, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Rounds of refinement at most: the parts are solved to the tolerance itself, and a round cuts the
// L^p residual by about tolerance (c g)^(p-1) (header), so two or three suffice.
constexpr int kMaxRounds = 6;

bool any(const std::array<bool, 3>& a) { return a[0] || a[1] || a[2]; }

Column3 norms(const Positions& v, const std::vector<char>& free, ResidualNorm norm) {
    Column3 out{0, 0, 0};
    for (int i = 0; i < v.rows(); ++i) {
        if (!free[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double a = std::abs(v(i, c));
            out[c] = norm == ResidualNorm::LInfinity ? std::max(out[c], a) : out[c] + a * a;
        }
    }
    if (norm == ResidualNorm::L2)
        for (double& o : out) o = std::sqrt(o);
    return out;
}

// (M + sigma C1) y = r on the free rows by Jacobi-preconditioned COCG, y = 0 on the fixed ones;
// adds weight * Re y to out. Returns the iterations.
int complex_part(const LinearSystem& system, Complex sigma, const Positions& r, double tolerance,
                 int max_iterations, double weight, Positions& out) {
    const SparseOperator& op = *system.op;
    const int n = op.size();
    const std::vector<char>& free = system.free;
    std::vector<Complex> inverse(n, Complex(0));
    for (int i = 0; i < n; ++i)
        if (free[i]) inverse[i] = 1.0 / (op.mass[i] - sigma * op.diagonal(i));
    ComplexPositions y = ComplexPositions::Zero(n, 3), res(n, 3), z(n, 3), p(n, 3), q(n, 3);
    Positions re(n, 3), im(n, 3), kre, kim;
    // q = (M - sigma K) p on the free rows (p is 0 on the fixed ones).
    const auto multiply = [&](const ComplexPositions& v, ComplexPositions& result) {
        re = v.real();
        im = v.imag();
        kre.resize(n, 3);
        kim.resize(n, 3);
        for_each_k_row(op, re, [&](int i, double s0, double s1, double s2) {
            kre(i, 0) = s0, kre(i, 1) = s1, kre(i, 2) = s2;
        });
        for_each_k_row(op, im, [&](int i, double s0, double s1, double s2) {
            kim(i, 0) = s0, kim(i, 1) = s1, kim(i, 2) = s2;
        });
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c)
                result(i, c) = free[i] ? op.mass[i] * v(i, c) -
                                             sigma * Complex(kre(i, c), kim(i, c))
                                       : Complex(0);
    };
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) res(i, c) = free[i] ? Complex(r(i, c)) : Complex(0);
    std::array<Complex, 3> rho{};
    Column3 goal{0, 0, 0};
    std::array<bool, 3> active{false, false, false};
    for (int c = 0; c < 3; ++c) {
        goal[c] = tolerance * res.col(c).norm();
        active[c] = goal[c] > 0;
    }
    for (int i = 0; i < n; ++i) z.row(i) = inverse[i] * res.row(i);
    p = z;
    for (int c = 0; c < 3; ++c) rho[c] = (res.col(c).array() * z.col(c).array()).sum();
    int it = 0;
    while (any(active) && it < max_iterations) {
        ++it;
        multiply(p, q);
        for (int c = 0; c < 3; ++c) {
            if (!active[c]) continue;
            const Complex alpha = rho[c] / (p.col(c).array() * q.col(c).array()).sum();
            y.col(c) += alpha * p.col(c);
            res.col(c) -= alpha * q.col(c);
            const double rn = res.col(c).norm();
            check_finite(rn, it);
            if (rn <= goal[c]) active[c] = false;
        }
        for (int i = 0; i < n; ++i) z.row(i) = inverse[i] * res.row(i);
        for (int c = 0; c < 3; ++c) {
            if (!active[c]) continue;
            const Complex next = (res.col(c).array() * z.col(c).array()).sum();
            p.col(c) = z.col(c) + (next / rho[c]) * p.col(c);
            rho[c] = next;
        }
    }
    out += weight * y.real();
    return it;
}

}  // namespace

bool power_solve_applies(const LinearSystem& system) {
    return system.order >= 3 && powers_first_order(system);
}

SolveStats solve_power(const LinearSystem& system, Positions& x, const Positions& b,
                       const std::array<double, 3>& goal, const SolveSettings& settings) {
    const double pi = 3.14159265358979323846;
    const SparseOperator& op = *system.op;
    const int n = op.size();
    const int power = system.order;
    const double c = std::pow(system.lambda_dt, 1.0 / power);
    const std::vector<char>& free = system.free;
    SolveStats stats;
    Positions r(n, 3), q, scratch, correction(n, 3);
    const int parts = (power + 1) / 2;
    for (int round = 0;; ++round) {
        system.apply(x, q, scratch);
        for (int i = 0; i < n; ++i)
            for (int col = 0; col < 3; ++col) r(i, col) = free[i] ? b(i, col) - q(i, col) : 0.0;
        const Column3 rn = norms(r, free, settings.norm);
        std::array<bool, 3> active{};
        double worst = 0;
        for (int col = 0; col < 3; ++col) {
            check_finite(rn[col], stats.iterations);
            active[col] = rn[col] > goal[col];
            worst = std::max(worst, goal[col] > 0 ? rn[col] / goal[col] : 0.0);
        }
        stats.residual = worst * settings.tolerance;  // relative to the right-hand side's scale
        if (!any(active) || round == kMaxRounds || stats.iterations >= settings.max_iterations) {
            stats.converged = !any(active);
            return stats;
        }
        correction.setZero();
        int done = 0;
        // Each part gets what the cap leaves; a part left without any is skipped, and the
        // residual the round leaves is reported.
        const auto budget = [&] { return settings.max_iterations - stats.iterations; };
        for (int m = 0; 2 * m + 1 < power && budget() > 0; ++m) {  // the pairs, theta_m < pi
            const Complex sigma = -c * std::polar(1.0, -pi * (2 * m + 1) / power);
            stats.iterations += complex_part(system, sigma, r, settings.tolerance, budget(),
                                             2.0 / power, correction);
            if (settings.progress && round == 0) settings.progress(double(++done) / parts);
        }
        if (power % 2 && budget() > 0) {  // the real root, sigma = c: first order, D = M
            LinearSystem first;
            first.op = system.op;
            first.free = free;
            first.diagonal = system.diagonal;
            first.lambda_dt = c;
            first.order = 1;
            Positions y = Positions::Zero(n, 3);
            for (int i = 0; i < n; ++i)
                if (free[i]) y.row(i) = r.row(i) / op.mass[i];  // D y_old = r
            SolveSettings part = settings;
            part.progress = nullptr;
            part.previous = nullptr;
            part.max_iterations = budget();
            const SolveStats s = solve(first, y, part);
            stats.iterations += s.iterations;
            for (int i = 0; i < n; ++i)
                if (free[i]) correction.row(i) += y.row(i) / power;
            if (settings.progress && round == 0) settings.progress(double(++done) / parts);
        }
        for (int i = 0; i < n; ++i)
            if (free[i]) x.row(i) += correction.row(i);
    }
}

}  // namespace detail
}  // namespace fairing
