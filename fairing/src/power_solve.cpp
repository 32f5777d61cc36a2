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

// Rounds of refinement at most: the parts are solved to the tolerance itself, and a round cuts the
// L^p residual by about tolerance (c g)^(p-1) (header), so two or three suffice.
constexpr int kMaxRounds = 6;

bool any(const std::array<bool, 3>& a) { return a[0] || a[1] || a[2]; }

// (M + sigma C1) y = r on the free rows by Jacobi-preconditioned COCG, y = 0 on the fixed ones;
// adds weight * Re y to out. Returns the iterations. The complex vectors hold six doubles per
// row (the three columns' real parts, then their imaginary parts), and an iteration makes three
// passes over them: the product fused with <p, q>, the updates fused with |r| and <r, z>, and
// the new direction (z = J^-1 r is never stored).
int complex_part(const LinearSystem& system, Complex sigma, const Positions& r, double tolerance,
                 int max_iterations, double weight, Positions& out) {
    const SparseOperator& op = *system.op;
    const int n = op.size();
    const int threads = op.threads;
    const char* free = system.free.data();
    const double* mass = op.mass.data();
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* w = weights_of(op);
    const double sr = sigma.real(), si = sigma.imag();
    std::vector<double> inverse(2 * static_cast<std::size_t>(n), 0.0);  // J^-1 per row, re and im
    std::vector<double> y(6 * static_cast<std::size_t>(n), 0.0), res(y), p(y), q(y);
    for (int i = 0; i < n; ++i) {
        if (!free[i]) continue;
        const Complex d = 1.0 / (mass[i] - sigma * op.diagonal(i));
        inverse[2 * i] = d.real();
        inverse[2 * i + 1] = d.imag();
        for (int c = 0; c < 3; ++c) res[6 * i + c] = r(i, c);
    }
    // z = J^-1 r per row and column: (zr, zi).
    const auto z_of = [&](int i, int c, double& zr, double& zi) {
        const double a = inverse[2 * i], b = inverse[2 * i + 1];
        const double rr = res[6 * i + c], ri = res[6 * i + 3 + c];
        zr = a * rr - b * ri;
        zi = a * ri + b * rr;
    };
    std::array<double, 9> sums = blocked_sum<9>(n, threads, [&](int i, double* a) {
        for (int c = 0; c < 3; ++c) {
            double zr, zi;
            z_of(i, c, zr, zi);
            p[6 * i + c] = zr;
            p[6 * i + 3 + c] = zi;
            const double rr = res[6 * i + c], ri = res[6 * i + 3 + c];
            a[c] += rr * rr + ri * ri;
            a[3 + 2 * c] += rr * zr - ri * zi;  // r . z, unconjugated
            a[4 + 2 * c] += rr * zi + ri * zr;
        }
    });
    std::array<Complex, 3> rho;
    Column3 goal{0, 0, 0};
    std::array<bool, 3> active{false, false, false};
    for (int c = 0; c < 3; ++c) {
        goal[c] = tolerance * std::sqrt(sums[c]);
        active[c] = goal[c] > 0;
        rho[c] = Complex(sums[3 + 2 * c], sums[4 + 2 * c]);
    }
    int it = 0;
    while (any(active) && it < max_iterations) {
        ++it;
        // q = (M - sigma K) p on the free rows, and <p, q> per column.
        std::array<double, 6> pq{};
        with_weights(w, [&](const auto& weights) {
            pq = blocked_sum<6>(n, threads, [&](int i, double* a) {
                if (!free[i]) return;
                const double* pi = &p[6 * static_cast<std::size_t>(i)];
                double k[6] = {0, 0, 0, 0, 0, 0};
                for (int e = start[i]; e < start[i + 1]; ++e) {
                    const double* pj = &p[6 * static_cast<std::size_t>(column[e])];
                    const double we = weights[e];
                    for (int c = 0; c < 6; ++c) k[c] += we * (pj[c] - pi[c]);
                }
                double* qi = &q[6 * static_cast<std::size_t>(i)];
                for (int c = 0; c < 3; ++c) {
                    qi[c] = mass[i] * pi[c] - (sr * k[c] - si * k[3 + c]);
                    qi[3 + c] = mass[i] * pi[3 + c] - (sr * k[3 + c] + si * k[c]);
                    a[2 * c] += pi[c] * qi[c] - pi[3 + c] * qi[3 + c];
                    a[2 * c + 1] += pi[c] * qi[3 + c] + pi[3 + c] * qi[c];
                }
            });
        });
        std::array<Complex, 3> alpha{};
        for (int c = 0; c < 3; ++c)
            if (active[c]) alpha[c] = rho[c] / Complex(pq[2 * c], pq[2 * c + 1]);
        sums = blocked_sum<9>(n, threads, [&](int i, double* a) {
            if (!free[i]) return;
            for (int c = 0; c < 3; ++c) {
                if (!active[c]) continue;
                const double ar = alpha[c].real(), ai = alpha[c].imag();
                double* yi = &y[6 * static_cast<std::size_t>(i)];
                double* ri = &res[6 * static_cast<std::size_t>(i)];
                const double* pi = &p[6 * static_cast<std::size_t>(i)];
                const double* qi = &q[6 * static_cast<std::size_t>(i)];
                yi[c] += ar * pi[c] - ai * pi[3 + c];
                yi[3 + c] += ar * pi[3 + c] + ai * pi[c];
                ri[c] -= ar * qi[c] - ai * qi[3 + c];
                ri[3 + c] -= ar * qi[3 + c] + ai * qi[c];
                double zr, zi;
                z_of(i, c, zr, zi);
                a[c] += ri[c] * ri[c] + ri[3 + c] * ri[3 + c];
                a[3 + 2 * c] += ri[c] * zr - ri[3 + c] * zi;
                a[4 + 2 * c] += ri[c] * zi + ri[3 + c] * zr;
            }
        });
        std::array<Complex, 3> beta{};
        for (int c = 0; c < 3; ++c) {
            if (!active[c]) continue;
            check_finite(sums[c], it);
            const Complex next(sums[3 + 2 * c], sums[4 + 2 * c]);
            beta[c] = next / rho[c];
            rho[c] = next;
            if (std::sqrt(sums[c]) <= goal[c]) active[c] = false;
        }
        for_each_row(n, threads, [&](int i) {
            if (!free[i]) return;
            double* pi = &p[6 * static_cast<std::size_t>(i)];
            for (int c = 0; c < 3; ++c) {
                if (!active[c]) continue;
                double zr, zi;
                z_of(i, c, zr, zi);
                const double br = beta[c].real(), bi = beta[c].imag();
                const double pr = pi[c], pim = pi[3 + c];
                pi[c] = zr + br * pr - bi * pim;
                pi[3 + c] = zi + br * pim + bi * pr;
            }
        });
    }
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out(i, c) += weight * y[6 * static_cast<std::size_t>(i) + c];
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
    double best = 0;  // the lowest worst residual ratio of a round so far
    for (int round = 0;; ++round) {
        system.apply(x, q, scratch);
        for (int i = 0; i < n; ++i)
            for (int col = 0; col < 3; ++col) r(i, col) = free[i] ? b(i, col) - q(i, col) : 0.0;
        const Column3 rn = column_norms(r, system.free, settings.norm, op.threads);
        std::array<bool, 3> active{};
        double worst = 0;
        for (int col = 0; col < 3; ++col) {
            check_finite(rn[col], stats.iterations);
            active[col] = rn[col] > goal[col];
            worst = std::max(worst, goal[col] > 0 ? rn[col] / goal[col] : 0.0);
        }
        // A round that raised the residual diverges: its parts' errors, amplified by (c g)^(p-1),
        // outweigh what they removed, and later rounds would compound it (to 1e67 on a mesh whose
        // recomputed curvature steps had shrunk vertex areas to 1e-9 of the mean). Its
        // correction is taken back and the solve stops unconverged.
        if (round > 0 && worst > best) {
            for (int i = 0; i < n; ++i)
                if (free[i]) x.row(i) -= correction.row(i);
            stats.residual = best * settings.tolerance;
            return stats;
        }
        best = worst;
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
