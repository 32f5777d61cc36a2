// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "complex_factor.h"

#include "kernels.h"
#include "multigrid.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fairing {
namespace detail {
namespace {

// Complex numbers as (re, im) pairs: std::complex's operators check for infinities on every
// product, which the inner loops cannot afford.
struct Cx {
    double re = 0, im = 0;
};
Cx mul(Cx a, Cx b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
Cx div(Cx a, Cx b) {
    const double d = b.re * b.re + b.im * b.im;
    return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}

void check_finite(Cx v, int iteration) {
    if (!std::isfinite(v.re) || !std::isfinite(v.im))
        throw Error("the linear solve produced a non-finite value at iteration " +
                    std::to_string(iteration) +
                    "; the input is too degenerate for this operator (try the umbrella "
                    "operator, or repair the mesh first)");
}

bool any(const std::array<bool, 3>& active) { return active[0] || active[1] || active[2]; }

// (K v)_i of the vector held in the first three columns of a 6-column (complex) array; weight
// null: all 1 (weights_of, UnitWeights).
inline void k_row_stride6(int i, const double* vs, const int* start, const int* column,
                          const double* weight, double k[3]) {
    k[0] = k[1] = k[2] = 0;
    const auto accumulate = [&](const auto& w) {
        for (int e = start[i]; e < start[i + 1]; ++e) {
            const double* vj = vs + 6 * column[e];
            for (int c = 0; c < 3; ++c) k[c] += w[e] * (vj[c] - vs[6 * i + c]);
        }
    };
    if (weight) accumulate(weight);
    else accumulate(UnitWeights{});
}

}  // namespace

bool complex_factor_applies(const LinearSystem& system) {
    if (system.order != 2) return false;
    const SparseOperator& op = *system.op;
    for (int i = 0; i < op.size(); ++i)
        if (system.free[i] && !(system.diagonal[i] == op.mass[i] && op.mass[i] > 0)) return false;
    return true;
}

ComplexFactorSolver::ComplexFactorSolver(const LinearSystem& system, Multigrid* preconditioner)
    : system_(system), s_(std::sqrt(system.lambda_dt)), preconditioner_(preconditioner) {
    const SparseOperator& op = *system.op;
    const int n = op.size();
    r_.resize(n, 6);
    p_.resize(n, 6);
    q_.resize(n, 6);
    if (preconditioner_) {
        u_.resize(n, 6);
        return;
    }
    inverse_.assign(2 * static_cast<std::size_t>(n), 0.0);
    for_each_row(n, op.threads, [&](int i) {
        if (!system.free[i]) return;
        // The complex diagonal: measured against M alone, |diagonal| and the first-order
        // diagonal M - s K_ii on the 1 M-face torus (curvature, default step): 72 iterations
        // against 108, 79 and 75.
        const Cx d{system.diagonal[i], s_ * op.diagonal(i)};
        const Cx inv = div({1, 0}, d);
        inverse_[2 * i] = inv.re;
        inverse_[2 * i + 1] = inv.im;
    });
}

std::array<double, 6> ComplexFactorSolver::product(const Complex6& p, Complex6& q) const {
    const SparseOperator& op = *system_.op;
    const double* ps = p.data();
    double* qs = q.data();
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    const double* d = system_.diagonal.data();
    const char* f = system_.free.data();
    const double s = s_;
    // p is zero on the fixed rows, so sum_j w_ij (p_j - p_i) is (K_ff p)_i: K restricted to the
    // free rows and columns, with the full diagonal.
    return blocked_sum<6>(op.size(), op.threads, [=](int i, double* a) {
        double* qi = qs + 6 * i;
        if (!f[i]) {
            for (int c = 0; c < 6; ++c) qi[c] = 0;
            return;
        }
        const double* pi = ps + 6 * i;
        double k[6] = {0, 0, 0, 0, 0, 0};
        const auto accumulate = [&](const auto& w) {
            for (int e = start[i]; e < start[i + 1]; ++e) {
                const double* pj = ps + 6 * column[e];
                for (int c = 0; c < 6; ++c) k[c] += w[e] * (pj[c] - pi[c]);
            }
        };
        if (weight) accumulate(weight);
        else accumulate(UnitWeights{});
        for (int c = 0; c < 3; ++c) {
            qi[c] = d[i] * pi[c] - s * k[3 + c];
            qi[3 + c] = d[i] * pi[3 + c] + s * k[c];
            a[c] += pi[c] * qi[c] - pi[3 + c] * qi[3 + c];
            a[3 + c] += pi[c] * qi[3 + c] + pi[3 + c] * qi[c];
        }
    });
}

std::array<double, 3> ComplexFactorSolver::l2_residual_norms(ResidualNorm norm) {
    const SparseOperator& op = *system_.op;
    const int n = op.size();
    const char* f = system_.free.data();
    const double* d = system_.diagonal.data();
    const double* rs = r_.data();
    double* vs = q_.data();  // free: q is rewritten by the next product
    // v = M^-1 Im r_c, in q's first three columns (stride 6); zero on the fixed rows.
    for_each_row(n, op.threads, [=](int i) {
        for (int c = 0; c < 3; ++c) vs[6 * i + c] = f[i] ? rs[6 * i + 3 + c] / d[i] : 0.0;
    });
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    const double s = s_;
    const bool l2 = norm == ResidualNorm::L2;
    const std::array<double, 3> sums = blocked_reduce<3>(
        n, op.threads,
        [=](int i, double* a) {
            if (!f[i]) return;
            double k[3];
            k_row_stride6(i, vs, start, column, weight, k);
            for (int c = 0; c < 3; ++c) {
                const double res = rs[6 * i + c] + s * k[c];
                a[c] = l2 ? a[c] + res * res : std::max(a[c], std::abs(res));
            }
        },
        [l2](std::array<double, 3>& total, const std::array<double, 3>& part) {
            for (int c = 0; c < 3; ++c)
                total[c] = l2 ? total[c] + part[c] : std::max(total[c], part[c]);
        });
    if (!l2) return sums;
    return {std::sqrt(sums[0]), std::sqrt(sums[1]), std::sqrt(sums[2])};
}

std::array<double, 6> ComplexFactorSolver::precondition(bool first) {
    // q is free once r is updated (the next product rewrites it): the cycle's work space.
    const std::array<double, 6> ru = preconditioner_->apply(r_.data(), u_.data(), q_.data());
    if (first) p_ = u_;
    return ru;
}

std::array<double, 9> ComplexFactorSolver::update(const double* alpha, bool first,
                                                  ResidualNorm norm, Positions* x) {
    const int n = system_.op->size();
    const char* f = system_.free.data();
    // With a preconditioner, u and r^T u come from precondition() once r is complete.
    const double* inv = preconditioner_ ? nullptr : inverse_.data();
    double* xs = x ? x->data() : nullptr;
    double* rs = r_.data();
    double* ps = p_.data();
    const double* qs = q_.data();
    const bool l2 = norm == ResidualNorm::L2;
    std::array<double, 9> sums = blocked_reduce<9>(
        n, system_.op->threads,
        [=](int i, double* a) {
            if (!f[i]) return;
            double* ri = rs + 6 * i;
            double* pi = ps + 6 * i;
            const double* qi = qs + 6 * i;
            const Cx w = inv ? Cx{inv[2 * i], inv[2 * i + 1]} : Cx{};
            for (int c = 0; c < 3; ++c) {
                if (alpha) {
                    const Cx ac{alpha[2 * c], alpha[2 * c + 1]};
                    const Cx aq = mul(ac, {qi[c], qi[3 + c]});
                    xs[3 * i + c] += mul(ac, {pi[c], pi[3 + c]}).re;
                    ri[c] -= aq.re;
                    ri[3 + c] -= aq.im;
                }
                const Cx rc{ri[c], ri[3 + c]};
                const double m2 = rc.re * rc.re + rc.im * rc.im;
                a[c] = l2 ? a[c] + m2 : std::max(a[c], std::sqrt(m2));
                if (!inv) continue;
                const Cx u = mul(w, rc);
                const Cx ru = mul(rc, u);
                a[3 + c] += ru.re;
                a[6 + c] += ru.im;
                if (first) {
                    pi[c] = u.re;
                    pi[3 + c] = u.im;
                }
            }
        },
        [l2](std::array<double, 9>& total, const std::array<double, 9>& part) {
            for (int c = 0; c < 3; ++c)
                total[c] = l2 ? total[c] + part[c] : std::max(total[c], part[c]);
            for (int k = 3; k < 9; ++k) total[k] += part[k];
        });
    if (preconditioner_) {
        const std::array<double, 6> ru = precondition(first);
        for (int k = 0; k < 6; ++k) sums[3 + k] = ru[k];
    }
    return sums;
}

void ComplexFactorSolver::next_direction(const double* beta) {
    const char* f = system_.free.data();
    const double* inv = inverse_.data();
    const double* rs = r_.data();
    const double* us = preconditioner_ ? u_.data() : nullptr;
    double* ps = p_.data();
    for_each_row(system_.op->size(), system_.op->threads, [=](int i) {
        if (!f[i]) return;
        const Cx w = us ? Cx{} : Cx{inv[2 * i], inv[2 * i + 1]};
        double* pi = ps + 6 * i;
        const double* ri = rs + 6 * i;
        for (int c = 0; c < 3; ++c) {
            if (std::isnan(beta[2 * c])) continue;  // column done: p stays
            const Cx u = us ? Cx{us[6 * i + c], us[6 * i + 3 + c]} : mul(w, {ri[c], ri[3 + c]});
            const Cx bp = mul({beta[2 * c], beta[2 * c + 1]}, {pi[c], pi[3 + c]});
            pi[c] = u.re + bp.re;
            pi[3 + c] = u.im + bp.im;
        }
    });
}

std::array<double, 3> ComplexFactorSolver::set_residual(const Positions& b, const Positions& x,
                                                        ResidualNorm norm) {
    const SparseOperator& op = *system_.op;
    const int n = op.size();
    const char* f = system_.free.data();
    const double* d = system_.diagonal.data();
    const double* m = op.mass.data();
    const double* xs = x.data();
    const double* bs = b.data();
    double* vs = q_.data();  // v = P M^-1 K x in q's first three columns (stride 6)
    double* rs = r_.data();
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    for_each_row(n, op.threads, [=](int i) {
        double k[3];
        k_row(i, xs, start, column, weight, k[0], k[1], k[2]);
        const double inverse = f[i] && m[i] > 0 ? 1.0 / m[i] : 0.0;
        for (int c = 0; c < 3; ++c) vs[6 * i + c] = k[c] * inverse;
    });
    // r = b - (D x + lambda_dt K v) on the free rows, as LinearSystem::apply computes A x.
    const double lambda = system_.lambda_dt;
    const bool l2 = norm == ResidualNorm::L2;
    const std::array<double, 3> sums = blocked_reduce<3>(
        n, op.threads,
        [=](int i, double* a) {
            double* ri = rs + 6 * i;
            for (int c = 0; c < 6; ++c) ri[c] = 0;
            if (!f[i]) return;
            double k[3];
            k_row_stride6(i, vs, start, column, weight, k);
            for (int c = 0; c < 3; ++c) {
                ri[c] = bs[3 * i + c] - (d[i] * xs[3 * i + c] + lambda * k[c]);
                a[c] = l2 ? a[c] + ri[c] * ri[c] : std::max(a[c], std::abs(ri[c]));
            }
        },
        [l2](std::array<double, 3>& total, const std::array<double, 3>& part) {
            for (int c = 0; c < 3; ++c)
                total[c] = l2 ? total[c] + part[c] : std::max(total[c], part[c]);
        });
    if (!l2) return sums;
    return {std::sqrt(sums[0]), std::sqrt(sums[1]), std::sqrt(sums[2])};
}

int ComplexFactorSolver::correct(Positions& x, const std::array<double, 3>& goal,
                                 ResidualNorm norm, int cap, std::array<bool, 3> active,
                                 const std::function<void(const std::array<double, 3>&)>& after) {
    const char* f = system_.free.data();
    const auto norms = [norm](const std::array<double, 9>& sums) {
        return norm == ResidualNorm::L2
                   ? std::array<double, 3>{std::sqrt(sums[0]), std::sqrt(sums[1]), std::sqrt(sums[2])}
                   : std::array<double, 3>{sums[0], sums[1], sums[2]};
    };
    // r = g (set by set_residual), p = J^-1 r (zero on the fixed rows).
    for_each_row(system_.op->size(), system_.op->threads, [&](int i) {
        if (!f[i])
            for (int c = 0; c < 6; ++c) p_(i, c) = 0;
    });
    std::array<double, 9> sums = update(nullptr, true, norm, nullptr);
    std::array<double, 3> rn = norms(sums);
    Cx rho[3];
    for (int c = 0; c < 3; ++c) {
        rho[c] = {sums[3 + c], sums[6 + c]};
        active[c] = active[c] && rn[c] > goal[c];
    }
    // A column stops when the L^2 residual of x + Re z is below its goal. That residual is
    // Re r_c + s K M^-1 Im r_c (A = (M - i s K) M^-1 (M + i s K), g real), one product to
    // compute, so it is checked only once the complex residual reaches `check`, which then
    // moves down by the factor still missing.
    std::array<double, 3> check = goal;
    int done = 0;
    while (any(active) && done < cap) {
        ++done;
        const std::array<double, 6> pq = product(p_, q_);
        double alpha[6] = {0, 0, 0, 0, 0, 0};
        for (int c = 0; c < 3; ++c)
            if (active[c]) {
                const Cx a = div(rho[c], {pq[c], pq[3 + c]});
                check_finite(a, done);
                alpha[2 * c] = a.re;
                alpha[2 * c + 1] = a.im;
            }
        sums = update(alpha, false, norm, &x);
        rn = norms(sums);
        bool test = false;
        for (int c = 0; c < 3; ++c) {
            check_finite({rn[c], 0}, done);
            test = test || (active[c] && rn[c] <= check[c]);
        }
        if (test) {
            const std::array<double, 3> true_rn = l2_residual_norms(norm);
            for (int c = 0; c < 3; ++c) {
                if (!active[c]) continue;
                if (true_rn[c] <= goal[c]) active[c] = false;
                else if (rn[c] <= check[c]) check[c] = rn[c] * std::max(0.01, goal[c] / true_rn[c]);
            }
        }
        if (after) after(rn);
        if (!any(active)) break;
        double beta[6] = {NAN, NAN, NAN, NAN, NAN, NAN};
        for (int c = 0; c < 3; ++c) {
            if (!active[c]) continue;
            const Cx rho_new{sums[3 + c], sums[6 + c]};
            const Cx b = div(rho_new, rho[c]);
            check_finite(b, done);
            beta[2 * c] = b.re;
            beta[2 * c + 1] = b.im;
            rho[c] = rho_new;
        }
        next_direction(beta);
    }
    return done;
}

}  // namespace detail
}  // namespace fairing
