#include "fairing/solver.h"

#include <array>
#include <cmath>
#include <string>

namespace fairing {
namespace {

using Column3 = std::array<double, 3>;

Column3 column_norms(const Positions& v, const std::vector<char>& free, ResidualNorm norm) {
    Column3 out{0, 0, 0};
    const double* d = v.data();
    for (int i = 0; i < static_cast<int>(v.rows()); ++i) {
        if (!free[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double a = d[3 * i + c];
            if (norm == ResidualNorm::L2) out[c] += a * a;
            else out[c] = std::max(out[c], std::abs(a));
        }
    }
    if (norm == ResidualNorm::L2)
        for (double& o : out) o = std::sqrt(o);
    return out;
}

Column3 column_dots(const Positions& a, const Positions& b, const std::vector<char>& free) {
    Column3 out{0, 0, 0};
    const double* pa = a.data();
    const double* pb = b.data();
    for (int i = 0; i < static_cast<int>(a.rows()); ++i) {
        if (!free[i]) continue;
        out[0] += pa[3 * i] * pb[3 * i];
        out[1] += pa[3 * i + 1] * pb[3 * i + 1];
        out[2] += pa[3 * i + 2] * pb[3 * i + 2];
    }
    return out;
}

void zero_fixed_rows(Positions& v, const std::vector<char>& free) {
    for (int i = 0; i < static_cast<int>(v.rows()); ++i)
        if (!free[i]) v.row(i).setZero();
}

}  // namespace

void LinearSystem::apply(const Positions& x, Positions& y, Positions& scratch) const {
    const int n = op->size();
    if (order == 1) {
        op->apply_k(x, y);
        for (int i = 0; i < n; ++i) y.row(i) = diagonal[i] * x.row(i) - lambda_dt * y.row(i);
    } else {
        // Hard constraints impose L(x_i) = 0 (section 2.7), so L^2 = L P L with P zeroing the
        // fixed rows; K P M^-1 K stays symmetric positive semi-definite.
        op->apply_l(x, scratch);
        for (int i = 0; i < n; ++i)
            if (!free[i]) scratch.row(i).setZero();
        op->apply_k(scratch, y);
        for (int i = 0; i < n; ++i) y.row(i) = diagonal[i] * x.row(i) + lambda_dt * y.row(i);
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
    const std::vector<char>& free = system.free;
    Positions b(n, 3), r(n, 3), z(n, 3), p(n, 3), q(n, 3), scratch(n, 3);

    for (int i = 0; i < n; ++i) b.row(i) = system.diagonal[i] * x.row(i);
    // The right-hand side actually solved on the free rows includes the fixed values' coupling:
    // b_f - A_fc x_c. Its norm (or b's, whichever is larger) scales the stopping rule.
    Positions x_fixed_only = Positions::Zero(n, 3);
    for (int i = 0; i < n; ++i)
        if (!free[i]) x_fixed_only.row(i) = x.row(i);
    system.apply(x_fixed_only, q, scratch);
    Positions effective_b = b - q;
    const Column3 norm_b = column_norms(b, free, settings.norm);
    const Column3 norm_eb = column_norms(effective_b, free, settings.norm);
    Column3 scale;
    for (int c = 0; c < 3; ++c) scale[c] = std::max(norm_b[c], norm_eb[c]);

    const std::vector<double> jacobi = system.jacobi_diagonal();
    auto precondition = [&](const Positions& in, Positions& out) {
        for (int i = 0; i < n; ++i) out.row(i) = in.row(i) / jacobi[i];
    };

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
        zero_fixed_rows(r, free);
        rn = column_norms(r, free, settings.norm);
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
        precondition(r, z);
        p = z;
        Column3 rz = column_dots(r, z, free);
        while ((active[0] || active[1] || active[2]) &&
               stats.iterations < settings.max_iterations) {
            ++stats.iterations;
            system.apply(p, q, scratch);
            zero_fixed_rows(q, free);
            const Column3 pq = column_dots(p, q, free);
            Column3 alpha{0, 0, 0};
            for (int c = 0; c < 3; ++c)
                if (active[c]) {
                    alpha[c] = rz[c] / pq[c];
                    check_finite(alpha[c], stats.iterations);
                }
            double* xs = x.data();
            double* rs = r.data();
            const double* ps = p.data();
            const double* qs = q.data();
            for (int i = 0; i < n; ++i) {
                if (!free[i]) continue;
                for (int c = 0; c < 3; ++c) {
                    xs[3 * i + c] += alpha[c] * ps[3 * i + c];
                    rs[3 * i + c] -= alpha[c] * qs[3 * i + c];
                }
            }
            rn = column_norms(r, free, settings.norm);
            for (int c = 0; c < 3; ++c) {
                check_finite(rn[c], stats.iterations);
                if (active[c] && converged_column(rn, c)) active[c] = false;
            }
            if (settings.progress) settings.progress(fraction_done(rn));
            if (!(active[0] || active[1] || active[2])) break;
            precondition(r, z);
            const Column3 rz_new = column_dots(r, z, free);
            double* zs = z.data();
            double* pw = p.data();
            for (int c = 0; c < 3; ++c) {
                if (!active[c]) continue;
                const double beta = rz_new[c] / rz[c];
                check_finite(beta, stats.iterations);
                for (int i = 0; i < n; ++i) pw[3 * i + c] = zs[3 * i + c] + beta * pw[3 * i + c];
                rz[c] = rz_new[c];
            }
        }
    }
    stats.residual = relative(rn);
    stats.converged = !(active[0] || active[1] || active[2]);
    return stats;
}

}  // namespace fairing
