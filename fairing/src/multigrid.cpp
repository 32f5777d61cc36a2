// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "multigrid.h"

#include "kernels.h"
#include "sweeps.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace fairing {
namespace detail {
namespace {

// Rows of the coarsest level, solved by dense LU (a 300 x 300 complex LU is a few ms).
constexpr int kCoarsest = 300;
// A stalled coarsening may leave more rows than a dense LU affords: that level is then
// smoothed (coarse_sweeps() Jacobi sweeps: still a symmetric operator) instead of solved.
constexpr int kDenseLimit = 3000;
// Jacobi sweeps before and after the coarse correction on the levels below the finest (where
// they are cheap: the first coarse level has about 1/9 of the rows): measured on the 1.2 M-face
// bunny (curvature L^2 22.5) 35 COCG iterations against 39 with one sweep. The complex cycle
// takes four: its coarse correction was the weak part on strong steps (the cycles kept falling
// with more sweeps: 2 / 3 / 4 / 6 / 8 sweeps, curvature L^2 360, 1 M-face torus 37 / 34 / 30 /
// 28 / 26, 1.2 M-face bunny 28 / 24 / 22 / 21 / 20). Four against two, one thread, CPU seconds
// (cycles): the one-click steps on the torus, umbrella 1.1e5 3.14 -> 2.94 s (30 -> 24),
// scale-dependent 4317 3.17 -> 2.93 (28 -> 23), curvature 36780 4.58 -> 4.69 (43 -> 39); on the
// bunny umbrella 197 2.82 -> 2.72 (15 -> 13), scale-dependent 22.1 3.96 -> 3.33 (23 -> 17),
// curvature 202 4.25 -> 3.95 (25 -> 21), curvature 360 4.58 -> 4.21 (torus 4.01 -> 3.73). The
// real cycle (first order) keeps two: four left its cycles as they were (torus and bunny at
// 4.74 and 75.84: 10, 15, 9, 12) and cost 1-8 % more time.
constexpr int kCoarseSweeps = 2;
constexpr int kComplexCoarseSweeps = 4;
constexpr int kMaxLevels = 12;
// Coarsening that keeps more than this fraction of the rows has stalled: stop there.
constexpr double kStall = 0.8;
// Weight of the Jacobi smoother times rho, a bound on rho(D_A^-1 A) (jacobi_bound): below 2, so
// a sweep contracts every mode of the real SPD matrix (w lambda_max <= 1.85). The bound used to be
// the row-scaled Gershgorin bound alone, 40-80 % high on the stiffness-dominated levels (4.05
// against a power-iteration estimate of 2.18 on the finest level of the 1.2 M-face bunny at
// curvature 75.84), with weight 1.7. Iterations with the tighter bound and these weights against
// before (1 thread, preconditioner=multigrid, curvature; 2026-11-25): bunny, first order at
// 4.74 / 75.84: 11 / 16 against 14 / 20, L^2 at 22.5 / 360: 26 / 35 against 31 / 44; 1 M-face
// torus 13 / 21 against 15 / 24 and 27 / 53 against 30 / 51; on the study's armadillo (n0.5),
// bunny 75 k, camel (iso0.25), two-density sphere and fandisk (n0.5), first order at 4.74 / 75.84
// / 1213 and L^2 at 22.5 / 360 / 5760, 10-25 % fewer in all 30 cases but two equal ones (camel:
// 24 / 41 / 60 and 59 / 77 / 91 against 30 / 53 / 78 and 68 / 93 / 114). The complex smoother
// keeps 1.7: 2.0 took the torus' L^2 at 360 from 53 to 94 iterations, 1.5 the bunny's from 35
// to 38. (That was with the bound on mass - a stiff; on the complex moduli (session 17) the
// weight matters little: 1.7 / 1.85 / 2.0 / 2.3 gave 23 / 22 / 22 / 24, 28 / 28 / 27 / 26 and
// 30 at every weight for curvature L^2 at 90 / 360 / 5000 on the 1 M-face torus, 20-21, 22 and
// 26-28 on the 1.2 M-face bunny.)
constexpr double kSmootherWeight = 1.85;
constexpr double kComplexSmootherWeight = 1.7;
// Strength threshold of the coarse levels (on the finest level every mesh neighbour is strong:
// the operator's own graph), halved per level as Vanek, Mandel and Brezina suggest.
constexpr double kTheta = 0.0;

// A matrix in compressed rows with its mass and stiffness parts (set-up only).
struct Split {
    std::vector<int> start{0}, col;
    std::vector<double> mass, stiff;
};

// Compressed rows with one value per entry: the prolongator and its transpose, whose entries
// need no more than float precision (the Galerkin products use the same rounded values, so
// the cycle stays exactly symmetric) and so take 8 bytes instead of 12.
struct Csr {
    std::vector<int> start{0}, col;
    std::vector<float> val;
};

}  // namespace

struct Multigrid::Impl {
    struct Level {
        int n = 0;
        int threads = 1;
        // Matrix of levels >= 1 (level 0 is the operator itself): B = re (+ i im).
        std::vector<int> start, col;
        std::vector<double> re, im;
        // Damped inverse diagonal of B: w / B_ii (Complex: re, im pairs); 0 on excluded rows.
        std::vector<double> inv;
        Csr p, r;  // prolongation from the next level and restriction R = P^T
        std::vector<double> b, x, res;  // work vectors, width W per row (level 0: the caller's)
    };

    const SparseOperator& op;
    const std::vector<double>& diagonal;
    const std::vector<char>& free;
    double a;
    Kind kind;
    int width;
    std::vector<Level> levels;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_real;
    Eigen::PartialPivLU<Eigen::MatrixXcd> lu_complex;
    bool dense = false;  // the coarsest level is solved by LU (else smoothed)
    // Level 0 smoothed by block Gauss-Seidel (sweeps.h; its inv then undamped) in rows of
    // gauss_seidel_block, else by damped Jacobi. Asked for by the constructor, kept by build()
    // where it applies.
    bool gauss_seidel = true;
    int gauss_seidel_block = 0;
    double* fine_work = nullptr;  // level 0's residual vector, lent by the caller of apply()

    double* work(Level& level, int l) { return l == 0 ? fine_work : level.res.data(); }
    double smoother_weight() const {
        return kind == Kind::Complex ? kComplexSmootherWeight : kSmootherWeight;
    }
    int coarse_sweeps() const {
        return kind == Kind::Complex ? kComplexCoarseSweeps : kCoarseSweeps;
    }

    Impl(const SparseOperator& o, const std::vector<double>& d, const std::vector<char>& f,
         double a_, Kind k)
        : op(o), diagonal(d), free(f), a(a_), kind(k), width(k == Kind::Real ? 3 : 6) {}

    template <class Row>
    Split coarsen(int n, const Row& row, const std::vector<double>& adiag, double theta,
                  Level& fine, double* omega_out);
    void build();
    void finish_level(Level& level, Split m, double omega);
    void coarsest(const Level& level);

    template <int W, bool C, class X>
    void row_product(const Level& level, int l, int i, const X& x, double* y) const;
    template <int W, bool C>
    void residual(const Level& level, int l, const double* b, const double* x,
                  double* res) const;
    template <int W, bool C>
    void smooth(Level& level, int l, const double* b, double* x);
    template <int W, bool C>
    void cycle(int l, const double* b, double* x, double* dots);
    template <int W, bool C>
    void cycle_gauss_seidel(const double* b, double* x, double* dots);
    template <int W, bool C>
    void restrict_to(const Level& level, const double* res, Level& next) const;
    template <int W, bool C>
    void solve_coarsest(const Level& level, const double* b, double* x) const;
};

namespace {

// agg[i]: aggregate of row i, -1 for excluded rows (not free, or A_ii <= 0). Greedy in three
// passes (Vanek et al. 1996, section 3): roots whose strong neighbours are all free of any
// aggregate take them; the rest join a neighbouring aggregate of the first pass; leftovers
// form aggregates of their own. Returns the number of aggregates.
template <class Strong>
int aggregate(int n, const std::vector<double>& adiag, const Strong& strong,
              std::vector<int>& agg) {
    constexpr int kNone = -2;
    agg.assign(static_cast<std::size_t>(n), kNone);
    for (int i = 0; i < n; ++i)
        if (!(adiag[i] > 0)) agg[i] = -1;
    int count = 0;
    for (int i = 0; i < n; ++i) {
        if (agg[i] != kNone) continue;
        bool all_free = true;
        strong(i, [&](int j) { all_free = all_free && agg[j] == kNone; });
        if (!all_free) continue;
        agg[i] = count;
        strong(i, [&](int j) { agg[j] = count; });
        ++count;
    }
    std::vector<int> joined(agg);
    for (int i = 0; i < n; ++i) {
        if (agg[i] != kNone) continue;
        strong(i, [&](int j) {
            if (joined[i] == kNone && agg[j] >= 0) joined[i] = agg[j];
        });
    }
    agg.swap(joined);
    for (int i = 0; i < n; ++i) {
        if (agg[i] != kNone) continue;
        agg[i] = count;
        strong(i, [&](int j) {
            if (agg[j] == kNone) agg[j] = count;
        });
        ++count;
    }
    return count;
}

// R = P^T (nc columns), rows filled in increasing fine row: the same on every run.
Csr transpose(const Csr& p, int nc) {
    Csr r;
    r.start.assign(static_cast<std::size_t>(nc) + 1, 0);
    for (int c : p.col) ++r.start[c + 1];
    for (int c = 0; c < nc; ++c) r.start[c + 1] += r.start[c];
    r.col.resize(p.col.size());
    r.val.resize(p.val.size());
    std::vector<int> next(r.start.begin(), r.start.end() - 1);
    const int n = static_cast<int>(p.start.size()) - 1;
    for (int i = 0; i < n; ++i)
        for (int e = p.start[i]; e < p.start[i + 1]; ++e) {
            const int k = next[p.col[e]]++;
            r.col[k] = i;
            r.val[k] = p.val[e];
        }
    return r;
}

// An upper bound on rho(D_B^-1 B) for B = mass - a stiff (Real) or mass + i a stiff (Complex)
// given by row(i, fn) (diagonal included), D_B its diagonal: the smaller of Gershgorin's bound
// on the rows of D_B^-1 B and on the symmetrically scaled |D_B|^-1/2 B |D_B|^-1/2 (similar to it
// up to a unit diagonal phase), max_i sum_j |B_ij| / sqrt(|B_ii| |B_jj|). The second is the
// tighter where the diagonal varies (needles: 2.86 against 4.05 on the bunny above). The
// complex bound takes the moduli |m + i a s|: on a coarse level the mass couplings (P^T M P is
// not diagonal) and the stiffness ones have the same sign, so the real m - a s cancels where the
// level's stiffness matches its mass, and a bound from it set the complex smoother's weight up
// to several times too high there. Measured (curvature L^2, one step, 2 threads, V-cycle): on
// a 2.5 M-face jittered torus the cycles went 33 / 126 / 32 at time steps 300 / 850 / 3147 and
// 29 / 29 / 31 with the complex bound; on a 10 M-face one at 1012 from 588 to 46, and on a
// 40 M-face one at 1012 (its automatic strength) COCG stalled near 1e-5 instead of converging.
// Rows with adiag <= 0 are excluded.
template <class Row>
double jacobi_bound(int n, const Row& row, const std::vector<double>& adiag, double a,
                    Multigrid::Kind kind = Multigrid::Kind::Real) {
    const bool complex = kind == Multigrid::Kind::Complex;
    const auto modulus = [a, complex](double m, double s) {
        return complex ? std::hypot(m, a * s) : std::abs(m - a * s);
    };
    // |B_ii|: adiag itself for Real (mass - a stiff > 0 on the rows kept).
    std::vector<double> complex_diagonal;
    if (complex) {
        complex_diagonal.assign(static_cast<std::size_t>(n), 0.0);
        for (int i = 0; i < n; ++i)
            if (adiag[i] > 0)
                row(i, [&](int j, double m, double s) {
                    if (j == i) complex_diagonal[i] = modulus(m, s);
                });
    }
    const std::vector<double>& diagonal = complex ? complex_diagonal : adiag;
    double by_rows = 0, symmetric = 0;
    for (int i = 0; i < n; ++i) {
        if (!(adiag[i] > 0) || !(diagonal[i] > 0)) continue;
        double sum = 0, scaled = 0;
        row(i, [&](int j, double m, double s) {
            const double v = modulus(m, s);
            sum += v;
            if (adiag[j] > 0 && diagonal[j] > 0) scaled += v / std::sqrt(diagonal[i] * diagonal[j]);
        });
        by_rows = std::max(by_rows, sum / diagonal[i]);
        symmetric = std::max(symmetric, scaled);
    }
    return std::min(by_rows, symmetric);
}

// R B P in both parts (mass, stiffness), coarse row by coarse row (Gustavson, dense
// accumulators): each coarse row sums its entries in a fixed order.
template <class Row>
Split galerkin(int nc, const Csr& r, const Csr& p, const Row& row) {
    Split coarse;
    std::vector<double> acc_m(static_cast<std::size_t>(nc), 0.0), acc_s(acc_m);
    std::vector<int> mark(static_cast<std::size_t>(nc), -1), touched;
    for (int c = 0; c < nc; ++c) {
        touched.clear();
        for (int e = r.start[c]; e < r.start[c + 1]; ++e) {
            const int i = r.col[e];
            const double ri = r.val[e];  // the float entry, as the cycle applies it
            row(i, [&](int k, double m, double s) {
                for (int f = p.start[k]; f < p.start[k + 1]; ++f) {
                    const int b = p.col[f];
                    if (mark[b] != c) {
                        mark[b] = c;
                        touched.push_back(b);
                        acc_m[b] = acc_s[b] = 0;
                    }
                    acc_m[b] += ri * m * p.val[f];
                    acc_s[b] += ri * s * p.val[f];
                }
            });
        }
        for (int b : touched) {
            coarse.col.push_back(b);
            coarse.mass.push_back(acc_m[b]);
            coarse.stiff.push_back(acc_s[b]);
        }
        coarse.start.push_back(static_cast<int>(coarse.col.size()));
    }
    return coarse;
}

}  // namespace

// Aggregates, the smoothed prolongator (into fine.p, fine.r) and the Galerkin coarse matrix
// R B P (both parts) of a level whose rows row(i, fn) lists as fn(j, mass, stiff), diagonal
// included. adiag: diagonal of A = mass - a stiff. *omega_out: the smoother's weight.
template <class Row>
Split Multigrid::Impl::coarsen(int n, const Row& row, const std::vector<double>& adiag,
                               double theta, Level& fine, double* omega_out) {
    const double aa = a;
    const auto strong = [&](int i, auto&& fn) {
        if (!(adiag[i] > 0)) return;
        row(i, [&](int j, double m, double s) {
            if (j == i || !(adiag[j] > 0)) return;
            const double v = m - aa * s;
            if (std::abs(v) >= theta * std::sqrt(adiag[i] * adiag[j]) && v != 0) fn(j);
        });
    };
    std::vector<int> agg;
    const int nc = aggregate(n, adiag, strong, agg);
    const double rho = jacobi_bound(n, row, adiag, aa, kind);
    *omega_out = rho > 0 ? smoother_weight() / rho : 0.0;
    // The prolongator is smoothed with the filtered matrix A_F (Vanek, Mandel, Brezina 1996,
    // section 3): repelling couplings (A_ij > 0: negative cotangent weights across obtuse
    // angles) are lumped onto the diagonal, so A_F 1 = A 1 (constants stay exact) and no
    // interpolation weight gets the wrong sign from them. On the 1 M-face jittered torus (11 %
    // of A's entries repelling) curvature L^2 at 360 took 46 cycles with A, 37 with A_F; scans
    // and the other operators moved by at most two (multigrid.h).
    std::vector<double> filtered_diag(adiag);
    for (int i = 0; i < n; ++i) {
        if (!(adiag[i] > 0)) continue;
        row(i, [&](int j, double m, double s) {
            const double v = m - aa * s;
            if (j != i && v > 0) filtered_diag[i] += v;
        });
    }
    const auto filtered_row = [&](int i, auto&& fn) {
        row(i, [&](int j, double m, double s) {
            if (j == i) fn(j, filtered_diag[i], 0.0);
            else if (!(m - aa * s > 0)) fn(j, m, s);
        });
    };
    const double filtered_rho = jacobi_bound(n, filtered_row, filtered_diag, aa);
    const double omega = filtered_rho > 0 ? 4.0 / (3.0 * filtered_rho) : 0.0;
    // P = (I - w D_F^-1 A_F) P_tent, row by row (merged per aggregate).
    Csr& p = fine.p;
    std::vector<std::pair<int, double>> entries;
    for (int i = 0; i < n; ++i) {
        if (agg[i] >= 0) {
            entries.clear();
            entries.emplace_back(agg[i], 1.0);
            const double scale = omega / filtered_diag[i];
            filtered_row(i, [&](int j, double m, double s) {
                if (agg[j] >= 0) entries.emplace_back(agg[j], -scale * (m - aa * s));
            });
            std::sort(entries.begin(), entries.end(),
                      [](const std::pair<int, double>& x, const std::pair<int, double>& y) {
                          return x.first < y.first;
                      });
            for (std::size_t k = 0; k < entries.size();) {
                double v = 0;
                const int c = entries[k].first;
                for (; k < entries.size() && entries[k].first == c; ++k) v += entries[k].second;
                p.col.push_back(c);
                p.val.push_back(static_cast<float>(v));
            }
        }
        p.start.push_back(static_cast<int>(p.col.size()));
    }
    p.col.shrink_to_fit();
    p.val.shrink_to_fit();
    fine.r = transpose(p, nc);
    Split coarse = galerkin(nc, fine.r, p, row);
    coarse.col.shrink_to_fit();
    coarse.mass.shrink_to_fit();
    coarse.stiff.shrink_to_fit();
    return coarse;
}

// The matrix of a coarse level (B = mass - a stiff, or mass + i a stiff) and its smoother.
void Multigrid::Impl::finish_level(Level& level, Split m, double omega) {
    const int n = static_cast<int>(m.start.size()) - 1;
    level.n = n;
    level.threads = n >= kParallelRows ? op.threads : 1;
    const bool complex = kind == Kind::Complex;
    // In place: the mass part becomes re, the stiffness part im (or is folded into re).
    for (std::size_t e = 0; e < m.mass.size(); ++e) {
        if (complex) m.stiff[e] *= a;
        else m.mass[e] -= a * m.stiff[e];
    }
    level.re = std::move(m.mass);
    if (complex) level.im = std::move(m.stiff);
    std::vector<double>().swap(m.stiff);
    level.start = std::move(m.start);
    level.col = std::move(m.col);
    level.inv.assign(static_cast<std::size_t>(complex ? 2 * n : n), 0.0);
    for (int i = 0; i < n; ++i)
        for (int e = level.start[i]; e < level.start[i + 1]; ++e) {
            if (level.col[e] != i) continue;
            if (!complex) {
                if (level.re[e] > 0) level.inv[i] = omega / level.re[e];
                continue;
            }
            const double dr = level.re[e], di = level.im[e], d2 = dr * dr + di * di;
            if (d2 > 0) {
                level.inv[2 * i] = omega * dr / d2;
                level.inv[2 * i + 1] = -omega * di / d2;
            }
        }
    const std::size_t w = static_cast<std::size_t>(width) * n;
    level.b.assign(w, 0.0);
    level.x.assign(w, 0.0);
    level.res.assign(w, 0.0);
}

void Multigrid::Impl::build() {
    const int n = op.size();
    levels.reserve(kMaxLevels);
    levels.emplace_back();
    Level& fine = levels.back();
    fine.n = n;
    fine.threads = op.threads;
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = op.weight.data();
    const auto fine_row = [&](int i, auto&& fn) {
        if (!free[i]) return;
        double kii = 0;
        for (int e = start[i]; e < start[i + 1]; ++e) {
            kii -= weight[e];
            if (free[column[e]]) fn(column[e], 0.0, weight[e]);
        }
        fn(i, diagonal[i], kii);
    };
    std::vector<double> adiag(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i)
        if (free[i]) adiag[i] = diagonal[i] - a * op.diagonal(i);
    double omega = 0;
    Split coarse = coarsen(n, fine_row, adiag, 0.0, levels[0], &omega);
    // Level 0's smoother: the diagonal of B itself, damped for Jacobi.
    const bool complex = kind == Kind::Complex;
    gauss_seidel = gauss_seidel && gauss_seidel_applies(op);
    gauss_seidel_block = sweep_block_rows(n);
    if (gauss_seidel) omega = 1;
    fine.inv.assign(static_cast<std::size_t>(complex ? 2 * n : n), 0.0);
    for (int i = 0; i < n; ++i) {
        if (!(adiag[i] > 0)) continue;
        if (!complex) {
            fine.inv[i] = omega / adiag[i];
            continue;
        }
        const double dr = diagonal[i], di = a * op.diagonal(i), d2 = dr * dr + di * di;
        fine.inv[2 * i] = omega * dr / d2;
        fine.inv[2 * i + 1] = -omega * di / d2;
    }
    if (coarse.start.size() == 1) return;  // no free row: level 0 alone, smoothed
    double theta = kTheta;
    for (int l = 1;; ++l) {
        const int nc = static_cast<int>(coarse.start.size()) - 1;
        const int nf = levels[l - 1].n;
        levels.emplace_back();
        Split m = std::move(coarse);
        std::vector<double> cdiag(static_cast<std::size_t>(nc), 0.0);
        for (int i = 0; i < nc; ++i)
            for (int e = m.start[i]; e < m.start[i + 1]; ++e)
                if (m.col[e] == i) cdiag[i] = m.mass[e] - a * m.stiff[e];
        const auto coarse_row = [&m](int i, auto&& fn) {
            for (int e = m.start[i]; e < m.start[i + 1]; ++e) fn(m.col[e], m.mass[e], m.stiff[e]);
        };
        const bool last = nc <= kCoarsest || nc > kStall * nf || l + 1 == kMaxLevels;
        if (last) {
            const double rho = jacobi_bound(nc, coarse_row, cdiag, a, kind);
            const double last_w = rho > 0 ? smoother_weight() / rho : 0.0;
            finish_level(levels[l], std::move(m), last_w);
            coarsest(levels[l]);
            return;
        }
        coarse = coarsen(nc, coarse_row, cdiag, theta, levels[l], &omega);
        finish_level(levels[l], std::move(m), omega);
        theta *= 0.5;
    }
}

void Multigrid::Impl::coarsest(const Level& level) {
    const int n = level.n;
    dense = n <= kDenseLimit;
    if (!dense) return;
    if (kind == Kind::Complex) {
        Eigen::MatrixXcd dense = Eigen::MatrixXcd::Zero(n, n);
        for (int i = 0; i < n; ++i)
            for (int e = level.start[i]; e < level.start[i + 1]; ++e)
                dense(i, level.col[e]) = {level.re[e], level.im[e]};
        lu_complex.compute(dense);
        return;
    }
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int e = level.start[i]; e < level.start[i + 1]; ++e)
            dense(i, level.col[e]) = level.re[e];
    lu_real.compute(dense);
}

// (B x)_i on level l into y (W columns; C: complex pairs (c, 3 + c)); x(j, v) writes x_j to v.
template <int W, bool C, class X>
void Multigrid::Impl::row_product(const Level& level, int l, int i, const X& x,
                                  double* y) const {
    double xi[W], xj[W];
    if (l == 0) {
        // x is zero on the fixed rows, so sum_j w_ij (x_j - x_i) is (K_ff x)_i.
        x(i, xi);
        double k[W] = {};
        with_weights(weights_of(op), [&](const auto& w) {
            for (int e = op.row_start[i]; e < op.row_start[i + 1]; ++e) {
                x(op.column[e], xj);
                for (int c = 0; c < W; ++c) k[c] += w[e] * (xj[c] - xi[c]);
            }
        });
        const double d = diagonal[i];
        if constexpr (C) {
            for (int c = 0; c < 3; ++c) {
                y[c] = d * xi[c] - a * k[3 + c];
                y[3 + c] = d * xi[3 + c] + a * k[c];
            }
        } else {
            for (int c = 0; c < W; ++c) y[c] = d * xi[c] - a * k[c];
        }
        return;
    }
    for (int c = 0; c < W; ++c) y[c] = 0;
    for (int e = level.start[i]; e < level.start[i + 1]; ++e) {
        x(level.col[e], xj);
        const double re = level.re[e];
        if constexpr (C) {
            const double im = level.im[e];
            for (int c = 0; c < 3; ++c) {
                y[c] += re * xj[c] - im * xj[3 + c];
                y[3 + c] += re * xj[3 + c] + im * xj[c];
            }
        } else {
            for (int c = 0; c < W; ++c) y[c] += re * xj[c];
        }
    }
}

namespace {

// out = inv_i g (the damped inverse diagonal of row i; complex pairs when C).
template <int W, bool C>
inline void scale(const double* inv, int i, const double* g, double* out) {
    if constexpr (C) {
        const double wr = inv[2 * i], wi = inv[2 * i + 1];
        for (int c = 0; c < 3; ++c) {
            const double gr = g[c], gi = g[3 + c];
            out[c] = wr * gr - wi * gi;
            out[3 + c] = wr * gi + wi * gr;
        }
    } else {
        for (int c = 0; c < W; ++c) out[c] = inv[i] * g[c];
    }
}

}  // namespace

// res = b - B x.
template <int W, bool C>
void Multigrid::Impl::residual(const Level& level, int l, const double* b, const double* x,
                               double* res) const {
    const auto load = [x](int j, double* v) {
        for (int c = 0; c < W; ++c) v[c] = x[W * j + c];
    };
    for_each_row(level.n, level.threads, [&](int i) {
        double y[W];
        row_product<W, C>(level, l, i, load, y);
        for (int c = 0; c < W; ++c) res[W * i + c] = b[W * i + c] - y[c];
    });
}

// One damped Jacobi sweep x += w D^-1 (b - B x) (level.res is the work space).
template <int W, bool C>
void Multigrid::Impl::smooth(Level& level, int l, const double* b, double* x) {
    double* res = work(level, l);
    residual<W, C>(level, l, b, x, res);
    const double* inv = level.inv.data();
    for_each_row(level.n, level.threads, [=](int i) {
        double u[W];
        scale<W, C>(inv, i, res + W * i, u);
        for (int c = 0; c < W; ++c) x[W * i + c] += u[c];
    });
}

template <int W, bool C>
void Multigrid::Impl::solve_coarsest(const Level& level, const double* b, double* x) const {
    const int n = level.n;
    if constexpr (C) {
        Eigen::MatrixXcd rhs(n, 3);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) rhs(i, c) = {b[W * i + c], b[W * i + 3 + c]};
        const Eigen::MatrixXcd sol = lu_complex.solve(rhs);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                x[W * i + c] = sol(i, c).real();
                x[W * i + 3 + c] = sol(i, c).imag();
            }
    } else {
        Eigen::MatrixXd rhs(n, W);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < W; ++c) rhs(i, c) = b[W * i + c];
        const Eigen::MatrixXd sol = lu_real.solve(rhs);
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < W; ++c) x[W * i + c] = sol(i, c);
    }
}

// next.b = R res (R = P^T, by its stored rows).
template <int W, bool C>
void Multigrid::Impl::restrict_to(const Level& level, const double* res, Level& next) const {
    const Csr& r = level.r;
    double* bc = next.b.data();
    for_each_row(next.n, next.threads, [&](int c) {
        double s[W] = {};
        for (int e = r.start[c]; e < r.start[c + 1]; ++e) {
            const double* ri = res + W * r.col[e];
            for (int k = 0; k < W; ++k) s[k] += r.val[e] * ri[k];
        }
        for (int k = 0; k < W; ++k) bc[W * c + k] = s[k];
    });
}

namespace {

// out = sum_j B_ij v_j for off-diagonal couplings given S = sum_j w_ij v_j: B_ij = -a w_ij
// (Real) or i a w_ij (Complex).
template <int W, bool C>
inline void off_diagonal(double a, const double* S, double* out) {
    if constexpr (C) {
        for (int c = 0; c < 3; ++c) {
            out[c] = -a * S[3 + c];
            out[3 + c] = a * S[c];
        }
    } else {
        for (int c = 0; c < W; ++c) out[c] = -a * S[c];
    }
}

// acc += b_i^T x_i per column, unconjugated: real in [0..2] (W = 3), else re in [0..2] and im in
// [3..5].
template <int W>
inline void add_unconjugated(const double* bi, const double* xi, double* acc) {
    if constexpr (W == 3) {
        for (int c = 0; c < 3; ++c) acc[c] += bi[c] * xi[c];
    } else {
        for (int c = 0; c < 3; ++c) {
            acc[c] += bi[c] * xi[c] - bi[3 + c] * xi[3 + c];
            acc[3 + c] += bi[c] * xi[3 + c] + bi[3 + c] * xi[c];
        }
    }
}

}  // namespace

// The V-cycle with level 0 smoothed by block Gauss-Seidel (sweeps.h): a forward sweep from zero
// before the coarse correction, a backward one after it, its transpose, so the cycle stays a
// (complex) symmetric operator. Sweeps read couplings to other blocks from a vector no block
// writes during the sweep (zero before, the corrected x after), so the result does not depend
// on the number of threads. As the Jacobi cycle, two passes over K: the forward sweep and the
// residual it leaves (each over part of every row), then the backward sweep.
template <int W, bool C>
void Multigrid::Impl::cycle_gauss_seidel(const double* b, double* x, double* dots) {
    Level& level = levels[0];
    Level& next = levels[1];
    const int n = level.n;
    const double* inv = level.inv.data();
    double* res = fine_work;
    const int* start = op.row_start.data();
    const int* column = op.column.data();
    const double* weight = weights_of(op);
    const char* f = free.data();
    const double a = this->a;
    const int block = gauss_seidel_block;
    // x_i = B_ii^-1 (b_i - sum_j B_ij v_j) over the couplings add(w, S) sums (S = sum_j w_ij
    // v_j); zero on fixed rows.
    const auto relax = [=](int i, const auto& add) {
        double* xi = x + W * i;
        if (!f[i]) {
            for (int c = 0; c < W; ++c) xi[c] = 0;
            return;
        }
        double S[W] = {}, g[W];
        with_weights(weight, [&](const auto& w) { add(w, S); });
        off_diagonal<W, C>(a, S, g);
        for (int c = 0; c < W; ++c) g[c] = b[W * i + c] - g[c];
        scale<W, C>(inv, i, g, xi);
    };
    // Forward, from zero: the couplings before i in its block.
    forward_sweep<1>(
        n, block, level.threads,
        [=](int i, int begin, int end, double*) {
            const RowRuns runs = row_runs(start, column, i, begin, end);
            relax(i, [&](const auto& w, double* S) {
                add_run<W>(x, column, w, runs.in_block, runs.diagonal, S);
            });
        },
        [](std::array<double, 1>&, const std::array<double, 1>&) {});
    // res = b - B x: row i's diagonal and lower couplings give b_i, the rest is left.
    for_each_row(n, level.threads, [=](int i) {
        double* ri = res + W * i;
        if (!f[i]) {
            for (int c = 0; c < W; ++c) ri[c] = 0;
            return;
        }
        const int block_begin = i / block * block;
        const RowRuns runs =
            row_runs(start, column, i, block_begin, std::min(n, block_begin + block));
        double S[W] = {}, g[W];
        with_weights(weight, [&](const auto& w) {
            add_run<W>(x, column, w, runs.first, runs.in_block, S);
            add_run<W>(x, column, w, runs.diagonal, runs.last, S);
        });
        off_diagonal<W, C>(a, S, g);
        for (int c = 0; c < W; ++c) ri[c] = -g[c];
    });
    restrict_to<W, C>(level, res, next);
    cycle<W, C>(1, next.b.data(), next.x.data(), nullptr);
    // res = x + P x_coarse (the corrected x). By reference: a copy of P per cycle cost 16 MB
    // and its time on the 1 M-face torus.
    const Csr& p = level.p;
    const double* xc = next.x.data();
    for_each_row(n, level.threads, [&](int i) {
        double v[W];
        for (int k = 0; k < W; ++k) v[k] = x[W * i + k];
        for (int e = p.start[i]; e < p.start[i + 1]; ++e)
            for (int k = 0; k < W; ++k) v[k] += p.val[e] * xc[W * p.col[e] + k];
        for (int k = 0; k < W; ++k) res[W * i + k] = v[k];
    });
    // x_i = B_ii^-1 (b_i - sum_{j>i in the block} B_ij x_j - sum_{other j} B_ij res_j), and the
    // unconjugated products b^T x.
    const std::array<double, 6> sums = backward_sweep_sum<6>(
        n, block, level.threads,
        [=](int i, int begin, int end, double* acc) {
            const RowRuns runs = row_runs(start, column, i, begin, end);
            relax(i, [&](const auto& w, double* S) {
                add_run<W>(res, column, w, runs.first, runs.diagonal, S);
                add_run<W>(res, column, w, runs.after, runs.last, S);
                add_run_down<W>(x, column, w, runs.diagonal, runs.after, S);
            });
            if (f[i]) add_unconjugated<W>(b + W * i, x + W * i, acc);
        },
        [](std::array<double, 6>& total, const std::array<double, 6>& part) {
            for (int k = 0; k < 6; ++k) total[k] += part[k];
        });
    if (dots)
        for (int k = 0; k < 6; ++k) dots[k] = sums[k];
}

// x = V(b) on level l: smooth, restrict the residual, recurse, prolong, smooth. Level 0 goes
// to cycle_gauss_seidel where its sweeps apply. Else the finest level takes one Jacobi sweep
// each way, fused with the products (x = w D^-1 b is never stored, the
// corrected x lives in res once the residual is restricted), which saves two passes over the
// vectors; coarser levels take coarse_sweeps() each way. dots (level 0): the unconjugated
// products b^T x per column (re; im for width 6), summed in fixed blocks.
template <int W, bool C>
void Multigrid::Impl::cycle(int l, const double* b, double* x, double* dots) {
    if (l == 0 && gauss_seidel && levels.size() > 1) {
        cycle_gauss_seidel<W, C>(b, x, dots);
        return;
    }
    Level& level = levels[l];
    const double* inv = level.inv.data();
    if (l + 1 == static_cast<int>(levels.size())) {
        if (dense) {
            solve_coarsest<W, C>(level, b, x);
            return;
        }
        for_each_row(level.n, level.threads, [&](int i) { scale<W, C>(inv, i, b + W * i, x + W * i); });
        for (int k = 1; k < coarse_sweeps(); ++k) smooth<W, C>(level, l, b, x);
        return;
    }
    Level& next = levels[l + 1];
    double* res = work(level, l);
    const int sweeps = l == 0 ? 1 : coarse_sweeps();
    if (sweeps == 1) {
        const auto jacobi_b = [b, inv](int j, double* v) { scale<W, C>(inv, j, b + W * j, v); };
        for_each_row(level.n, level.threads, [&](int i) {
            double y[W];
            row_product<W, C>(level, l, i, jacobi_b, y);
            for (int c = 0; c < W; ++c) res[W * i + c] = b[W * i + c] - y[c];
        });
    } else {
        for_each_row(level.n, level.threads, [&](int i) { scale<W, C>(inv, i, b + W * i, x + W * i); });
        for (int k = 1; k < sweeps; ++k) smooth<W, C>(level, l, b, x);
        residual<W, C>(level, l, b, x, res);
    }
    restrict_to<W, C>(level, res, next);
    cycle<W, C>(l + 1, next.b.data(), next.x.data(), nullptr);
    const Csr& p = level.p;
    const double* xc = next.x.data();
    double* corrected = sweeps == 1 ? res : x;
    for_each_row(level.n, level.threads, [&](int i) {
        double v[W];
        if (sweeps == 1) scale<W, C>(inv, i, b + W * i, v);
        else for (int k = 0; k < W; ++k) v[k] = x[W * i + k];
        for (int e = p.start[i]; e < p.start[i + 1]; ++e)
            for (int k = 0; k < W; ++k) v[k] += p.val[e] * xc[W * p.col[e] + k];
        for (int k = 0; k < W; ++k) corrected[W * i + k] = v[k];
    });
    if (sweeps > 1) {
        for (int k = 0; k < sweeps; ++k) smooth<W, C>(level, l, b, x);
        return;
    }
    const auto load = [res](int j, double* v) {
        for (int c = 0; c < W; ++c) v[c] = res[W * j + c];
    };
    const std::array<double, 6> sums = blocked_sum<6>(level.n, level.threads, [&](int i, double* a) {
        double y[W], g[W], u[W];
        row_product<W, C>(level, l, i, load, y);
        for (int c = 0; c < W; ++c) g[c] = b[W * i + c] - y[c];
        scale<W, C>(inv, i, g, u);
        double* xi = x + W * i;
        for (int c = 0; c < W; ++c) xi[c] = res[W * i + c] + u[c];
        if (dots) add_unconjugated<W>(b + W * i, xi, a);
    });
    if (dots)
        for (int k = 0; k < 6; ++k) dots[k] = sums[k];
}

Multigrid::Multigrid(const SparseOperator& op, const std::vector<double>& diagonal,
                     const std::vector<char>& free, double a, Kind kind, bool gauss_seidel)
    : impl_(std::make_unique<Impl>(op, diagonal, free, a, kind)) {
    impl_->gauss_seidel = gauss_seidel;
    impl_->build();
}

bool Multigrid::gauss_seidel() const { return impl_->gauss_seidel && impl_->levels.size() > 1; }

Multigrid::~Multigrid() = default;

std::array<double, 6> Multigrid::apply(const double* r, double* z, double* work) {
    impl_->fine_work = work;
    std::array<double, 6> dots{};
    switch (impl_->kind) {
    case Kind::Real: impl_->cycle<3, false>(0, r, z, dots.data()); break;
    case Kind::Complex: impl_->cycle<6, true>(0, r, z, dots.data()); break;
    }
    if (impl_->levels.size() > 1) return dots;
    // Level 0 alone (no free row) took the coarsest branch, which sums nothing.
    const int w = impl_->width;
    return blocked_sum<6>(impl_->levels[0].n, impl_->levels[0].threads, [=](int i, double* a) {
        for (int c = 0; c < 3; ++c) {
            if (w == 3) {
                a[c] += r[3 * i + c] * z[3 * i + c];
                continue;
            }
            a[c] += r[6 * i + c] * z[6 * i + c] - r[6 * i + 3 + c] * z[6 * i + 3 + c];
            a[3 + c] += r[6 * i + c] * z[6 * i + 3 + c] + r[6 * i + 3 + c] * z[6 * i + c];
        }
    });
}

int Multigrid::width() const { return impl_->width; }
int Multigrid::levels() const { return static_cast<int>(impl_->levels.size()); }

std::size_t Multigrid::bytes() const {
    std::size_t total = 0;
    const auto add = [&total](const auto& v) { total += v.capacity() * sizeof(v[0]); };
    for (const Impl::Level& level : impl_->levels) {
        add(level.start), add(level.col), add(level.re), add(level.im), add(level.inv);
        add(level.p.start), add(level.p.col), add(level.p.val);
        add(level.r.start), add(level.r.col), add(level.r.val);
        add(level.b), add(level.x), add(level.res);
    }
    return total;
}

}  // namespace detail
}  // namespace fairing
