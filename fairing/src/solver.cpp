// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "fairing/solver.h"

#include "complex_factor.h"
#include "kernels.h"
#include "multigrid.h"
#include "power_solve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

namespace fairing {
namespace {

using Column3 = std::array<double, 3>;

using detail::column_norms;

// Per column sum over the free rows of a_i b_i.
Column3 column_dots(const Positions& a, const Positions& b, const std::vector<char>& free,
                    int threads) {
    const double* pa = a.data();
    const double* pb = b.data();
    const char* f = free.data();
    return detail::blocked_sum<3>(static_cast<int>(a.rows()), threads, [=](int i, double* s) {
        if (!f[i]) return;
        for (int c = 0; c < 3; ++c) s[c] += pa[3 * i + c] * pb[3 * i + c];
    });
}

}  // namespace

void LinearSystem::apply(const Positions& x, Positions& y, Positions& scratch) const {
    apply_dot(x, y, scratch);
}

Column3 LinearSystem::apply_dot(const Positions& x, Positions& y, Positions& scratch) const {
    const int n = op->size();
    y.resize(n, 3);
    const double* xs = x.data();
    const double* d = diagonal.empty() ? nullptr : diagonal.data();  // empty: D = 0
    const char* f = free.data();
    double* ys = y.data();
    const double lambda = lambda_dt;
    // Row i of A x: d_i x_i + sign lambda (K v)_i, v = (P M^-1 K)^(order-1) x, sign = (-1)^order
    // (order 1: -lambda K x; order 2: lambda K P M^-1 K x). Hard constraints impose L(x_i) = 0
    // (section 2.7), so L^p = L P L P ... L with P zeroing the fixed rows; the operator
    // (-K) (M^-1 P (-K))^(order-1) stays symmetric positive semi-definite.
    const double sign = order % 2 ? -1.0 : 1.0;
    const Positions* v = &x;
    Positions second;  // orders 3 and 4 alternate between scratch and this
    for (int power = 1; power < order; ++power) {
        Positions& out = power % 2 ? scratch : second;
        out.resize(n, 3);
        double* ss = out.data();
        const double* m = op->mass.data();
        detail::for_each_k_row(*op, *v, [=](int i, double s0, double s1, double s2) {
            const double inverse = f[i] && m[i] > 0 ? 1.0 / m[i] : 0.0;
            ss[3 * i] = s0 * inverse;
            ss[3 * i + 1] = s1 * inverse;
            ss[3 * i + 2] = s2 * inverse;
        });
        v = &out;
    }
    const double scale = sign * lambda;
    return detail::sum_over_k_rows(*op, *v, [=](int i, double s0, double s1, double s2, double* a) {
        // D = 0 still adds 0 x_i, so the bits are those of an explicit diagonal of zeros.
        detail::system_row(d ? d[i] : 0.0, scale, xs + 3 * i, s0, s1, s2, f[i] != 0, ys + 3 * i, a);
    });
}

std::vector<double> LinearSystem::jacobi_diagonal() const {
    const int n = op->size();
    std::vector<double> d(n);
    detail::for_each_row(n, op->threads, [&](int i) {
        double extra = 0;
        if (order == 1) {
            extra = -op->diagonal(i);
        } else if (order > 2) {
            // Orders 3 and 4: the diagonal of (-K) (M^-1 P (-K))^(order-1) would need the wider
            // rings; its first-order estimate |K_ii|^p / M_i^(p-1) is a positive diagonal like it
            // (Jacobi needs no more; these solves take it only with soft weights).
            const double kii = std::abs(op->diagonal(i));
            const double mi = op->mass[i] > 0 ? op->mass[i] : 1.0;
            extra = kii * std::pow(kii / mi, order - 1);
        } else {
            // (K P M^-1 K)_ii = sum over free j of K_ij^2 / M_j, j = i included.
            const double kii = op->diagonal(i);
            if (free[i] && op->mass[i] > 0) extra += kii * kii / op->mass[i];
            for (int k = op->row_start[i]; k < op->row_start[i + 1]; ++k) {
                const int j = op->column[k];
                if (free[j] && op->mass[j] > 0) extra += op->weight[k] * op->weight[k] / op->mass[j];
            }
        }
        const double a = diagonal[i] + lambda_dt * extra;
        d[i] = a > 0 ? a : diagonal[i];
    });
    return d;
}

namespace {

// Relative tolerance of the first-order solves inside the Factored preconditioner: B^-1 needs
// only a rough inverse, and flexible CG absorbs the rest (1e-2 was measured best, see
// bench/results).
constexpr double kInnerTolerance = 1e-2;
// Cap of each inner solve. Typical solves take 5-20 iterations (bench/results); on a mesh of
// collapsing needles they may not reach the tolerance at all, and a rough B^-1 is still a valid
// preconditioner for flexible CG, so the work per outer iteration stays bounded.
constexpr int kInnerCap = 64;

// Automatic: an L^2 solve starts with Jacobi, which wins on light steps (no inner solves), and
// after this many iterations switches to Factored if, at the rate seen so far, Jacobi would need
// as many again. An iteration of Factored costs some 20 of Jacobi's (bench/results), so past
// roughly 2 x kJacobiTrial Jacobi iterations Factored is the cheaper one.
constexpr int kJacobiTrial = 40;

using detail::check_finite;

bool any(const std::array<bool, 3>& active) { return active[0] || active[1] || active[2]; }

std::vector<double> inverse_jacobi(const LinearSystem& system) {
    std::vector<double> inverse = system.jacobi_diagonal();
    for (double& v : inverse) v = 1.0 / v;
    return inverse;
}

// One pass over the free rows: x += alpha p, r -= alpha q, returning the new residual norms
// and, when inv is given, r.z with z = J^-1 r (the next CG coefficient).
struct UpdateSums {
    Column3 residual;
    Column3 rz;
};

UpdateSums update_iterate(const LinearSystem& system, Positions& x, Positions& r,
                          const Positions& p, const Positions& q, const double alpha[3],
                          ResidualNorm norm, const double* inv) {
    const char* f = system.free.data();
    double* xs = x.data();
    double* rs = r.data();
    const double* ps = p.data();
    const double* qs = q.data();
    const double a0 = alpha[0], a1 = alpha[1], a2 = alpha[2];
    const bool l2 = norm == ResidualNorm::L2;
    // a[0..2]: squares (L2) or maxima of |r|; a[3..5]: r.J^-1 r.
    const std::array<double, 6> sums = detail::blocked_reduce<6>(
        system.op->size(), system.op->threads,
        [=](int i, double* a) {
            if (!f[i]) return;
            double* xi = xs + 3 * i;
            double* ri = rs + 3 * i;
            const double* pi = ps + 3 * i;
            const double* qi = qs + 3 * i;
            xi[0] += a0 * pi[0];
            xi[1] += a1 * pi[1];
            xi[2] += a2 * pi[2];
            ri[0] -= a0 * qi[0];
            ri[1] -= a1 * qi[1];
            ri[2] -= a2 * qi[2];
            const double w = inv ? inv[i] : 0.0;
            for (int c = 0; c < 3; ++c) {
                const double rr = ri[c] * ri[c];
                a[c] = l2 ? a[c] + rr : std::max(a[c], std::abs(ri[c]));
                a[3 + c] += rr * w;
            }
        },
        [l2](std::array<double, 6>& total, const std::array<double, 6>& part) {
            for (int c = 0; c < 3; ++c) {
                total[c] = l2 ? total[c] + part[c] : std::max(total[c], part[c]);
                total[3 + c] += part[3 + c];
            }
        });
    UpdateSums out;
    out.residual = l2 ? Column3{std::sqrt(sums[0]), std::sqrt(sums[1]), std::sqrt(sums[2])}
                      : Column3{sums[0], sums[1], sums[2]};
    out.rz = {sums[3], sums[4], sums[5]};
    return out;
}

// One CG update of the active columns: alpha = numerator / p.q, x += alpha p, r -= alpha q (with
// inv: Jacobi's r.z rides on it, see update_iterate); columns that meet their goal stop, and
// after_iteration sees the residuals.
UpdateSums cg_update(const LinearSystem& system, Positions& x, Positions& r, const Positions& p,
                     const Positions& q, const Column3& numerator, const Column3& pq,
                     const Column3& goal, ResidualNorm norm, const double* inv, int done,
                     std::array<bool, 3>& active, Column3& rn,
                     const std::function<void(const Column3&)>& after_iteration) {
    double alpha[3] = {0, 0, 0};
    for (int c = 0; c < 3; ++c)
        if (active[c]) {
            alpha[c] = numerator[c] / pq[c];
            check_finite(alpha[c], done);
        }
    const UpdateSums sums = update_iterate(system, x, r, p, q, alpha, norm, inv);
    rn = sums.residual;
    for (int c = 0; c < 3; ++c) {
        check_finite(rn[c], done);
        if (active[c] && rn[c] <= goal[c]) active[c] = false;
    }
    if (after_iteration) after_iteration(rn);
    return sums;
}

// Fletcher-Reeves beta = rz_new / rz on the active columns (rz <- rz_new); keep = 1 where a
// column stays put.
void cg_beta(const Column3& rz_new, Column3& rz, const std::array<bool, 3>& active, int done,
             double beta[3], double keep[3]) {
    for (int c = 0; c < 3; ++c) {
        beta[c] = 0;
        keep[c] = 0;
        if (active[c]) {
            beta[c] = rz_new[c] / rz[c];
            check_finite(beta[c], done);
            rz[c] = rz_new[c];
        } else {
            keep[c] = 1;
        }
    }
}

// Iterations of Jacobi-preconditioned CG on the free rows, from x with r = b - A x (r zero on
// fixed rows). Column c iterates while active[c], and stops once rn[c] <= goal[c]; at most
// `cap` iterations (counted from `done`). Returns the iteration count reached.
int jacobi_cg(const LinearSystem& system, const double* inv, Positions& x, Positions& r,
              Positions& p, Positions& q, Positions& scratch, const Column3& goal,
              ResidualNorm norm, int done, int cap, std::array<bool, 3>& active, Column3& rn,
              const std::function<void(const Column3&)>& after_iteration) {
    const int n = system.op->size();
    const int threads = system.op->threads;
    (void)threads;
    const char* f = system.free.data();
    double* ps = p.data();
    double* rs = r.data();
    // p = z = J^-1 r, rz = r.z
    Column3 rz = detail::blocked_sum<3>(n, threads, [=](int i, double* a) {
        const double s = f[i] ? inv[i] : 0.0;
        for (int c = 0; c < 3; ++c) {
            ps[3 * i + c] = rs[3 * i + c] * s;
            a[c] += rs[3 * i + c] * ps[3 * i + c];
        }
    });

    while (any(active) && done < cap) {
        ++done;
        const Column3 pq = system.apply_dot(p, q, scratch);
        const UpdateSums sums = cg_update(system, x, r, p, q, rz, pq, goal, norm, inv, done,
                                          active, rn, after_iteration);
        if (!any(active)) break;
        // p = J^-1 r + beta p on the columns still iterating.
        double beta[3], keep[3];
        cg_beta(sums.rz, rz, active, done, beta, keep);
        FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
        for (int i = 0; i < n; ++i) {
            if (!f[i]) continue;
            for (int c = 0; c < 3; ++c) {
                double& pc = ps[3 * i + c];
                pc = keep[c] != 0 ? pc : rs[3 * i + c] * inv[i] + beta[c] * pc;
            }
        }
    }
    return done;
}

// z ~ B^-1 r for B = (D - s K) D^-1 (D - s K) (see solver.h): two Jacobi-CG solves with the
// first-order matrix D - s K, from zero, to kInnerTolerance.
class FactoredPreconditioner {
public:
    FactoredPreconditioner(const LinearSystem& outer, int cap) : cap_(cap) {
        inner_.op = outer.op;
        inner_.diagonal = outer.diagonal;
        inner_.free = outer.free;
        inner_.lambda_dt = std::sqrt(outer.lambda_dt);
        inner_.order = 1;
        inverse_ = inverse_jacobi(inner_);
        const int n = outer.op->size();
        rhs_.resize(n, 3);
        p_.resize(n, 3);
        q_.resize(n, 3);
    }

    // z = B^-1 r on the free rows, 0 on the fixed ones; `u` is scratch. Returns the inner
    // iterations.
    int apply(const Positions& r, Positions& z, Positions& u) {
        const int n = inner_.op->size();
        const char* f = inner_.free.data();
        const double* d = inner_.diagonal.data();
        const int threads = inner_.op->threads;
        detail::for_each_row(n, threads, [&](int i) {
            for (int c = 0; c < 3; ++c) rhs_(i, c) = f[i] ? r(i, c) : 0.0;
        });
        int iterations = solve_from_zero(u);
        detail::for_each_row(n, threads, [&](int i) {
            for (int c = 0; c < 3; ++c) rhs_(i, c) = f[i] ? d[i] * u(i, c) : 0.0;
        });
        iterations += solve_from_zero(z);
        return iterations;
    }

private:
    // y = (D - s K)^-1 rhs_ roughly; rhs_ is consumed (it becomes the residual).
    int solve_from_zero(Positions& y) {
        y.setZero(inner_.op->size(), 3);
        Column3 rn = column_norms(rhs_, inner_.free, ResidualNorm::L2, inner_.op->threads);
        Column3 goal;
        std::array<bool, 3> active;
        for (int c = 0; c < 3; ++c) {
            goal[c] = kInnerTolerance * rn[c];
            active[c] = rn[c] > 0;
        }
        return jacobi_cg(inner_, inverse_.data(), y, rhs_, p_, q_, q_, goal, ResidualNorm::L2, 0,
                         cap_, active, rn, {});
    }

    LinearSystem inner_;
    std::vector<double> inverse_;
    Positions rhs_, p_, q_;
    int cap_;
};

// Iterations of flexible CG (FCG(1)) preconditioned by B, from x with r = b - A x.
// Same contract as jacobi_cg; inner iterations are added to *inner, and no new outer iteration
// starts once *inner reaches inner_cap.
int factored_fcg(const LinearSystem& system, FactoredPreconditioner& preconditioner, Positions& x,
                 Positions& r, Positions& p, Positions& q, Positions& z, Positions& scratch,
                 const Column3& goal, ResidualNorm norm, int done, int cap,
                 std::array<bool, 3>& active, Column3& rn, int* inner, int inner_cap,
                 const std::function<void(const Column3&)>& after_iteration) {
    const int n = system.op->size();
    const int threads = system.op->threads;
    const std::vector<char>& free = system.free;
    const char* f = free.data();
    *inner += preconditioner.apply(r, p, scratch);  // p = z = B^-1 r
    Column3 pr = column_dots(p, r, free, threads);
    while (any(active) && done < cap && *inner < inner_cap) {
        ++done;
        const Column3 pq = system.apply_dot(p, q, scratch);
        cg_update(system, x, r, p, q, pr, pq, goal, norm, nullptr, done, active, rn,
                  after_iteration);
        if (!any(active)) break;
        *inner += preconditioner.apply(r, z, scratch);
        // p = z - (z.q / p.q) p: A-orthogonal to the previous direction even though B^-1 is
        // only applied approximately.
        const Column3 zq = column_dots(z, q, free, threads);
        double beta[3] = {0, 0, 0};
        double keep[3] = {0, 0, 0};
        for (int c = 0; c < 3; ++c) {
            if (active[c]) {
                beta[c] = -zq[c] / pq[c];
                check_finite(beta[c], done);
            } else {
                keep[c] = 1;
            }
        }
        double* pw = p.data();
        const double* zs = z.data();
        const double* rs = r.data();
        pr = detail::blocked_sum<3>(n, threads, [=](int i, double* a) {
            if (!f[i]) return;
            for (int c = 0; c < 3; ++c) {
                double& pc = pw[3 * i + c];
                pc = keep[c] != 0 ? pc : zs[3 * i + c] + beta[c] * pc;
                a[c] += pc * rs[3 * i + c];
            }
        });
    }
    return done;
}

// Iterations of CG preconditioned by one multigrid V-cycle (multigrid.h; first-order systems),
// from x with r = b - A x. Same contract as jacobi_cg; z is work space.
int multigrid_cg(const LinearSystem& system, detail::Multigrid& mg, Positions& x, Positions& r,
                 Positions& p, Positions& q, Positions& z, const Column3& goal, ResidualNorm norm,
                 int done, int cap, std::array<bool, 3>& active, Column3& rn,
                 const std::function<void(const Column3&)>& after_iteration) {
    const int n = system.op->size();
    const int threads = system.op->threads;
    const std::vector<char>& free = system.free;
    const char* f = free.data();
    // q is free between the update and the next product: the cycle's work space.
    const auto precondition = [&mg, &q](const Positions& from, Positions& to) {
        const std::array<double, 6> dots = mg.apply(from.data(), to.data(), q.data());
        return Column3{dots[0], dots[1], dots[2]};
    };
    Column3 rz = precondition(r, p);  // p = z = B^-1 r
    while (any(active) && done < cap) {
        ++done;
        const Column3 pq = system.apply_dot(p, q, z);
        cg_update(system, x, r, p, q, rz, pq, goal, norm, nullptr, done, active, rn,
                  after_iteration);
        if (!any(active)) break;
        double beta[3], keep[3];
        cg_beta(precondition(r, z), rz, active, done, beta, keep);
        double* pw = p.data();
        const double* zs = z.data();
        detail::for_each_row(n, threads, [=](int i) {
            if (!f[i]) return;
            for (int c = 0; c < 3; ++c) {
                double& pc = pw[3 * i + c];
                pc = keep[c] != 0 ? pc : zs[3 * i + c] + beta[c] * pc;
            }
        });
    }
    return done;
}

// b = D x_old, and the norms that scale the stopping rule. The right-hand side actually solved
// on the free rows includes the fixed values' coupling, b_f - A_fc x_c; its norm (or b's,
// whichever is larger) is the scale. Without fixed rows the two are the same and the product is
// skipped. q and scratch are work space.
Column3 right_hand_side(const LinearSystem& system, const Positions& x, ResidualNorm norm,
                        Positions& b) {
    const int n = system.op->size();
    const int threads = system.op->threads;
    const std::vector<char>& free = system.free;
    const double* d = system.diagonal.data();
    detail::for_each_row(n, threads, [&](int i) { b.row(i) = d[i] * x.row(i); });
    const Column3 norm_b = column_norms(b, free, norm, threads);
    if (std::find(free.begin(), free.end(), 0) == free.end()) return norm_b;
    Positions fixed_only = Positions::Zero(n, 3), q, scratch;
    for (int i = 0; i < n; ++i)
        if (!free[i]) fixed_only.row(i) = x.row(i);
    system.apply(fixed_only, q, scratch);
    fixed_only = b - q;
    const Column3 norm_eb = column_norms(fixed_only, free, norm, threads);
    Column3 scale;
    for (int c = 0; c < 3; ++c) scale[c] = std::max(norm_b[c], norm_eb[c]);
    return scale;
}

// Worst column of rn relative to the scale of the stopping rule.
double relative(const Column3& rn, const Column3& scale) {
    double worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, scale[c] > 0 ? rn[c] / scale[c] : rn[c]);
    return worst;
}

// SolveSettings::progress from residual norms: how far they have come down, on a log scale,
// from the first ones seen to the goal.
class Progress {
public:
    Progress(const SolveSettings& settings, const Column3& goal) : goal_(goal) {
        if (settings.progress)
            callback_ = [this, &settings](const Column3& rn) { settings.progress(fraction(rn)); };
    }
    void start(const Column3& rn) {
        if (started_) return;
        initial_ = rn;
        started_ = true;
    }
    const std::function<void(const Column3&)>& callback() const { return callback_; }

private:
    double fraction(const Column3& now) const {
        double worst = 1;
        for (int c = 0; c < 3; ++c) {
            if (!(now[c] > goal_[c]) || !(initial_[c] > goal_[c])) continue;
            worst = std::min(worst,
                             std::log(initial_[c] / now[c]) / std::log(initial_[c] / goal_[c]));
        }
        return std::max(0.0, worst);
    }
    Column3 goal_, initial_{0, 0, 0};
    bool started_ = false;
    std::function<void(const Column3&)> callback_;
};

// The stiffness of the system as its diagonal sees it: the mean over the free rows of
// a (-K_ii) / D_i, a = lambda_dt (first order) or sqrt(lambda_dt) (the complex factor of L^2),
// and the number of those rows. Jacobi's iterations grow as the square root of the first.
std::array<double, 2> stiffness(const LinearSystem& system) {
    const SparseOperator& op = *system.op;
    const double a = system.order == 1 ? system.lambda_dt : std::sqrt(system.lambda_dt);
    const char* f = system.free.data();
    const double* d = system.diagonal.data();
    const std::array<double, 2> sums =
        detail::blocked_sum<2>(op.size(), op.threads, [&](int i, double* s) {
            if (!f[i] || !(d[i] > 0)) return;
            s[0] += a * -op.diagonal(i) / d[i];
            s[1] += 1;
        });
    return {sums[1] > 0 ? sums[0] / sums[1] : 0.0, sums[1]};
}

// Automatic's choice of the multigrid V-cycle (multigrid.h). A cycle costs about three products
// with K (two on the finest level, the coarse levels about one) against one for a Jacobi
// iteration, and its set-up some ten Jacobi iterations, so it pays only where Jacobi needs
// several times more iterations than it does: strong steps. Measured in one run (1 thread, CPU
// seconds of fair(), bench/results/issue12/preconditioners.md, 2026-11-25), 1.2 M-face bunny
// then 1 M-face torus, stiffness (above) in brackets, Jacobi / multigrid:
//   first order: curvature 4.74 [5.6, 6.2] 1.19 / 1.75 s, 1.11 / 1.28 s; umbrella 3.16 [3.2]
//     and scale-dependent 1.58 [5.0, 3.9] Jacobi 1.2-1.8x faster; curvature 19 [22.5, 25]
//     1.99 / 2.04 s, 1.76 / 1.59 s; curvature 76 [90, 100] 3.25 / 2.18 s, 2.75 / 2.09 s.
//   L^2 (complex Jacobi / complex multigrid): curvature 22.5 [5.6, 6.2] 5.28 / 4.75 s,
//     5.43 / 5.70 s; umbrella 10 [3.2] Jacobi 1.7-1.9x faster; scale-dependent 2.5 [5.0, 3.9]
//     3.90 / 3.29 s, 1.43 / 1.97 s; curvature 90 [11.3, 12.5] 8.02 / 5.72 s, 6.95 / 7.79 s;
//     curvature 360 [22.5, 25] 10.83 / 6.36 s, 8.03 / 7.00 s.
// So: first order from stiffness 20, L^2 from 8 (the defaults, at 3-6, stay on the Jacobi paths,
// whose memory is lower: the hierarchy and one more vector cost 110-180 bytes per vertex; the
// torus' L^2 at 90 is the one measured loss, 12 %), and only with at least kMultigridRows free
// vertices (not measured below; a small solve is fast anyway). Re-measured once the V-cycle's
// weights came from a tighter bound (multigrid.cpp, kSmootherWeight: 10-25 % fewer cycles): the
// V-cycle now wins the bunny's curvature and scale-dependent L^2 defaults by 20-22 % and still
// loses the torus' by 23-60 %, at about the same stiffness; the thresholds stand
// (bench/results/issue12/preconditioners.md, last section).
//
// Since then the complex solve's Jacobi gave way to block symmetric Gauss-Seidel
// (complex_factor.h) from stiffness 3.5 on (and below since session 19, after the figures
// further down), except for the umbrella, and the V-cycle's threshold moved. Measured in one run
// each (1 thread, CPU seconds of fair(), bench/results/issue12/preconditioners.md, "Symmetric
// Gauss-Seidel"), complex Jacobi / Gauss-Seidel / V-cycle, stiffness in brackets:
//   bunny (Loop x2, 603 k vertices): umbrella 10 [3.2] 1.34 / 1.42 / 2.28 s; scale-dependent 2.5
//     [5.0] 3.86 / 3.28 / 3.09; curvature 22.5 [5.6] 5.22 / 3.80 / 4.43; curvature 90 [11.2]
//     6.95 / 4.90 / 4.91; umbrella 197 [14.2] 2.43 / 2.27 / 3.02; scale-dependent 22.1 [14.9]
//     7.21 / 5.61 / 4.13; curvature 202 [16.8] 8.81 / 6.35 / 5.59; curvature 360 [22.4]
//     9.70 / 7.18 / 5.17.
//   torus (500 k): umbrella 10 [3.2] 0.86 / 0.90 / 1.68; scale-dependent 2.5 [3.9] 1.27 / 1.13 /
//     1.98; curvature 22.5 [6.2] 2.33 / 1.93 / 2.82; curvature 90 [12.4] 2.91 / 2.45 / 3.57;
//     curvature 360 [24.8] 4.14 / 3.02 / 5.34; the one-click steps [162-339] 8.2-13.9 /
//     6.9-8.4 / 3.1-6.1.
//   armadillo, bunny00, elephant (Loop, 104-178 k, in cache): Gauss-Seidel within 10 % of
//     Jacobi, faster on the 178 k elephant; umbrella 197 [14.0] Jacobi 0.29-0.54 s, Gauss-Seidel
//     20-34 % slower, V-cycle 0.44-0.70; scale-dependent 22 [11.2-15.0] V-cycle 0.91-1.04 s
//     against Gauss-Seidel 1.09-1.15 from 13.7 on; curvature 201 [13.8-17.2] V-cycle better from
//     15; curvature 360 [18.5-23] V-cycle better but on the armadillo (0.86 against 0.61 s).
//   camel, dragon, sphere (13-20 k, one sweep block): Gauss-Seidel halves the iterations
//     and takes 25-40 % less time from 3.9 on.
// So the umbrella kept complex Jacobi (its iterations drop by 10-25 % only) up to the V-cycle
// at 20, the other operators swept from 3.5 and took the V-cycle from 14.
//
// Then the V-cycle's finest level got Gauss-Seidel smoothing (multigrid.h: up to 26 % fewer
// cycles), which moved the other operators' threshold down to 9. Same run format, Gauss-Seidel
// / V-cycle: bunny curvature 22.5 [5.6] 3.91 / 3.94 s, scale-dependent 2.5 [5.0] 3.62 / 3.26,
// curvature 90 [11.3] 5.10 / 4.21, scale-dependent 22.1 [14.9] 5.66 / 4.10, curvature 202
// [16.9] 6.15 / 4.54; umbrella 197 [14.1] complex Jacobi 2.56 / 2.90; torus curvature 22.5
// [5.5] 2.09 / 3.00, curvature 90 [11.0] 2.71 / 3.49, curvature 360 [22.0] 3.29 / 4.92;
// armadillo, bunny00, elephant (104-178 k): ties at 4.6-5.8, the V-cycle 5-25 % faster from 10
// on but on the armadillo's curvature 90 [9.25] (0.51 / 0.46 s); umbrella 197 [14.0] complex
// Jacobi 0.29-0.48 s / 0.38-0.67. Below 9 the sweeps hold less memory than the hierarchy and
// tie or win; from 9 the scans want the V-cycle, the torus not (1.3x and 1.5x lost at 11 and
// 22).
//
// After the V-cycle's filtered prolongator and four coarse sweeps (multigrid.cpp, session 12;
// same run format, Gauss-Seidel / V-cycle): bunny curvature 22.5 [5.6] 3.44 / 3.34 s, 90 [11.3]
// 4.78 / 3.82; torus curvature 22.5 [5.5] 1.91 / 2.81, 90 [11.0] 2.50 / 2.93, 360 [22.0] 3.00 /
// 3.58. The threshold stands: the torus still loses 1.2x at 11 and 22 (1.3x and 1.5x before).
constexpr double kMultigridFirstOrder = 20;
constexpr double kMultigridComplex = 9;
constexpr double kMultigridComplexUnitWeights = 20;
constexpr double kMultigridRows = 50000;
// The sweeps also win below the stiffness of 3.5 from which they used to be taken (nothing had
// been measured there, and the scans' one-click curvature steps fall there: time steps 1-3).
// Session 19, one thread, CPU seconds of fair() (iterations), complex Jacobi / Gauss-Seidel,
// stiffness in brackets: bunny Loop x2 curvature 0.05 [0.27] 1.31 / 1.05 (16 / 8), 0.5 [0.84]
// 2.06 / 1.52 (37 / 18), scale-dependent 0.05 [0.71] 1.45 / 1.28, 0.5 [2.2] 2.35 / 2.17, 2 [4.5]
// 3.32 / 3.00; 1 M-face torus curvature 0.05 / 0.5 0.70 / 0.68, 1.05 / 0.99, scale-dependent
// 0.05 [0.53] 0.59 / 0.63 (a loss, 9 / 7 iterations), 0.5 0.83 / 0.83, 2 1.18 / 1.11;
// raw-triangulation dragon (1.3 M faces) curvature 0.05 2.18 / 1.83, 0.5 [1.3] 3.25 / 2.67,
// 2.546 [3.0] (its one-click step) 4.82 / 3.70 (110 / 61), scale-dependent 0.05 / 0.5 / 2
// 2.10 / 1.85, 3.23 / 2.85, 4.52 / 3.22; the study's sphere 3 k and 51 k, flat patch, fandisk
// and camel at 0.05 and 1: Gauss-Seidel faster in 18 of 20 (by up to 28 %), one tie, one loss
// (the flat patch's curvature 0.05, 1.3 / 1.4 ms); over all 36 cases 32 faster, 2 ties and 2
// losses of 6-8 % on the mildest steps. So every weighted operator sweeps; the umbrella keeps
// complex Jacobi (above: its iterations drop by 10-25 % only).

// A later step of the same run (settings.previous: an L^2 step re-assembled on the smoothed
// mesh) takes the V-cycle when the previous one did, or when complex Jacobi (or Gauss-Seidel,
// below) needed more than this many iterations there: about what a V-cycle solve costs in
// Jacobi iterations (set-up ~13, then ~35 cycles of ~3.2 each at the one-click strengths). The stiffness does not predict
// the later steps: on the smoothed mesh it rises while Jacobi's iterations rise on a scan and
// fall on a smooth shape. Measured (1 thread, curvature L^2 x4, process seconds of fair();
// solves' iterations; complex Jacobi / V-cycle throughout):
//   bunny Loop x2 (1.2 M faces), 22.5: Jacobi 116, 206, 218, 238 (29.6 s) / 31, 46, 48, 51
//     (23.4 s), stiffness 5.7 then 7.7-7.9 (so the threshold of 8 gave Jacobi at 23.0 and the
//     V-cycle from 25 on, 31.0 s against 24.7 s); 10: 92, 168, 173, 190 (25.1 s) / 29-44 (21.0 s)
//   torus (1 M faces), 22.5: 72, 62, 50, 51 (7.6 s) / 30, 26, 20, 20 (10.4 s), stiffness 5.5
//     then 6.6; 50: 84, 69, 60, 58 (8.6 s) / 37, 31, 26, 25 (12.2 s)
// With Gauss-Seidel (1 thread, curvature L^2 x4, Gauss-Seidel throughout /
// V-cycle throughout): bunny 22.5: 60, 120, 121, 128 (22.2 s) / 27, 45, 43, 42 (23.0 s); 50:
// 76, 135, 133, 149 (25.9 s) / 30-43 (22.1 s); torus 22.5: 42, 32, 27, 25 (6.0 s) / 25-18
// (9.6 s); 50: 47-32 (6.9 s) / 31-20 (11.1 s). A Gauss-Seidel iteration costs ~1.2 Jacobi
// iterations and a V-cycle step about 110 of them on the bunny, so the same threshold serves.
constexpr int kJacobiWorthMultigrid = 100;

// Needle-rich meshes (noise in all directions leaves near-degenerate triangles, whose
// cotangent weights are large) make the V-cycle slow while the Gauss-Seidel sweeps cope: one
// curvature-flow L^2 step at its automatic time step took 119 V-cycles (14.9 s) against 205
// Gauss-Seidel iterations (9.6 s) on the 1.2 M-face bunny with 0.25 edge of isotropic noise
// (with the noise along the normals: 26 cycles, 4.0 s), 290 cycles (24.2 s) against 221
// iterations (8.0 s) on the 1 M-face torus, 70 (1.83 s) against 138 (1.47 s) on bunny00 Loop x1
// (151 k vertices); docs/performance.md, "Noise in all directions". What tells these meshes
// apart is the share of K's couplings heavier than kHeavyCoupling times the mean: 0.09-0.13 % on
// three Loop-subdivided scans (bunny, bunny00, armadillo) and the torus with isotropic noise, at
// most 0.001 % on the same meshes with the noise along the normals. The one-click curvature flow
// (L^2, 4 steps, automatic strength) on the bunny with isotropic noise: 77.1 s -> 44.7 s, the
// later steps no longer handed to the V-cycle (kJacobiWorthMultigrid), the same result to 6e-10
// of the bounding box's diagonal. Above kHeavyShare, when some couplings are negative
// (cotangent weights of obtuse angles, eq. 14: needles have large ones of both signs),
// Automatic keeps the L^2 step off the V-cycle (the hand-over after half the iteration cap
// stays). The scale-dependent weights
// (eq. 11), all positive, are heavy on the same meshes at short edges, but there the V-cycle
// still wins: 31 cycles (4.5 s) against 106 Gauss-Seidel iterations (5.2 s) on the bunny.
constexpr double kHeavyCoupling = 16;
constexpr double kHeavyShare = 1e-4;

bool needle_rich(const SparseOperator& op) {
    if (op.unit_weights || op.weight.empty()) return false;
    const double* w = op.weight.data();
    const int n = op.size();
    const int* start = op.row_start.data();
    const std::array<double, 2> total = detail::blocked_sum<2>(n, op.threads, [=](int i, double* s) {
        for (int e = start[i]; e < start[i + 1]; ++e) s[0] += std::abs(w[e]);
        s[1] += start[i + 1] - start[i];
    });
    if (!(total[1] > 0) || !(total[0] > 0)) return false;
    const double heavy = kHeavyCoupling * total[0] / total[1];
    const std::array<double, 2> count = detail::blocked_sum<2>(n, op.threads, [=](int i, double* s) {
        for (int e = start[i]; e < start[i + 1]; ++e) {
            s[0] += std::abs(w[e]) > heavy;
            s[1] += w[e] < 0;
        }
    });
    return count[1] > 0 && count[0] > kHeavyShare * total[1];
}

// Automatic's choice of the V-cycle, given the system's stiffness s. The needle count (two
// passes over K) runs only when the V-cycle would otherwise be taken.
bool automatic_multigrid(const LinearSystem& system, const std::array<double, 2>& s,
                         const SolveStats* previous) {
    if (s[1] < kMultigridRows) return false;
    const bool wanted =
        previous && previous->complex_factor && system.order == 2
            ? previous->multigrid || previous->iterations > kJacobiWorthMultigrid
            : s[0] >= (system.order == 1          ? kMultigridFirstOrder
                       : system.op->unit_weights ? kMultigridComplexUnitWeights
                                                 : kMultigridComplex);
    return wanted && !(system.order == 2 && needle_rich(*system.op));
}

// Whether the multigrid preconditioner is used: asked for, or chosen by Automatic.
bool use_multigrid(const LinearSystem& system, Preconditioner preconditioner) {
    if (preconditioner == Preconditioner::Multigrid) return true;
    return preconditioner == Preconditioner::Automatic &&
           automatic_multigrid(system, stiffness(system), nullptr);
}

// CG's recursively updated residual drifts from the true one on ill-conditioned systems (the
// L^2 forms), so convergence is confirmed on the true residual, restarting from the current
// iterate when it disagrees, at most this many times.
constexpr int kMaxRestarts = 8;

// Automatic, L^2 without soft weights (complex_factor.h): corrections by the complex solve until
// the true L^2 residual meets the goal, preconditioned by the V-cycle (multigrid), else by
// Gauss-Seidel (gauss_seidel) or complex Jacobi. Needs only b besides the complex solver's
// vectors.
SolveStats solve_complex(const LinearSystem& system, Positions& x, const Positions& b,
                         const Column3& scale, const Column3& goal, const SolveSettings& settings,
                         bool multigrid, bool gauss_seidel = false) {
    SolveStats stats;
    stats.complex_factor = true;
    // The hierarchy first: its set-up's work space is gone before the solver's vectors come.
    std::unique_ptr<detail::Multigrid> cycle;
    if (multigrid) {
        cycle = std::make_unique<detail::Multigrid>(*system.op, system.diagonal, system.free,
                                                    std::sqrt(system.lambda_dt),
                                                    detail::Multigrid::Kind::Complex);
        stats.multigrid = true;
    }
    detail::ComplexFactorSolver solver(system, cycle.get(), gauss_seidel);
    stats.gauss_seidel = solver.gauss_seidel();
    Progress progress(settings, goal);
    std::array<bool, 3> active{false, false, false};
    Column3 rn{0, 0, 0};
    for (int restart = 0;; ++restart) {
        rn = solver.set_residual(b, x, settings.norm);
        for (int c = 0; c < 3; ++c) {
            check_finite(rn[c], stats.iterations);
            active[c] = rn[c] > goal[c];
        }
        progress.start(rn);
        if (!any(active) || restart == kMaxRestarts || stats.iterations >= settings.max_iterations)
            break;
        stats.iterations += solver.correct(x, goal, settings.norm,
                                           settings.max_iterations - stats.iterations, active,
                                           progress.callback());
    }
    stats.residual = relative(rn, scale);
    stats.converged = !any(active);
    return stats;
}

// Automatic's decision after the Jacobi trial: the iterations still needed at the trial's
// geometric rate (from `start` to `rn` in `done` iterations), worst active column.
double remaining_iterations(const std::array<bool, 3>& active, const Column3& start,
                            const Column3& rn, const Column3& goal, int done) {
    double remaining = 0;
    for (int c = 0; c < 3; ++c) {
        if (!active[c]) continue;
        if (!(rn[c] < start[c])) return INFINITY;
        const double rate = std::log(rn[c] / start[c]) / done;
        remaining = std::max(remaining, std::log(goal[c] / rn[c]) / rate);
    }
    return remaining;
}

// r = b - A x on the free rows (0 on the fixed ones), returning its norms; q and scratch are
// work space.
Column3 true_residual(const LinearSystem& system, const Positions& b, const Positions& x,
                      ResidualNorm norm, Positions& r, Positions& q, Positions& scratch) {
    const char* f = system.free.data();
    system.apply(x, q, scratch);
    detail::for_each_row(system.op->size(), system.op->threads, [&](int i) {
        for (int c = 0; c < 3; ++c) r(i, c) = f[i] ? b(i, c) - q(i, c) : 0.0;
    });
    return column_norms(r, system.free, norm, system.op->threads);
}

// Jacobi CG, or flexible CG with the factored preconditioner (both for L^2 with soft weights, or
// when asked for), until the true residual meets the goal.
SolveStats solve_real(const LinearSystem& system, Positions& x, const Positions& b,
                      const Column3& scale, const Column3& goal, const SolveSettings& settings) {
    const int n = system.op->size();
    // scratch holds M^-1 K p between the two products of an L^2 system (and the inner solves'
    // first solution); first-order solves never touch it.
    Positions r(n, 3), p(n, 3), q(n, 3), scratch(system.order >= 2 ? n : 0, 3);
    SolveStats stats;
    std::unique_ptr<FactoredPreconditioner> factored;
    std::unique_ptr<detail::Multigrid> multigrid;
    Positions z;
    const auto use_factored = [&] {
        factored = std::make_unique<FactoredPreconditioner>(system, kInnerCap);
        z.resize(n, 3);
        stats.factored = true;
    };
    // L^2 with soft weights has no multigrid path (the complex factor needs D = M): Multigrid
    // then behaves as Automatic.
    bool trial_pending = system.order == 2 &&
                         (settings.preconditioner == Preconditioner::Automatic ||
                          settings.preconditioner == Preconditioner::Multigrid);
    if (system.order == 2 && settings.preconditioner == Preconditioner::Factored) use_factored();
    if (system.order == 1 && use_multigrid(system, settings.preconditioner)) {
        multigrid = std::make_unique<detail::Multigrid>(*system.op, system.diagonal, system.free,
                                                        system.lambda_dt,
                                                        detail::Multigrid::Kind::Real);
        z.resize(n, 3);
        stats.multigrid = true;
    }
    // Jacobi's diagonal (for L^2 a sweep over the 2-ring) only when Jacobi iterations may run.
    const std::vector<double> inverse =
        factored || multigrid ? std::vector<double>() : inverse_jacobi(system);
    // The iteration cap bounds the work too: an inner iteration is one product with K, an
    // iteration of the L^2 system two, so the inner solves get twice the cap.
    const int inner_cap = 2 * settings.max_iterations;

    Progress progress(settings, goal);
    const std::function<void(const Column3&)>& after_iteration = progress.callback();
    std::array<bool, 3> active{false, false, false};
    Column3 rn{0, 0, 0};
    for (int restart = 0;; ++restart) {
        rn = true_residual(system, b, x, settings.norm, r, q, scratch);
        for (int c = 0; c < 3; ++c) {
            check_finite(rn[c], stats.iterations);
            active[c] = rn[c] > goal[c];
        }
        progress.start(rn);
        if (!any(active) || restart == kMaxRestarts || stats.iterations >= settings.max_iterations ||
            stats.inner_iterations >= inner_cap)
            break;
        if (multigrid) {
            stats.iterations = multigrid_cg(system, *multigrid, x, r, p, q, z, goal, settings.norm,
                                            stats.iterations, settings.max_iterations, active, rn,
                                            after_iteration);
            continue;
        }
        if (factored) {
            stats.iterations = factored_fcg(system, *factored, x, r, p, q, z, scratch, goal,
                                            settings.norm, stats.iterations,
                                            settings.max_iterations, active, rn,
                                            &stats.inner_iterations, inner_cap, after_iteration);
            continue;
        }
        const int trial_end = trial_pending
                                  ? std::min(settings.max_iterations, stats.iterations + kJacobiTrial)
                                  : settings.max_iterations;
        const int before = stats.iterations;
        const Column3 start = rn;
        stats.iterations = jacobi_cg(system, inverse.data(), x, r, p, q, scratch, goal,
                                     settings.norm, stats.iterations, trial_end, active, rn,
                                     after_iteration);
        if (trial_pending && stats.iterations == trial_end && any(active) &&
            trial_end < settings.max_iterations) {
            trial_pending = false;
            const double remaining =
                remaining_iterations(active, start, rn, goal, stats.iterations - before);
            if (remaining > kJacobiTrial) use_factored();
            else stats.iterations = jacobi_cg(system, inverse.data(), x, r, p, q, scratch, goal,
                                              settings.norm, stats.iterations,
                                              settings.max_iterations, active, rn, after_iteration);
            --restart;  // the switch (or going on) is not a restart
        }
    }
    stats.residual = relative(rn, scale);
    stats.converged = !any(active);
    return stats;
}

}  // namespace

SolveStats solve(const LinearSystem& system, Positions& x, const SolveSettings& settings) {
    Positions b(system.op->size(), 3);
    const Column3 scale = right_hand_side(system, x, settings.norm, b);
    Column3 goal;
    for (int c = 0; c < 3; ++c) goal[c] = scale[c] > 0 ? settings.tolerance * scale[c] : 0.0;
    const bool complex = settings.preconditioner == Preconditioner::Automatic ||
                         settings.preconditioner == Preconditioner::Multigrid;
    // L^3 and L^4 without soft weights: by partial fractions (power_solve.h); with them, or when
    // Jacobi is asked for, Jacobi CG on the L^p system itself.
    if (complex && detail::power_solve_applies(system))
        return detail::solve_power(system, x, b, goal, settings);
    if (!complex || !detail::complex_factor_applies(system))
        return solve_real(system, x, b, scale, goal, settings);
    if (settings.preconditioner != Preconditioner::Automatic)
        return solve_complex(system, x, b, scale, goal, settings, true);
    const std::array<double, 2> s = stiffness(system);
    if (automatic_multigrid(system, s, settings.previous))
        return solve_complex(system, x, b, scale, goal, settings, true);
    // For the umbrella complex Jacobi's iterations cost less than Gauss-Seidel's fewer (above).
    const bool gauss_seidel = !system.op->unit_weights;
    // Automatic on the Jacobi path, with half the cap: a system it stalls on (needles whose
    // capped cotangents still leave it ill-conditioned: curvature L^2 x4 at time step 4 on
    // CGAL's camel with isotropic noise stalled at 1e-5 after 2000 iterations) is handed to the
    // multigrid V-cycle from where it stopped, with the rest (the four steps then took 2141
    // iterations in all, against 527 with the V-cycle throughout).
    SolveSettings first = settings;
    first.max_iterations = (settings.max_iterations + 1) / 2;
    SolveStats stats = solve_complex(system, x, b, scale, goal, first, false, gauss_seidel);
    SolveSettings rest = settings;
    rest.max_iterations = settings.max_iterations - stats.iterations;
    if (stats.converged || rest.max_iterations <= 0) return stats;
    const SolveStats more = solve_complex(system, x, b, scale, goal, rest, true);
    stats.iterations += more.iterations;
    stats.multigrid = true;
    stats.residual = more.residual;
    stats.converged = more.converged;
    return stats;
}

}  // namespace fairing
