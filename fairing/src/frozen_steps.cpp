// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "frozen_steps.h"

#include "fairing/invariants.h"
#include "complex_factor.h"
#include "geometry.h"
#include "kernels.h"
#include "lanczos_filter.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fairing {
namespace detail {
namespace {

using Column3 = std::array<double, 3>;

// The first pass stops when the coefficients move by less than kSafety times the goal: the
// difference between iterates estimates the error of the older one, and Lanczos may stall for
// a few steps before converging again.
constexpr double kSafety = 0.1;
constexpr int kCheckEvery = 4;

// T_k of one column: diagonal a, off-diagonal b (b[j] couples j and j + 1).
struct Tridiagonal {
    std::vector<double> a, b;
};

// |u| phi(T) e1: the coefficients of the Lanczos vectors in x_0 - x_s (frozen_steps.h,
// lanczos_filter.h). With `partial`, also those of x_0 - x_m for m = 1..s-1.
std::vector<double> coefficients(const Tridiagonal& t, double beta0, double lambda, int steps,
                                 int power, std::vector<std::vector<double>>* partial) {
    const int k = static_cast<int>(t.a.size());
    const std::size_t first = partial ? partial->size() : 0;
    std::vector<double> sum = implicit_steps_filter(t.a, t.b, k, lambda, steps, power, nullptr,
                                                    partial);
    for (double& v : sum) v *= beta0;
    if (partial)
        for (std::size_t m = first; m < partial->size(); ++m)
            for (double& v : (*partial)[m]) v *= beta0;
    return sum;
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0;
    for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
        const double e = (i < a.size() ? a[i] : 0.0) - (i < b.size() ? b[i] : 0.0);
        d += e * e;
    }
    return std::sqrt(d);
}

double norm(const std::vector<double>& a) { return distance(a, {}); }

// What the second pass adds up: acc += c_j z_j, and for the intermediate results X_{m+1}
// (m = 0..s-2, interleaved per vertex) either
// - single precision (first choice: half the memory and traffic), the differences
//   kept[m] += (c^(m+1)_j - c_j) z_j, so that X_{m+1} = X_s - kept[m] is rounded relative to
//   |X_{m+1} - X_s|, not to the positions; or
// - double precision, kept[m] += c^(m+1)_j z_j while j < end[m] (X_{m+1} = x_0 - kept[m]):
//   fewer steps filter more smoothly and their coefficients decay sooner.
struct Accumulation {
    std::array<const std::vector<double>*, 3> final{};
    std::array<const std::vector<std::vector<double>>*, 3> partial{};
    Positions* acc = nullptr;
    std::vector<double>* kept = nullptr;
    std::vector<float>* kept_single = nullptr;
    int kept_steps = 0;
    std::vector<int> end;  // double precision only; increasing in m
    // Step j's coefficients, [c] for acc and [3 (m + 1) + c] for kept[m], set by at(), and the
    // first kept[m] still accumulating.
    std::vector<double> step;
    int first = 0;

    void at(int j) {
        step.assign(3 * (kept_steps + 1), 0.0);
        while (!kept_single && first < kept_steps && j >= end[first]) ++first;
        for (int c = 0; c < 3; ++c) {
            const std::vector<double>& f = *final[c];
            step[c] = j < static_cast<int>(f.size()) ? f[j] : 0.0;
            const double minus = kept_single ? step[c] : 0.0;
            for (int m = first; m < kept_steps; ++m) {
                const std::vector<double>& p = (*partial[c])[m];
                step[3 * (m + 1) + c] = (j < static_cast<int>(p.size()) ? p[j] : 0.0) - minus;
            }
        }
    }
};

// The shortest prefix of `c` whose tail has a norm <= goal.
int prefix(const std::vector<double>& c, double goal) {
    double tail = 0;
    for (int j = static_cast<int>(c.size()) - 1; j >= 0; --j) {
        tail += c[j] * c[j];
        if (std::sqrt(tail) > goal) return j + 1;
    }
    return 0;
}

// The Lanczos process on G (or G1), three columns at once, in z = D^-1/2 v form: G v becomes
// D^-1 C z, products need no scaling, and x_s = x_0 - sum_j c_j z_j.
class Lanczos {
public:
    Lanczos(const LinearSystem& system, bool squared) : system_(system) {
        const int n = system.op->size();
        g_.op = system.op;
        g_.free = system.free;
        // No diagonal: A x with D = 0 and lambda_dt = 1 is C x (without 8 bytes per vertex of
        // zeros: LinearSystem::diagonal).
        g_.lambda_dt = 1;
        g_.order = squared ? 1 : system.order;
        a_.resize(n, 3);
        b_.resize(n, 3);
        q_.resize(n, 3);
    }

    // B = D^-1 (C x_0) on the free rows (the start, not yet normalized); returns |u| per column.
    Column3 start(const Positions& x0) {
        LinearSystem c = g_;
        c.order = system_.order;
        Positions scratch;
        c.apply(x0, q_, scratch);
        const char* f = system_.free.data();
        const double* d = system_.diagonal.data();
        const int n = system_.op->size();
        const Column3 squares = blocked_sum<3>(n, system_.op->threads, [&](int i, double* s) {
            for (int col = 0; col < 3; ++col) {
                a_(i, col) = 0;
                b_(i, col) = f[i] ? q_(i, col) / d[i] : 0.0;
                s[col] += q_(i, col) * b_(i, col);
            }
        });
        for (int col = 0; col < 3; ++col) {
            norm_[col] = std::sqrt(squares[col]);
            previous_[col] = 0;
        }
        return norm_;
    }

    // One step: returns alpha_j per column, and sets norm() to |w_{j+1}| (0 for a column whose
    // Krylov space is exhausted: it stays at zero).
    Column3 step(const Accumulation* accumulate) {
        const Column3 bq = g_.apply_dot(b_, q_, scratch_);
        Column3 alpha{0, 0, 0}, inverse{0, 0, 0};
        for (int c = 0; c < 3; ++c)
            if (norm_[c] > 0) {
                inverse[c] = 1 / norm_[c];
                alpha[c] = bq[c] * inverse[c] * inverse[c];
            }
        const Column3 squares = update(alpha, inverse, accumulate);
        for (int c = 0; c < 3; ++c) {
            previous_[c] = inverse[c] > 0 ? std::sqrt(squares[c]) : 0.0;
            norm_[c] = previous_[c];
        }
        a_.swap(b_);
        return alpha;
    }

    const Column3& norm() const { return norm_; }

private:
    // z_j = B / |B|; w = D^-1 C z_j - alpha z_j - beta_{j-1} z_{j-1} into A, z_j into B;
    // returns |w|^2 in the D-norm. Fixed rows stay zero.
    Column3 update(const Column3& alpha, const Column3& inverse, const Accumulation* acc) {
        const int n = system_.op->size();
        const char* f = system_.free.data();
        const double* d = system_.diagonal.data();
        double* as = a_.data();
        double* bs = b_.data();
        const double* qs = q_.data();
        const Column3 beta = previous_;
        const double* step = acc ? acc->step.data() : nullptr;
        double* sum = acc ? acc->acc->data() : nullptr;
        double* kept = acc && acc->kept ? acc->kept->data() : nullptr;
        float* single = acc && acc->kept_single ? acc->kept_single->data() : nullptr;
        const int kept_columns = acc ? 3 * acc->kept_steps : 0;
        return blocked_sum<3>(n, system_.op->threads, [&](int i, double* s) {
            if (!f[i]) return;
            double z[3];
            for (int c = 0; c < 3; ++c) {
                z[c] = bs[3 * i + c] * inverse[c];
                const double w = qs[3 * i + c] * inverse[c] / d[i] - alpha[c] * z[c] -
                                 beta[c] * as[3 * i + c];
                as[3 * i + c] = w;
                bs[3 * i + c] = z[c];
                s[c] += d[i] * w * w;
            }
            if (!step) return;
            for (int c = 0; c < 3; ++c) sum[3 * i + c] += step[c] * z[c];
            if (single) {
                float* k = single + static_cast<std::size_t>(i) * kept_columns;
                for (int e = 0; e < kept_columns; e += 3) {
                    k[e] += static_cast<float>(step[3 + e] * z[0]);
                    k[e + 1] += static_cast<float>(step[4 + e] * z[1]);
                    k[e + 2] += static_cast<float>(step[5 + e] * z[2]);
                }
                return;
            }
            double* k = kept + static_cast<std::size_t>(i) * kept_columns;
            for (int e = 3 * acc->first; e < kept_columns; e += 3) {
                k[e] += step[3 + e] * z[0];
                k[e + 1] += step[4 + e] * z[1];
                k[e + 2] += step[5 + e] * z[2];
            }
        });
    }

    const LinearSystem& system_;
    LinearSystem g_;
    Positions a_, b_, q_, scratch_;
    Column3 norm_{0, 0, 0}, previous_{0, 0, 0};
};

// |D^1/2 x|_free per column: the scale of the stopping rule.
Column3 scale_of(const LinearSystem& system, const Positions& x) {
    const char* f = system.free.data();
    const double* d = system.diagonal.data();
    const Column3 s = blocked_sum<3>(system.op->size(), system.op->threads, [&](int i, double* a) {
        if (!f[i]) return;
        for (int c = 0; c < 3; ++c) a[c] += d[i] * x(i, c) * x(i, c);
    });
    return {std::sqrt(s[0]), std::sqrt(s[1]), std::sqrt(s[2])};
}

struct FirstPass {
    bool converged = false;
    int steps = 0;
    double error = 0;
    std::array<Tridiagonal, 3> t;
    Column3 beta0{0, 0, 0};
    Column3 scale{0, 0, 0};
};

// Builds T_k until the coefficients settle (see frozen_steps.h), or gives up.
FirstPass first_pass(const FrozenProblem& p, Lanczos& lanczos, const Positions& x0,
                     bool squared) {
    FirstPass out;
    const double lambda = p.system->lambda_dt;
    out.beta0 = lanczos.start(x0);
    const Column3 scale = scale_of(*p.system, x0);
    out.scale = scale;
    std::array<std::vector<double>, 3> last;
    Column3 first_error{0, 0, 0};
    std::array<bool, 3> live{};
    for (int c = 0; c < 3; ++c) live[c] = out.beta0[c] > 0;
    for (int j = 0; j < p.max_iterations; ++j) {
        const Column3 alpha = lanczos.step(nullptr);
        const Column3& next = lanczos.norm();
        for (int c = 0; c < 3; ++c) {
            if (!live[c]) continue;
            if (!std::isfinite(alpha[c]) || !std::isfinite(next[c])) return out;
            out.t[c].a.push_back(alpha[c]);
            if (next[c] > 0) out.t[c].b.push_back(next[c]);
            else live[c] = false;  // exhausted: T is exact
        }
        out.steps = j + 1;
        const bool exhausted = !live[0] && !live[1] && !live[2];
        if (out.steps % kCheckEvery != 0 && !exhausted) continue;
        double worst = 0;
        bool done = true;
        for (int c = 0; c < 3; ++c) {
            if (out.t[c].a.empty()) continue;
            Tridiagonal t = out.t[c];
            t.b.resize(t.a.size() - 1);
            const std::vector<double> y = coefficients(t, out.beta0[c], lambda, p.steps,
                                                      squared ? p.system->order : 1, nullptr);
            const double error = distance(y, last[c]);
            const double goal = kSafety * p.tolerance * std::max(scale[c], norm(y));
            if (first_error[c] == 0) first_error[c] = error;
            done = done && (error <= goal || !live[c]);
            worst = std::max(worst, error / std::max(scale[c], norm(y)));
            if (p.progress && error > goal && first_error[c] > goal)
                p.progress(0.5 * std::max(0.0, std::log(first_error[c] / error) /
                                                   std::log(first_error[c] / goal)));
            last[c] = y;
        }
        out.error = worst;
        if (done) {
            out.converged = true;
            return out;
        }
    }
    return out;
}

// Rescaling of one component after every step, replayed from X_1..X_s (frozen_steps.h) as
// x = g_s + a_s (X_s - g_s) + delta, delta = sum_k (a_{k-1} - a_k) (g_k - g_s): the form of
// restore_measure plus a translation made of small differences.
struct Rescaling {
    double a = 1;
    Vec3 delta = Vec3::Zero();
    // Rounding of delta: that of each X_k (intermediate()) times |a_{k-1} - a_k|.
    double rounding = 0;
};

constexpr double kRounding = 1e-14;

// The intermediate results, as the second pass kept them (see Accumulation).
struct Kept {
    const std::vector<double>* doubles = nullptr;
    const std::vector<float>* singles = nullptr;
    int lanczos_steps = 0;
};

// X_k into `work` (whose other rows hold x_0 = X_s) from x_0 (double) or X_s (single); returns
// the rounding of the largest entry of the kept vector (the rounding of X_k).
double intermediate(const FrozenProblem& p, const Kept& kept, int k, const Positions& x0,
                    const Positions& xs, Positions& work) {
    const int n = static_cast<int>(x0.rows());
    const int m = p.steps - 1;
    const char* f = p.system->free.data();
    double largest = 0;
    for (int i = 0; i < n; ++i)
        if (f[i])
            for (int c = 0; c < 3; ++c) {
                const std::size_t e = (static_cast<std::size_t>(i) * m + k - 1) * 3 + c;
                const double d = kept.singles ? (*kept.singles)[e] : (*kept.doubles)[e];
                work(i, c) = (kept.singles ? xs(i, c) : x0(i, c)) - d;
                largest = std::max(largest, std::abs(d));
            }
    // Double: ~1e-14 relative (sums of double products). Single: each of the Lanczos steps'
    // terms rounded to 2^-24, partial sums up to a few times the total.
    return largest * (kept.singles ? 4.0 * kept.lanczos_steps * 0x1p-24 : kRounding);
}

// Scale a_k and centroid g_k of X_k for one component; false if its measure is not positive.
bool measure(const FrozenProblem& p, std::size_t c, const Positions& x, double& a, Vec3& g) {
    const Component& comp = p.mesh->components()[p.rescaled[c]];
    const bool volume = comp.closed();
    const double ratio = p.target[c] / (volume ? component_volume(*p.mesh, comp, x)
                                               : component_area(*p.mesh, comp, x));
    if (!(ratio > 0) || !std::isfinite(ratio)) return false;
    a = std::pow(ratio, volume ? 1.0 / 3.0 : 0.5);
    g = component_centroid(*p.mesh, comp, x);
    return true;
}

// X_s = x_0 - acc, rescaled as the steps one by one would, into x; x is untouched when a
// measure stops being positive or the rounding of the replay could exceed a tenth of the
// tolerance.
enum class Restored { Yes, NotPositive, Rounding };

Restored restore_at_end(const FrozenProblem& p, const Positions& acc, const Kept& kept,
                        Positions& x) {
    const int s = p.steps;
    const char* f = p.system->free.data();
    const auto& components = p.mesh->components();
    Positions shape = x;
    for (int i = 0; i < shape.rows(); ++i)
        if (f[i]) shape.row(i) -= acc.row(i);
    const std::size_t count = p.rescaled.size();
    std::vector<Rescaling> r(count);
    std::vector<Vec3> g(count);
    for (std::size_t c = 0; c < count; ++c)
        if (!measure(p, c, shape, r[c].a, g[c])) return Restored::NotPositive;
    Positions work = count > 0 ? shape : Positions();
    std::vector<double> a_previous(count, 1.0);  // a_0 = 1
    for (int k = 1; k < s && count > 0; ++k) {
        const double rounding = intermediate(p, kept, k, x, shape, work);
        for (std::size_t c = 0; c < count; ++c) {
            double a;
            Vec3 centroid;
            if (!measure(p, c, work, a, centroid)) return Restored::NotPositive;
            const double step = a_previous[c] - a;
            r[c].delta += step * (centroid - g[c]);
            r[c].rounding += std::abs(step) * rounding;
            a_previous[c] = a;
        }
    }
    for (std::size_t c = 0; c < count; ++c) {
        double size = 0;
        for (int v : components[p.rescaled[c]].vertices) {
            const Vec3 y = g[c] + r[c].a * (row(shape, v) - g[c]) + r[c].delta;
            size = std::max(size, (y - g[c]).norm());
            shape.row(v) = y.transpose();
        }
        if (!(r[c].rounding <= 0.1 * p.tolerance * size)) return Restored::Rounding;
    }
    if (!shape.allFinite()) return Restored::NotPositive;
    x.swap(shape);
    return Restored::Yes;
}

// The second pass: replays the basis and returns x_0 - X_s in `sum`, the intermediate results in
// single or double precision as asked (see Accumulation).
void second_pass(const FrozenProblem& p, const FirstPass& first, Accumulation& acc, bool squared,
                 const Positions& x, Positions& sum, std::vector<double>& kept,
                 std::vector<float>& kept_single, bool single) {
    const std::size_t size = static_cast<std::size_t>(x.rows()) * 3 * acc.kept_steps;
    sum.setZero(x.rows(), 3);
    if (single) kept_single.assign(size, 0.0f);
    else kept.assign(size, 0.0);
    acc.acc = &sum;
    acc.kept = single || acc.kept_steps == 0 ? nullptr : &kept;
    acc.kept_single = single ? &kept_single : nullptr;
    acc.first = 0;
    Lanczos lanczos(*p.system, squared);
    lanczos.start(x);
    for (int j = 0; j < first.steps; ++j) {
        acc.at(j);
        lanczos.step(&acc);
        if (p.progress) p.progress(0.5 + 0.5 * (j + 1) / first.steps);
    }
}

}  // namespace

FrozenOutcome take_frozen_steps(const FrozenProblem& p, Positions& x) {
    FrozenOutcome outcome;
    const bool squared = powers_first_order(*p.system);
    FirstPass first;
    {
        Lanczos lanczos(*p.system, squared);  // its vectors go before the second pass's
        first = first_pass(p, lanczos, x, squared);
    }
    outcome.lanczos_steps = first.steps;
    outcome.products = first.steps + 1;
    outcome.error = first.error;
    if (!first.converged) return outcome;

    const int kept_steps = p.rescaled.empty() ? 0 : p.steps - 1;
    std::array<std::vector<double>, 3> final;
    std::array<std::vector<std::vector<double>>, 3> partial;
    Accumulation acc;
    for (int c = 0; c < 3; ++c) {
        Tridiagonal t = first.t[c];
        if (!t.a.empty()) t.b.resize(t.a.size() - 1);
        final[c] = coefficients(t, first.beta0[c], p.system->lambda_dt, p.steps,
                                squared ? p.system->order : 1,
                                kept_steps > 0 ? &partial[c] : nullptr);
        partial[c].resize(kept_steps, std::vector<double>());
        acc.final[c] = &final[c];
        acc.partial[c] = &partial[c];
    }
    acc.kept_steps = kept_steps;
    // Double precision: kept[m] to the accuracy of the result, as its error enters x_s only
    // multiplied by a difference of two rescalings.
    acc.end.assign(kept_steps, 0);
    for (int m = 0; m < kept_steps; ++m)
        for (int c = 0; c < 3; ++c)
            acc.end[m] = std::max(acc.end[m], prefix(partial[c][m], kSafety * p.tolerance *
                                                                        first.scale[c]));
    for (int m = 1; m < kept_steps; ++m) acc.end[m] = std::max(acc.end[m], acc.end[m - 1]);
    Positions sum;
    std::vector<double> kept;
    std::vector<float> kept_single;
    // Single precision first; again in double when its rounding could reach the tolerance.
    for (bool single = kept_steps > 0;; single = false) {
        second_pass(p, first, acc, squared, x, sum, kept, kept_single, single);
        outcome.products += first.steps + 1;
        Kept k;
        k.doubles = &kept;
        k.singles = single ? &kept_single : nullptr;
        k.lanczos_steps = first.steps;
        const Restored restored = restore_at_end(p, sum, k, x);
        outcome.taken = restored == Restored::Yes;
        if (restored != Restored::Rounding || !single) return outcome;
        kept_single = std::vector<float>();
    }
}

}  // namespace detail
}  // namespace fairing
