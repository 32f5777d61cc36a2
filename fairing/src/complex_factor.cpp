// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "complex_factor.h"

#include "kernels.h"
#include "sweeps.h"
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
    with_weights(weight, [&](const auto& w) {
        for (int e = start[i]; e < start[i + 1]; ++e) {
            const double* vj = vs + 6 * column[e];
            for (int c = 0; c < 3; ++c) k[c] += w[e] * (vj[c] - vs[6 * i + c]);
        }
    });
}

// Norm of r^ (|r^_i|^2 = |D_i| |r~_i|^2) and r^T r^ = sum D_i r~_i^2 for one row into a[0..8].
inline void transformed_sums(Cx d, const double* ri, bool l2, double* a) {
    const double abs_d = std::sqrt(d.re * d.re + d.im * d.im);
    for (int c = 0; c < 3; ++c) {
        const Cx rc{ri[c], ri[3 + c]};
        const double m2 = abs_d * (rc.re * rc.re + rc.im * rc.im);
        a[c] = l2 ? a[c] + m2 : std::max(a[c], std::sqrt(m2));
        const Cx rr = mul(d, mul(rc, rc));
        a[3 + c] += rr.re;
        a[6 + c] += rr.im;
    }
}

std::array<double, 9> combine_norms_and_products(bool l2, std::array<double, 9>& total,
                                                 const std::array<double, 9>& part) {
    for (int c = 0; c < 3; ++c) total[c] = l2 ? total[c] + part[c] : std::max(total[c], part[c]);
    for (int k = 3; k < 9; ++k) total[k] += part[k];
    return total;
}

}  // namespace

bool complex_factor_applies(const LinearSystem& system) {
    return system.order == 2 && powers_first_order(system);
}

bool powers_first_order(const LinearSystem& system) {
    if (system.order < 2) return false;
    const SparseOperator& op = *system.op;
    for (int i = 0; i < op.size(); ++i)
        if (system.free[i] && !(system.diagonal[i] == op.mass[i] && op.mass[i] > 0)) return false;
    return true;
}

ComplexFactorSolver::ComplexFactorSolver(const LinearSystem& system, Multigrid* preconditioner,
                                         bool gauss_seidel)
    : system_(system),
      s_(std::sqrt(system.lambda_dt)),
      gauss_seidel_(!preconditioner && gauss_seidel && gauss_seidel_applies(*system.op)),
      block_(sweep_block_rows(system.op->size())),
      preconditioner_(preconditioner) {
    const SparseOperator& op = *system.op;
    const int n = op.size();
    r_.resize(n, 6);
    p_.resize(n, 6);
    q_.resize(n, 6);
    if (preconditioner_ || gauss_seidel_) {
        u_.resize(n, 6);
        if (gauss_seidel_) {
            imaginary_ = imaginary_diagonal();
        }
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
        with_weights(weight, [&](const auto& w) {
            for (int e = start[i]; e < start[i + 1]; ++e) {
                const double* pj = ps + 6 * column[e];
                for (int c = 0; c < 6; ++c) k[c] += w[e] * (pj[c] - pi[c]);
            }
        });
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
    const double* rs = r_.data();  // Re r_c in columns 0..2
    double* vs = q_.data();  // free: q is rewritten by the next product
    // v = M^-1 Im r_c, in q's first three columns (stride 6); zero on the fixed rows. Gauss-
    // Seidel: r_c itself is not kept; v and Re r_c (in q's last three columns) come from r~.
    if (gauss_seidel_) {
        sweep_residual();
        rs = vs + 3;
    } else {
        for_each_row(n, op.threads, [=](int i) {
            for (int c = 0; c < 3; ++c) vs[6 * i + c] = f[i] ? rs[6 * i + 3 + c] / d[i] : 0.0;
        });
    }
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

std::vector<double> ComplexFactorSolver::imaginary_diagonal() const {
    const SparseOperator& op = *system_.op;
    std::vector<double> imaginary(static_cast<std::size_t>(op.size()), 0.0);
    for_each_row(op.size(), op.threads, [&](int i) {
        if (system_.free[i]) imaginary[i] = s_ * op.diagonal(i);
    });
    return imaginary;
}

ComplexFactorSolver::SweepView ComplexFactorSolver::sweep_view() const {
    const SparseOperator& op = *system_.op;
    return {system_.free.data(), system_.diagonal.data(), imaginary_.data(), op.row_start.data(),
            op.column.data(), weights_of(op), s_};
}

std::array<double, 9> ComplexFactorSolver::sweep_start(ResidualNorm norm) {
    const SparseOperator& op = *system_.op;
    const SweepView v = sweep_view();
    double* rs = r_.data();
    double* ps = p_.data();
    const bool l2 = norm == ResidualNorm::L2;
    // r~_i = (g_i - i s sum_{j<i in the block} w_ij r~_j) / D_i, in place: the rows before i
    // already hold r~.
    return forward_sweep<9>(
        op.size(), block_, op.threads,
        [=](int i, int begin, int end, double* a) {
            double* ri = rs + 6 * i;
            double* pi = ps + 6 * i;
            if (!v.free[i]) {
                for (int c = 0; c < 6; ++c) ri[c] = pi[c] = 0;
                return;
            }
            double lower[6] = {0, 0, 0, 0, 0, 0};
            const RowRuns runs = row_runs(v.start, v.column, i, begin, end);
            with_weights(v.weight, [&](const auto& w) {
                add_run<6>(rs, v.column, w, runs.in_block, runs.diagonal, lower);
            });
            const Cx d{v.mass[i], v.imaginary[i]};
            const Cx inv = div({1, 0}, d);
            for (int c = 0; c < 3; ++c) {
                const Cx t = mul(inv, {ri[c] + v.s * lower[3 + c], ri[3 + c] - v.s * lower[c]});
                ri[c] = pi[c] = t.re;
                ri[3 + c] = pi[3 + c] = t.im;
            }
            transformed_sums(d, ri, l2, a);
        },
        [l2](std::array<double, 9>& total, const std::array<double, 9>& part) {
            combine_norms_and_products(l2, total, part);
        });
}

std::array<double, 6> ComplexFactorSolver::sweep_product(const double* beta) {
    const SparseOperator& op = *system_.op;
    const int n = op.size();
    const SweepView v = sweep_view();
    const double* rs = r_.data();
    double* ps = p_.data();
    double* us = u_.data();
    double* ys = q_.data();
    // Backward: p~_i = r~_i + beta p~_i, then u_i = p~_i - i s (sum_{j>i in the block} w_ij u_j)
    // / D_i, i.e. (D + L^T) u = D p~.
    backward_sweep(n, block_, op.threads, [=](int i, int begin, int end) {
        double* ui = us + 6 * i;
        if (!v.free[i]) {
            for (int c = 0; c < 6; ++c) ui[c] = 0;
            return;
        }
        double* pi = ps + 6 * i;
        if (beta) {
            const double* ri = rs + 6 * i;
            for (int c = 0; c < 3; ++c) {
                if (std::isnan(beta[2 * c])) continue;  // column done: p stays
                const Cx bp = mul({beta[2 * c], beta[2 * c + 1]}, {pi[c], pi[3 + c]});
                pi[c] = ri[c] + bp.re;
                pi[3 + c] = ri[3 + c] + bp.im;
            }
        }
        double upper[6] = {0, 0, 0, 0, 0, 0};
        const RowRuns runs = row_runs(v.start, v.column, i, begin, end);
        with_weights(v.weight, [&](const auto& w) {
            add_run_down<6>(us, v.column, w, runs.diagonal, runs.after, upper);
        });
        const Cx inv = div({1, 0}, {v.mass[i], v.imaginary[i]});
        for (int c = 0; c < 3; ++c) {
            // i s U / D_i with U = upper (re, im): i s U = (-s U.im, s U.re).
            const Cx t = mul(inv, {-v.s * upper[3 + c], v.s * upper[c]});
            ui[c] = pi[c] - t.re;
            ui[3 + c] = pi[3 + c] - t.im;
        }
    });
    // Forward: (D + L) y = D p~ - D u + R u, R the couplings between blocks, so
    // u + y = p~ + i s (sum_{j outside} w_ij u_j - sum_{j<i in the block} w_ij y_j) / D_i;
    // p^T A^ p^ = sum D_i p~_i (u_i + y_i).
    return forward_sweep<6>(
        n, block_, op.threads,
        [=](int i, int begin, int end, double* a) {
            double* yi = ys + 6 * i;
            if (!v.free[i]) {
                for (int c = 0; c < 6; ++c) yi[c] = 0;
                return;
            }
            // outside - lower in one pass: u_j with +w_ij outside the block, y_j with -w_ij
            // before i inside it.
            double outside[6] = {0, 0, 0, 0, 0, 0}, lower[6] = {0, 0, 0, 0, 0, 0};
            const RowRuns runs = row_runs(v.start, v.column, i, begin, end);
            with_weights(v.weight, [&](const auto& w) {
                add_run<6>(us, v.column, w, runs.first, runs.in_block, outside);
                add_run<6>(us, v.column, w, runs.after, runs.last, outside);
                add_run<6>(ys, v.column, w, runs.in_block, runs.diagonal, lower);
            });
            double coupled[6];
            for (int c = 0; c < 6; ++c) coupled[c] = outside[c] - lower[c];
            const Cx d{v.mass[i], v.imaginary[i]};
            const Cx inv = div({1, 0}, d);
            const double* pi = ps + 6 * i;
            const double* ui = us + 6 * i;
            for (int c = 0; c < 3; ++c) {
                const double re = coupled[c], imag = coupled[3 + c];
                const Cx t = mul(inv, {-v.s * imag, v.s * re});
                const Cx q{pi[c] + t.re, pi[3 + c] + t.im};  // u + y
                yi[c] = q.re - ui[c];
                yi[3 + c] = q.im - ui[3 + c];
                const Cx dpq = mul(d, mul({pi[c], pi[3 + c]}, q));
                a[c] += dpq.re;
                a[3 + c] += dpq.im;
            }
        },
        [](std::array<double, 6>& total, const std::array<double, 6>& part) {
            for (int k = 0; k < 6; ++k) total[k] += part[k];
        });
}

std::array<double, 9> ComplexFactorSolver::sweep_update(const double* alpha, ResidualNorm norm,
                                                        Positions& x) {
    const int n = system_.op->size();
    const char* f = system_.free.data();
    const double* m = system_.diagonal.data();
    const double* im = imaginary_.data();
    double* xs = x.data();
    double* rs = r_.data();
    const double* us = u_.data();
    const double* ys = q_.data();
    const bool l2 = norm == ResidualNorm::L2;
    return blocked_reduce<9>(
        n, system_.op->threads,
        [=](int i, double* a) {
            if (!f[i]) return;
            double* ri = rs + 6 * i;
            const double* ui = us + 6 * i;
            const double* yi = ys + 6 * i;
            for (int c = 0; c < 3; ++c) {
                const Cx ac{alpha[2 * c], alpha[2 * c + 1]};
                xs[3 * i + c] += mul(ac, {ui[c], ui[3 + c]}).re;
                const Cx aq = mul(ac, {ui[c] + yi[c], ui[3 + c] + yi[3 + c]});
                ri[c] -= aq.re;
                ri[3 + c] -= aq.im;
            }
            transformed_sums({m[i], im[i]}, ri, l2, a);
        },
        [l2](std::array<double, 9>& total, const std::array<double, 9>& part) {
            combine_norms_and_products(l2, total, part);
        });
}

void ComplexFactorSolver::sweep_residual() {
    const SparseOperator& op = *system_.op;
    const SweepView v = sweep_view();
    const double* rs = r_.data();
    double* vs = q_.data();
    // r_c = D r~ + i s sum_{j<i in the block} w_ij r~_j.
    forward_sweep<1>(
        op.size(), block_, op.threads,
        [=](int i, int begin, int end, double*) {
            double* vi = vs + 6 * i;
            if (!v.free[i]) {
                for (int c = 0; c < 6; ++c) vi[c] = 0;
                return;
            }
            double lower[6] = {0, 0, 0, 0, 0, 0};
            const RowRuns runs = row_runs(v.start, v.column, i, begin, end);
            with_weights(v.weight, [&](const auto& w) {
                add_run<6>(rs, v.column, w, runs.in_block, runs.diagonal, lower);
            });
            const double* ri = rs + 6 * i;
            for (int c = 0; c < 3; ++c) {
                const Cx rc = mul({v.mass[i], v.imaginary[i]}, {ri[c], ri[3 + c]});
                vi[3 + c] = rc.re - v.s * lower[3 + c];
                vi[c] = (rc.im + v.s * lower[c]) / v.mass[i];
            }
        },
        [](std::array<double, 1>&, const std::array<double, 1>&) {});
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
    start_norms_ = l2 ? std::array<double, 3>{std::sqrt(sums[0]), std::sqrt(sums[1]),
                                              std::sqrt(sums[2])}
                      : sums;
    return start_norms_;
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
    // Gauss-Seidel tracks the transformed residual r^ = E^-1 r_c; its norms are reported and
    // compared scaled by what the two were at the start (g's norms over r^'s), an estimate
    // that the check on the L^2 residual below corrects.
    std::array<double, 3> scale{1, 1, 1};
    std::array<double, 9> sums;
    if (gauss_seidel_) {
        sums = sweep_start(norm);
    } else {
        // r = g (set by set_residual), p = J^-1 r (zero on the fixed rows).
        for_each_row(system_.op->size(), system_.op->threads, [&](int i) {
            if (!f[i])
                for (int c = 0; c < 6; ++c) p_(i, c) = 0;
        });
        sums = update(nullptr, true, norm, nullptr);
    }
    std::array<double, 3> rn = norms(sums);
    if (gauss_seidel_)
        for (int c = 0; c < 3; ++c) {
            if (rn[c] > 0) scale[c] = start_norms_[c] / rn[c];
            rn[c] *= scale[c];
        }
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
    double beta[6] = {NAN, NAN, NAN, NAN, NAN, NAN};
    int done = 0;
    while (any(active) && done < cap) {
        // Gauss-Seidel folds the new direction (p~ = r~ + beta p~) into the product's first sweep.
        const std::array<double, 6> pq =
            gauss_seidel_ ? sweep_product(done > 0 ? beta : nullptr) : product(p_, q_);
        ++done;
        double alpha[6] = {0, 0, 0, 0, 0, 0};
        for (int c = 0; c < 3; ++c)
            if (active[c]) {
                const Cx a = div(rho[c], {pq[c], pq[3 + c]});
                check_finite(a, done);
                alpha[2 * c] = a.re;
                alpha[2 * c + 1] = a.im;
            }
        sums = gauss_seidel_ ? sweep_update(alpha, norm, x) : update(alpha, false, norm, &x);
        rn = norms(sums);
        for (int c = 0; c < 3; ++c) rn[c] *= scale[c];
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
        for (int c = 0; c < 3; ++c) {
            beta[2 * c] = beta[2 * c + 1] = NAN;
            if (!active[c]) continue;
            const Cx rho_new{sums[3 + c], sums[6 + c]};
            const Cx b = div(rho_new, rho[c]);
            check_finite(b, done);
            beta[2 * c] = b.re;
            beta[2 * c + 1] = b.im;
            rho[c] = rho_new;
        }
        if (!gauss_seidel_) next_direction(beta);
    }
    return done;
}

}  // namespace detail
}  // namespace fairing
