#include "fairing/solver.h"

#include "kernels.h"

#include <array>
#include <cmath>
#include <string>

namespace fairing {
namespace {

using Column3 = std::array<double, 3>;

// Sums (L2: of squares, then the root) or maxima (L-infinity) of |v| per column over the free
// rows: one pass, split over `threads`.
Column3 column_norms(const Positions& v, const std::vector<char>& free, ResidualNorm norm,
                     int threads) {
    const int n = static_cast<int>(v.rows());
    const double* d = v.data();
    const char* f = free.data();
    double s0 = 0, s1 = 0, s2 = 0, m0 = 0, m1 = 0, m2 = 0;
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1) \
                   reduction(+ : s0, s1, s2) reduction(max : m0, m1, m2))
    for (int i = 0; i < n; ++i) {
        if (!f[i]) continue;
        const double a0 = d[3 * i], a1 = d[3 * i + 1], a2 = d[3 * i + 2];
        s0 += a0 * a0;
        s1 += a1 * a1;
        s2 += a2 * a2;
        m0 = std::max(m0, std::abs(a0));
        m1 = std::max(m1, std::abs(a1));
        m2 = std::max(m2, std::abs(a2));
    }
    if (norm == ResidualNorm::L2) return {std::sqrt(s0), std::sqrt(s1), std::sqrt(s2)};
    return {m0, m1, m2};
}

// Per column sum over the free rows of a_i b_i.
Column3 column_dots(const Positions& a, const Positions& b, const std::vector<char>& free,
                    int threads) {
    const int n = static_cast<int>(a.rows());
    const double* pa = a.data();
    const double* pb = b.data();
    const char* f = free.data();
    double s0 = 0, s1 = 0, s2 = 0;
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1) \
                   reduction(+ : s0, s1, s2))
    for (int i = 0; i < n; ++i) {
        if (!f[i]) continue;
        s0 += pa[3 * i] * pb[3 * i];
        s1 += pa[3 * i + 1] * pb[3 * i + 1];
        s2 += pa[3 * i + 2] * pb[3 * i + 2];
    }
    return {s0, s1, s2};
}

}  // namespace

void LinearSystem::apply(const Positions& x, Positions& y, Positions& scratch) const {
    const int n = op->size();
    y.resize(n, 3);
    const double* xs = x.data();
    const double* d = diagonal.data();
    double* ys = y.data();
    const double lambda = lambda_dt;
    if (order == 1) {
        detail::for_each_k_row(*op, x, [=](int i, double s0, double s1, double s2) {
            ys[3 * i] = d[i] * xs[3 * i] - lambda * s0;
            ys[3 * i + 1] = d[i] * xs[3 * i + 1] - lambda * s1;
            ys[3 * i + 2] = d[i] * xs[3 * i + 2] - lambda * s2;
        });
    } else {
        // Hard constraints impose L(x_i) = 0 (section 2.7), so L^2 = L P L with P zeroing the
        // fixed rows; K P M^-1 K stays symmetric positive semi-definite.
        scratch.resize(n, 3);
        double* ss = scratch.data();
        const double* m = op->mass.data();
        const char* f = free.data();
        detail::for_each_k_row(*op, x, [=](int i, double s0, double s1, double s2) {
            const double inverse = f[i] && m[i] > 0 ? 1.0 / m[i] : 0.0;
            ss[3 * i] = s0 * inverse;
            ss[3 * i + 1] = s1 * inverse;
            ss[3 * i + 2] = s2 * inverse;
        });
        detail::for_each_k_row(*op, scratch, [=](int i, double s0, double s1, double s2) {
            ys[3 * i] = d[i] * xs[3 * i] + lambda * s0;
            ys[3 * i + 1] = d[i] * xs[3 * i + 1] + lambda * s1;
            ys[3 * i + 2] = d[i] * xs[3 * i + 2] + lambda * s2;
        });
    }
}

std::vector<double> LinearSystem::jacobi_diagonal() const {
    const int n = op->size();
    std::vector<double> d(n);
    for (int i = 0; i < n; ++i) {
        double extra = 0;
        if (order == 1) {
            extra = -op->diagonal(i);
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
    }
    return d;
}

SolveStats solve(const LinearSystem& system, Positions& x, const SolveSettings& settings) {
    const int n = system.op->size();
    const int threads = system.op->threads;
    (void)threads;
    const std::vector<char>& free = system.free;
    const char* f = free.data();
    const double* d = system.diagonal.data();
    Positions b(n, 3), r(n, 3), p(n, 3), q(n, 3), scratch(n, 3);

    // b = D x_old. The right-hand side actually solved on the free rows includes the fixed
    // values' coupling, b_f - A_fc x_c; its norm (or b's, whichever is larger) scales the
    // stopping rule. Without fixed rows the two are the same and the product is skipped.
    bool any_fixed = false;
    for (int i = 0; i < n; ++i) {
        b.row(i) = d[i] * x.row(i);
        any_fixed = any_fixed || !f[i];
    }
    const Column3 norm_b = column_norms(b, free, settings.norm, threads);
    Column3 scale = norm_b;
    if (any_fixed) {
        p.setZero();
        for (int i = 0; i < n; ++i)
            if (!f[i]) p.row(i) = x.row(i);
        system.apply(p, q, scratch);
        r = b - q;
        const Column3 norm_eb = column_norms(r, free, settings.norm, threads);
        for (int c = 0; c < 3; ++c) scale[c] = std::max(norm_b[c], norm_eb[c]);
    }

    const std::vector<double> jacobi = system.jacobi_diagonal();
    std::vector<double> inverse_jacobi(n);
    for (int i = 0; i < n; ++i) inverse_jacobi[i] = 1.0 / jacobi[i];
    const double* inv = inverse_jacobi.data();

    auto converged_column = [&](const Column3& rn, int c) {
        return scale[c] > 0 ? rn[c] <= settings.tolerance * scale[c] : rn[c] == 0;
    };
    auto relative = [&](const Column3& rn) {
        double worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, scale[c] > 0 ? rn[c] / scale[c] : rn[c]);
        return worst;
    };
    auto check_finite = [&](double v, int iteration) {
        if (!std::isfinite(v))
            throw Error("the linear solve produced a non-finite value at iteration " +
                        std::to_string(iteration) +
                        "; the input is too degenerate for this operator (try the umbrella "
                        "operator, or repair the mesh first)");
    };
    Column3 initial{0, 0, 0};
    bool have_initial = false;
    auto fraction_done = [&](const Column3& now) {
        double worst = 1;
        for (int c = 0; c < 3; ++c) {
            const double goal = settings.tolerance * scale[c];
            if (!(now[c] > goal) || !(initial[c] > goal)) continue;
            worst = std::min(worst, std::log(initial[c] / now[c]) / std::log(initial[c] / goal));
        }
        return std::max(0.0, worst);
    };

    // CG's recursively updated residual drifts from the true one on ill-conditioned systems (the
    // L^2 forms), so convergence is confirmed on the true residual, restarting from the current
    // iterate when it disagrees.
    constexpr int kMaxRestarts = 8;
    SolveStats stats;
    std::array<bool, 3> active{false, false, false};
    Column3 rn{0, 0, 0};
    for (int restart = 0;; ++restart) {
        system.apply(x, q, scratch);
        r = b - q;
        rn = column_norms(r, free, settings.norm, threads);
        for (int c = 0; c < 3; ++c) {
            check_finite(rn[c], stats.iterations);
            active[c] = !converged_column(rn, c);
        }
        if (!have_initial) {
            initial = rn;
            have_initial = true;
        }
        if (!(active[0] || active[1] || active[2]) || restart == kMaxRestarts ||
            stats.iterations >= settings.max_iterations)
            break;

        // p = z = J^-1 r, rz = r.z
        double* ps = p.data();
        double* rs = r.data();
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) ps[3 * i + c] = f[i] ? rs[3 * i + c] * inv[i] : 0.0;
        Column3 rz = column_dots(r, p, free, threads);

        while ((active[0] || active[1] || active[2]) &&
               stats.iterations < settings.max_iterations) {
            ++stats.iterations;
            system.apply(p, q, scratch);
            const Column3 pq = column_dots(p, q, free, threads);
            double alpha[3] = {0, 0, 0};
            for (int c = 0; c < 3; ++c)
                if (active[c]) {
                    alpha[c] = rz[c] / pq[c];
                    check_finite(alpha[c], stats.iterations);
                }
            // One pass: x += alpha p, r -= alpha q, the residual norms and r.z with z = J^-1 r.
            double* xs = x.data();
            const double* qs = q.data();
            const double a0 = alpha[0], a1 = alpha[1], a2 = alpha[2];
            double n0 = 0, n1 = 0, n2 = 0, m0 = 0, m1 = 0, m2 = 0, z0 = 0, z1 = 0, z2 = 0;
            FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) \
                           if(threads > 1) reduction(+ : n0, n1, n2, z0, z1, z2) \
                           reduction(max : m0, m1, m2))
            for (int i = 0; i < n; ++i) {
                if (!f[i]) continue;
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
                n0 += ri[0] * ri[0];
                n1 += ri[1] * ri[1];
                n2 += ri[2] * ri[2];
                m0 = std::max(m0, std::abs(ri[0]));
                m1 = std::max(m1, std::abs(ri[1]));
                m2 = std::max(m2, std::abs(ri[2]));
                z0 += ri[0] * ri[0] * inv[i];
                z1 += ri[1] * ri[1] * inv[i];
                z2 += ri[2] * ri[2] * inv[i];
            }
            rn = settings.norm == ResidualNorm::L2
                     ? Column3{std::sqrt(n0), std::sqrt(n1), std::sqrt(n2)}
                     : Column3{m0, m1, m2};
            for (int c = 0; c < 3; ++c) {
                check_finite(rn[c], stats.iterations);
                if (active[c] && converged_column(rn, c)) active[c] = false;
            }
            if (settings.progress) settings.progress(fraction_done(rn));
            if (!(active[0] || active[1] || active[2])) break;
            // p = J^-1 r + beta p on the columns still iterating.
            const Column3 rz_new{z0, z1, z2};
            double beta[3] = {0, 0, 0};
            double keep[3] = {0, 0, 0};  // 1 where the column stays put
            for (int c = 0; c < 3; ++c) {
                if (active[c]) {
                    beta[c] = rz_new[c] / rz[c];
                    check_finite(beta[c], stats.iterations);
                    rz[c] = rz_new[c];
                } else {
                    keep[c] = 1;
                }
            }
            FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
            for (int i = 0; i < n; ++i) {
                if (!f[i]) continue;
                for (int c = 0; c < 3; ++c) {
                    double& pc = ps[3 * i + c];
                    pc = keep[c] != 0 ? pc : rs[3 * i + c] * inv[i] + beta[c] * pc;
                }
            }
        }
    }
    stats.residual = relative(rn);
    stats.converged = !(active[0] || active[1] || active[2]);
    return stats;
}

}  // namespace fairing
