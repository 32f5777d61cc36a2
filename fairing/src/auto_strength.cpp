#include "auto_strength.h"

#include "fairing/solver.h"
#include "geometry.h"
#include "kernels.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace fairing {
namespace detail {

Positions robust_normals(const HalfEdgeMesh& mesh, const Positions& x) {
    const int n = mesh.num_vertices();
    Positions area = Positions::Zero(n, 3);
    for (const Triangle& t : mesh.faces()) {
        const Vec3 a = row(x, t[0]);
        const Eigen::RowVector3d normal = (row(x, t[1]) - a).cross(row(x, t[2]) - a).transpose();
        for (int k = 0; k < 3; ++k) area.row(t[k]) += normal;
    }
    // Averaging over the one-ring tames the noise's tilt of the normals (a quarter-edge noise
    // tilts single-face normals by ~15 degrees), which would otherwise leak tangential sliding
    // into the normal residual.
    Positions smooth = area;
    for (const Triangle& t : mesh.faces()) {
        const Eigen::RowVector3d sum = area.row(t[0]) + area.row(t[1]) + area.row(t[2]);
        for (int k = 0; k < 3; ++k) smooth.row(t[k]) += sum;
    }
    for (int i = 0; i < n; ++i) {
        const double length = smooth.row(i).norm();
        if (length > 0) smooth.row(i) /= length;
        else smooth.row(i).setZero();
    }
    return smooth;
}

Positions smoothed_copy(const SparseOperator& op, const Positions& x, int data, int passes) {
    Positions a = x.topRows(data), b(data, 3);
    for (int pass = 0; pass < passes; ++pass) {
        for (int i = 0; i < data; ++i) {
            Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
            int m = 0;
            for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
                if (op.column[k] < data) {
                    sum += a.row(op.column[k]);
                    ++m;
                }
            b.row(i) = m > 0 ? Eigen::RowVector3d(0.5 * a.row(i) + 0.5 * sum / m) : a.row(i);
        }
        a.swap(b);
    }
    return a;
}

namespace {

// Number of neighbours of i among the data vertices.
int valence(const SparseOperator& op, int i, int data) {
    int m = 0;
    for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k) m += op.column[k] < data;
    return m;
}

// Median of |v - median(v)| (v is reordered).
double median_absolute_deviation(std::vector<double>& v) {
    if (v.empty()) return 0;
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    const double median = *middle;
    for (double& a : v) a = std::abs(a - median);
    std::nth_element(v.begin(), middle, v.end());
    return *middle;
}

// The normal component of the uniform bi-Laplacian at every vertex whose two-ring is interior,
// divided by the norm of its stencil (so every value has the noise's variance), for vertices
// with use[i] (all when `use` is empty).
std::vector<double> normalized_bilaplacian(const SparseOperator& op, const HalfEdgeMesh& mesh,
                                           const Positions& x, const Positions& normals,
                                           const std::vector<char>& use, bool strict) {
    const int n = mesh.num_vertices();
    std::vector<int> m(n);
    Positions lx(n, 3);
    for (int i = 0; i < n; ++i) {
        m[i] = valence(op, i, n);
        Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
        for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k)
            if (op.column[k] < n) sum += x.row(op.column[k]);
        lx.row(i) = m[i] > 0 ? Eigen::RowVector3d(sum / m[i] - x.row(i)) : Eigen::RowVector3d::Zero();
    }
    const auto interior = [&](int i) { return m[i] >= 3 && !mesh.is_boundary_vertex(i); };
    std::vector<double> coef(n, 0.0), values;
    std::vector<char> listed(n, 0);
    std::vector<int> touched;
    const auto add = [&](int j, double c) {
        if (!listed[j]) touched.push_back(j);
        listed[j] = 1;
        coef[j] += c;
    };
    for (int i = 0; i < n; ++i) {
        if ((!use.empty() && !use[i]) || !interior(i) || normals.row(i).squaredNorm() == 0) continue;
        bool ok = true;
        for (int k = op.row_start[i]; k < op.row_start[i + 1] && ok; ++k)
            ok = op.column[k] < n && (!strict || interior(op.column[k]));
        if (!ok) continue;
        // Row i of L^2 = L (L x), L = A - I, A_ij = 1/m_i on the one-ring:
        // e_i - sum_j (2/m_i) e_j + sum_j sum_{k ~ j} e_k / (m_i m_j).
        Eigen::RowVector3d bilaplacian = -lx.row(i);
        add(i, 1.0);
        for (int k = op.row_start[i]; k < op.row_start[i + 1]; ++k) {
            const int j = op.column[k];
            bilaplacian += lx.row(j) / m[i];
            add(j, -2.0 / m[i]);
            for (int l = op.row_start[j]; l < op.row_start[j + 1]; ++l)
                if (op.column[l] < n) add(op.column[l], 1.0 / (static_cast<double>(m[i]) * m[j]));
        }
        double norm2 = 0;
        for (int j : touched) {
            norm2 += coef[j] * coef[j];
            coef[j] = 0;
            listed[j] = 0;
        }
        touched.clear();
        if (norm2 > 0) values.push_back(normals.row(i).dot(bilaplacian) / std::sqrt(norm2));
    }
    return values;
}

}  // namespace

double estimate_noise(const SparseOperator& op, const HalfEdgeMesh& mesh, const Positions& x,
                      const Positions& normals, const std::vector<char>& use) {
    // Too few qualifying vertices for a median: widen the set rather than guess.
    constexpr std::size_t kEnough = 16;
    std::vector<double> v = normalized_bilaplacian(op, mesh, x, normals, use, true);
    if (v.size() < kEnough) v = normalized_bilaplacian(op, mesh, x, normals, {}, true);
    if (v.size() < kEnough) v = normalized_bilaplacian(op, mesh, x, normals, {}, false);
    return 1.482602218505602 * median_absolute_deviation(v);
}

namespace {

// The filter of `steps` steps of tau = lambda / steps, as functions of an eigenvalue g of G.
struct Filter {
    double lambda = 0;
    int steps = 1;
    bool explicit_steps = false;

    // log of the per-mode gain of one step, times steps: the whole filter is exp(this).
    double log_gain(double g) const {
        const double t = lambda / steps * g;
        return explicit_steps ? steps * std::log(std::abs(1 - t)) : -steps * std::log1p(t);
    }
    // h(g): how much of a mode is kept.
    double keep(double g) const {
        g = std::max(g, 0.0);
        if (explicit_steps) return std::pow(1 - lambda / steps * g, steps);
        return std::exp(log_gain(g));
    }
    // phi(g) = (1 - h(g)) / g: the displacement per unit of u; lambda at g = 0.
    double move(double g) const {
        g = std::max(g, 0.0);
        const double t = lambda / steps * g;
        if (t < 1e-300) return lambda;
        if (explicit_steps && t >= 0.5) return (1 - keep(g)) / g;
        const double l = explicit_steps ? steps * std::log1p(-t) : -steps * std::log1p(t);
        return -std::expm1(l) / g;
    }
};

// Three independent Lanczos processes on G (one per column), in the coordinates q = D^-1/2 v,
// where G v = D^-1/2 C q and the inner product is <a, b>_D = sum_free D_i a_i b_i. Never more
// than two basis vectors are kept.
struct Lanczos {
    Positions previous, current, product;
    std::array<std::vector<double>, 3> alpha, beta;  // beta[j] joins basis vectors j and j+1
    std::array<double, 3> start_norm{{0, 0, 0}};
    std::array<bool, 3> active{{true, true, true}};
};

struct Context {
    const StrengthProblem& p;
    LinearSystem c;           // lambda_dt = length_unit, diagonal 0: apply() is unit * C
    std::vector<double> d;    // D_i on free rows, 1 elsewhere
    std::vector<char> data;   // free data rows: they count in the risk and the trace
    Positions scratch;
    int n = 0;
};

// product = unit * C current; returns alpha = <current, D^-1 product>_D per column.
std::array<double, 3> multiply(Context& ctx, Lanczos& l) {
    return ctx.c.apply_dot(l.current, l.product, ctx.scratch);
}

// One recurrence step given alpha_j and beta_{j-1}: previous <- the next basis vector. With
// `measure`, beta_j is measured and stored, else taken from what is stored (the second pass
// regenerates the first pass's basis bit for bit).
void advance(Context& ctx, Lanczos& l, int j, bool measure) {
    const int n = ctx.n;
    std::array<double, 3> a{}, b{}, inverse{};
    for (int c = 0; c < 3; ++c) {
        if (!l.active[c]) continue;
        a[c] = l.alpha[c][j];
        b[c] = j > 0 ? l.beta[c][j - 1] : 0.0;
    }
    const double* d = ctx.d.data();
    const char* f = ctx.p.free->data();
    double* prev = l.previous.data();
    const double* cur = l.current.data();
    const double* prod = l.product.data();
    double s0 = 0, s1 = 0, s2 = 0;
    const int threads = ctx.p.op->threads;
    (void)threads;
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1) \
                   reduction(+ : s0, s1, s2))
    for (int i = 0; i < n; ++i) {
        if (!f[i]) continue;
        double w[3];
        for (int c = 0; c < 3; ++c) {
            w[c] = prod[3 * i + c] / d[i] - a[c] * cur[3 * i + c] - b[c] * prev[3 * i + c];
            prev[3 * i + c] = w[c];
        }
        s0 += d[i] * w[0] * w[0];
        s1 += d[i] * w[1] * w[1];
        s2 += d[i] * w[2] * w[2];
    }
    const std::array<double, 3> sums{{s0, s1, s2}};
    for (int c = 0; c < 3; ++c) {
        if (!l.active[c]) continue;
        if (measure) {
            const double norm = std::sqrt(sums[c]);
            // Breakdown: the Krylov space is exhausted, T_k is exact.
            if (!(norm > 1e-13 * (std::abs(a[c]) + b[c]))) {
                l.active[c] = false;
                continue;
            }
            l.beta[c].push_back(norm);
        } else if (static_cast<int>(l.beta[c].size()) <= j) {
            l.active[c] = false;
            continue;
        }
        inverse[c] = 1.0 / l.beta[c][j];
    }
    FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) prev[3 * i + c] = f[i] ? prev[3 * i + c] * inverse[c] : 0.0;
    l.previous.swap(l.current);
}

// Eigenvalues and eigenvectors of T_k.
struct Ritz {
    Eigen::VectorXd theta;
    Eigen::MatrixXd vectors;
};

Ritz ritz(const std::vector<double>& alpha, const std::vector<double>& beta, int k) {
    Ritz r;
    if (k == 0) return r;
    Eigen::VectorXd diagonal = Eigen::Map<const Eigen::VectorXd>(alpha.data(), k);
    Eigen::VectorXd sub = k > 1 ? Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(beta.data(), k - 1))
                                : Eigen::VectorXd(0);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
    solver.computeFromTridiagonal(diagonal, sub, Eigen::ComputeEigenvectors);
    r.theta = solver.eigenvalues();
    r.vectors = solver.eigenvectors();
    return r;
}

int size_of(const Lanczos& l, int c) {
    return std::min(static_cast<int>(l.alpha[c].size()), static_cast<int>(l.beta[c].size()) + 1);
}

// Quadrature sum_j (Q_0j)^2 fn(theta_j) over the Ritz pairs.
template <class Fn>
double quadrature(const Ritz& r, Fn fn) {
    double s = 0;
    for (int j = 0; j < r.theta.size(); ++j) s += r.vectors(0, j) * r.vectors(0, j) * fn(r.theta(j));
    return s;
}

// tr H(lambda) over the data rows for every lambda of the grid, by Lanczos quadrature on the
// probes (each column one probe).
std::vector<double> traces(const Context& ctx, const Lanczos& z, double count,
                           const std::vector<double>& grid) {
    std::vector<double> out(grid.size(), 0.0);
    int probes = 0;
    std::array<Ritz, 3> rz;
    for (int c = 0; c < 3; ++c) {
        rz[c] = ritz(z.alpha[c], z.beta[c], size_of(z, c));
        probes += rz[c].theta.size() > 0;
    }
    for (std::size_t g = 0; g < grid.size(); ++g) {
        const Filter filter{grid[g], ctx.p.steps, ctx.p.explicit_integration};
        for (int c = 0; c < 3; ++c)
            if (rz[c].theta.size() > 0)
                out[g] += count / probes * quadrature(rz[c], [&](double t) { return filter.keep(t); });
    }
    return out;
}

// Coefficients of r_c(lambda) on the Lanczos basis: |u_c| Q phi(Theta) Q^T e1.
Eigen::VectorXd displacement(const Ritz& r, double start_norm, const Filter& filter) {
    Eigen::VectorXd phi(r.theta.size());
    for (int j = 0; j < r.theta.size(); ++j) phi(j) = filter.move(r.theta(j)) * r.vectors(0, j);
    return start_norm * (r.vectors * phi);
}

std::uint64_t mix(std::uint64_t v) {  // splitmix64: probe signs independent of thread count
    v += 0x9e3779b97f4a7c15ull;
    v = (v ^ (v >> 30)) * 0xbf58476d1ce4e5b9ull;
    v = (v ^ (v >> 27)) * 0x94d049bb133111ebull;
    return v ^ (v >> 31);
}

// First basis vectors: u = D^-1/2 C x for the positions, Rademacher probes on the data rows.
void start(Context& ctx, Lanczos& u, Lanczos& z, double& count) {
    const int n = ctx.n;
    u.current.setZero(n, 3);
    z.current.setZero(n, 3);
    ctx.c.apply(*ctx.p.x, u.product, ctx.scratch);
    std::array<double, 3> su{{0, 0, 0}};
    count = 0;
    for (int i = 0; i < n; ++i) {
        if (!(*ctx.p.free)[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double v = u.product(i, c);
            su[c] += v * v / ctx.d[i];
            u.current(i, c) = v / ctx.d[i];
        }
        if (!ctx.data[i]) continue;
        ++count;
        const std::uint64_t bits = mix(static_cast<std::uint64_t>(i));
        for (int c = 0; c < 3; ++c) z.current(i, c) = ((bits >> c) & 1 ? 1.0 : -1.0) / std::sqrt(ctx.d[i]);
    }
    for (int c = 0; c < 3; ++c) {
        u.start_norm[c] = std::sqrt(su[c]);
        z.start_norm[c] = std::sqrt(count);
        u.active[c] = u.start_norm[c] > 0;
        z.active[c] = count > 0;
        const double su_inv = u.active[c] ? 1 / u.start_norm[c] : 0.0;
        const double sz_inv = z.active[c] ? 1 / z.start_norm[c] : 0.0;
        u.current.col(c) *= su_inv;
        z.current.col(c) *= sz_inv;
    }
    u.previous.setZero(n, 3);
    z.previous.setZero(n, 3);
}

// One Lanczos step of a block: alpha measured, then the next vector.
void step(Context& ctx, Lanczos& l, int j) {
    const std::array<double, 3> a = multiply(ctx, l);
    for (int c = 0; c < 3; ++c)
        if (l.active[c]) l.alpha[c].push_back(a[c]);
    advance(ctx, l, j, true);
}

int argmin(const std::vector<double>& v) {
    return static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
}

// Relative change of the curves between two checkpoints below which a point counts as converged.
constexpr double kConverged = 5e-3;
// The Lanczos process runs until its curves are converged up to this factor above the risk's
// minimizer (and the minimizer has settled).
constexpr double kMargin = 2;
constexpr int kMaxSteps = 400;
// Rows of the sketch of the normal components (exact below this many data vertices).
constexpr int kSketch = 4096;
// Second pass: points of the final lambda grid.
constexpr int kGrid = 16;

// A sketch of the normal components n_i . r_i: CountSketch (Charikar, Chen & Farach-Colton
// 2002) of every basis vector's normal part, so that |sketch of r(lambda)|^2 estimates
// RSS_n(lambda) to about sqrt(2 / rows) at every checkpoint without keeping the basis. With no
// more data vertices than rows it is exact (one row per vertex).
struct Sketch {
    int rows = 0;
    bool exact = false;
    std::vector<int> bucket;     // per vertex, -1 off the data
    std::vector<float> sign;
    std::array<std::vector<std::vector<float>>, 3> columns;  // [c][j]: rows floats

    Sketch() = default;
    Sketch(const Context& ctx, int data_count) {
        exact = data_count <= kSketch;
        rows = exact ? data_count : kSketch;
        bucket.assign(ctx.n, -1);
        sign.assign(ctx.n, 1.0f);
        int next = 0;
        for (int i = 0; i < ctx.n; ++i) {
            if (!ctx.data[i]) continue;
            const std::uint64_t h = mix(static_cast<std::uint64_t>(i) + 0x5bd1e995ull);
            bucket[i] = exact ? next++ : static_cast<int>(h % static_cast<std::uint64_t>(rows));
            if (!exact) sign[i] = (h >> 40) & 1 ? 1.0f : -1.0f;
        }
    }
    void add(const Lanczos& u, const Positions& normals) {
        for (int c = 0; c < 3; ++c) {
            if (!u.active[c]) continue;
            std::vector<float> col(rows, 0.0f);
            for (std::size_t i = 0; i < bucket.size(); ++i)
                if (bucket[i] >= 0)
                    col[bucket[i]] += sign[i] * static_cast<float>(normals(i, c) * u.current(i, c));
            columns[c].push_back(std::move(col));
        }
    }
    // |sum_c S_c y_c|^2
    double rss(const std::array<Eigen::VectorXd, 3>& y) const {
        std::vector<double> v(rows, 0.0);
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < y[c].size(); ++j) {
                const float* col = columns[c][j].data();
                const double a = y[c](j);
                for (int r = 0; r < rows; ++r) v[r] += a * col[r];
            }
        double s = 0;
        for (double a : v) s += a * a;
        return s;
    }
};

struct Curves {
    std::vector<double> rss, trace;  // rss NaN where not evaluated
    std::size_t first = 0;           // below: the filter keeps over 98 % (not evaluated)
    std::size_t reach = 0;           // [first, reach) converged since the last checkpoint
};

struct Search {
    std::vector<double> grid;
    double minimizer = 0;     // of the risk over the converged points
    double converged_to = 0;  // largest converged lambda
    double count = 0;
};

// Points evaluated past the last converged one at each checkpoint.
constexpr std::size_t kAhead = 6;

// The risk curve at a checkpoint: traces everywhere, RSS_n from where the filter starts to act
// up to a few points past those that have converged since the last checkpoint.
Curves checkpoint(const Context& ctx, const Lanczos& u, const Lanczos& z, const Sketch& sketch,
                  const Search& s, const Curves& last) {
    Curves now;
    now.trace = traces(ctx, z, s.count, s.grid);
    now.rss.assign(s.grid.size(), std::numeric_limits<double>::quiet_NaN());
    while (now.first + 1 < s.grid.size() && now.trace[now.first + 1] > 0.98 * s.count)
        ++now.first;
    std::array<Ritz, 3> ru;
    for (int c = 0; c < 3; ++c) ru[c] = ritz(u.alpha[c], u.beta[c], size_of(u, c));
    now.reach = now.first;
    bool settled = true;
    for (std::size_t g = now.first; g < s.grid.size() && g < now.reach + kAhead; ++g) {
        const Filter filter{s.grid[g], ctx.p.steps, ctx.p.explicit_integration};
        std::array<Eigen::VectorXd, 3> y;
        for (int c = 0; c < 3; ++c) y[c] = displacement(ru[c], u.start_norm[c], filter);
        now.rss[g] = sketch.rss(y);
        settled = settled && g < last.rss.size() && std::isfinite(last.rss[g]) &&
                  std::abs(now.rss[g] - last.rss[g]) <= kConverged * now.rss[g] &&
                  std::abs(now.trace[g] - last.trace[g]) <=
                      kConverged * std::max(s.count - now.trace[g], 1e-3 * s.count);
        if (settled) now.reach = g + 1;
    }
    return now;
}

// Runs both Lanczos processes, with the sketched risk at checkpoints, until the risk's
// minimizer has settled inside the converged part of the curves.
Search search(Context& ctx, Lanczos& u, Lanczos& z, Sketch& sketch, const Positions& normals,
              double count, double sigma) {
    Search s;
    s.count = count;
    const double top = ctx.p.explicit_integration ? 0.999 * ctx.p.max_time_step : 1e7;
    for (double l = 1e-4; l < top; l *= std::pow(10.0, 0.1)) s.grid.push_back(l);
    if (ctx.p.explicit_integration) s.grid.push_back(top);
    Curves last;
    double previous_minimizer = 0;
    int next_check = 6;
    for (int j = 0; j < kMaxSteps; ++j) {
        const bool u_active = u.active[0] || u.active[1] || u.active[2];
        const bool z_active = z.active[0] || z.active[1] || z.active[2];
        if (u_active) sketch.add(u, normals);
        if (u_active) step(ctx, u, j);
        if (z_active) step(ctx, z, j);
        if (ctx.p.progress) ctx.p.progress(0.7 * (1 - 16.0 / (16.0 + j)));
        const bool exhausted = !(u.active[0] || u.active[1] || u.active[2] || z.active[0] ||
                                 z.active[1] || z.active[2]);
        if (j + 1 < next_check && !exhausted) continue;
        next_check = std::max(j + 2, static_cast<int>(1.4 * (j + 1)));
        Curves now = checkpoint(ctx, u, z, sketch, s, last);
        if (exhausted) {  // T is exact: every evaluated point holds
            now.reach = now.first;
            while (now.reach < now.rss.size() && std::isfinite(now.rss[now.reach])) ++now.reach;
        }
        last = now;
        if (now.reach == now.first) continue;
        std::vector<double> risk;
        for (std::size_t g = now.first; g < now.reach; ++g)
            risk.push_back(now.rss[g] + 2 * sigma * sigma * now.trace[g]);
        const std::size_t best = now.first + argmin(risk);
        s.minimizer = s.grid[best];
        s.converged_to = s.grid[now.reach - 1];
        const bool settled = std::abs(s.minimizer / previous_minimizer - 1) < 0.3;
        previous_minimizer = s.minimizer;
        if (exhausted || now.reach == s.grid.size() ||
            (settled && s.converged_to >= kMargin * s.minimizer))
            break;
    }
    if (s.converged_to == 0) {  // nothing converged within the cap: take what there is
        s.converged_to = s.grid.front();
        s.minimizer = s.grid.front();
    }
    return s;
}

// Regenerates the positions' basis and accumulates, per data vertex and grid point, the normal
// component of r(lambda); returns RSS_n per grid point.
std::vector<double> second_pass(Context& ctx, Lanczos& u, const Positions& normals,
                                const std::vector<double>& grid) {
    const int m = static_cast<int>(grid.size());
    // Coefficients of r_c(lambda) on the basis: |u_c| Q phi(Theta) Q^T e1.
    std::array<Eigen::MatrixXd, 3> coef;
    int k = 0;
    for (int c = 0; c < 3; ++c) {
        const int kc = size_of(u, c);
        k = std::max(k, kc);
        const Ritz r = ritz(u.alpha[c], u.beta[c], kc);
        coef[c] = Eigen::MatrixXd::Zero(std::max(kc, 1), m);
        for (int g = 0; g < m && kc > 0; ++g) {
            const Filter filter{grid[g], ctx.p.steps, ctx.p.explicit_integration};
            Eigen::VectorXd phi(kc);
            for (int j = 0; j < kc; ++j) phi(j) = filter.move(r.theta(j)) * r.vectors(0, j);
            coef[c].col(g) = u.start_norm[c] * (r.vectors * phi);
        }
    }
    std::vector<float> acc(static_cast<std::size_t>(ctx.p.data_vertices) * m, 0.0f);
    Lanczos regen;
    regen.alpha = u.alpha;
    regen.beta = u.beta;
    regen.start_norm = u.start_norm;
    double unused = 0;
    Lanczos probes;  // start() builds both; the probes are dropped at once
    start(ctx, regen, probes, unused);
    probes = Lanczos();
    std::array<int, 3> sizes{{size_of(u, 0), size_of(u, 1), size_of(u, 2)}};
    const int data = ctx.p.data_vertices;
    for (int j = 0; j < k; ++j) {
        // Accumulate basis vector j (held in regen.current).
        const double* q = regen.current.data();
        const int threads = ctx.p.op->threads;
        (void)threads;
        std::array<const double*, 3> cj{};
        for (int c = 0; c < 3; ++c) cj[c] = j < sizes[c] ? coef[c].data() + static_cast<std::ptrdiff_t>(j) : nullptr;
        const std::array<std::ptrdiff_t, 3> stride{{coef[0].rows(), coef[1].rows(), coef[2].rows()}};
        FAIRING_PRAGMA(omp parallel for num_threads(threads) schedule(static) if(threads > 1))
        for (int i = 0; i < data; ++i) {
            if (!ctx.data[i]) continue;
            double a[3];
            for (int c = 0; c < 3; ++c) a[c] = cj[c] ? normals(i, c) * q[3 * i + c] : 0.0;
            float* s = acc.data() + static_cast<std::size_t>(i) * m;
            for (int g = 0; g < m; ++g) {
                double v = 0;
                for (int c = 0; c < 3; ++c)
                    if (cj[c]) v += a[c] * cj[c][g * stride[c]];
                s[g] += static_cast<float>(v);
            }
        }
        if (ctx.p.progress) ctx.p.progress(0.7 + 0.3 * (j + 1) / k);
        if (j + 1 == k) break;
        multiply(ctx, regen);
        advance(ctx, regen, j, false);
    }
    std::vector<double> rss(m, 0.0);
    for (int i = 0; i < data; ++i)
        for (int g = 0; g < m; ++g) rss[g] += static_cast<double>(acc[static_cast<std::size_t>(i) * m + g]) * acc[static_cast<std::size_t>(i) * m + g];
    return rss;
}

// The minimizer of SURE on the grid, refined by a parabola in log(lambda) through its
// neighbours.
void choose(StrengthEstimate& e) {
    const int m = static_cast<int>(e.grid.size());
    std::vector<double> risk(m);
    const double s2 = e.noise_level * e.noise_level;
    for (int g = 0; g < m; ++g) risk[g] = e.rss[g] + 2 * s2 * e.trace[g];
    const int best = argmin(risk);
    double log_lambda = std::log(e.grid[best]);
    if (best > 0 && best + 1 < m) {
        const double a = risk[best - 1], b = risk[best], c = risk[best + 1];
        const double h = std::log(e.grid[best + 1] / e.grid[best]);
        const double curvature = a - 2 * b + c;
        if (curvature > 0) log_lambda += std::max(-1.0, std::min(1.0, 0.5 * (a - c) / curvature)) * h;
    }
    e.time_step = std::exp(log_lambda);
    e.trace_fraction = e.trace[best] / e.data_count;
    if (std::getenv("FAIRING_AUTO_DEBUG")) {
        std::fprintf(stderr, "auto: sigma %g N %g lanczos %d chosen %g\n", e.noise_level,
                     e.data_count, e.lanczos_steps, e.time_step);
        for (int g = 0; g < m; ++g) {
            const double rest = e.data_count - e.trace[g];
            std::fprintf(stderr, "  lambda %10.4g rss %10.4g tr %10.4g sure %10.4g gcv %10.4g\n",
                         e.grid[g], e.rss[g], e.trace[g], risk[g],
                         e.rss[g] / (rest * rest) * e.data_count);
        }
    }
}

}  // namespace

// Umbrella passes (half steps) smoothing the copy the normals are taken from.
constexpr int kSmoothingPasses = 4;

StrengthEstimate estimate_strength(const StrengthProblem& p) {
    StrengthEstimate e;
    // Normals of a lightly smoothed copy: those of the noisy mesh are tilted by the noise (by
    // ~25 degrees at half an edge), which hides part of it from the normal components.
    const Positions normals =
        robust_normals(*p.mesh, smoothed_copy(*p.op, *p.x, p.data_vertices, kSmoothingPasses));
    std::vector<char> use(p.data_vertices, 0);
    for (int i = 0; i < p.data_vertices; ++i) use[i] = (*p.free)[i];
    e.noise_level = estimate_noise(*p.op, *p.mesh, *p.x, normals, use);
    if (!(e.noise_level > 0)) return e;

    Context ctx{p, LinearSystem{}, {}, {}, Positions(), p.op->size()};
    ctx.c.op = p.op;
    ctx.c.free = *p.free;
    ctx.c.lambda_dt = p.length_unit;
    ctx.c.order = p.order;
    ctx.c.diagonal.assign(ctx.n, 0.0);
    ctx.d.assign(ctx.n, 1.0);
    ctx.data.assign(ctx.n, 0);
    double mean_d = 0, count = 0;
    for (int i = 0; i < ctx.n; ++i) {
        if (!(*p.free)[i]) continue;
        ctx.d[i] = p.op->mass[i] / (i < p.data_vertices ? (*p.weight)[i] : 1.0);
        if (i >= p.data_vertices) continue;
        ctx.data[i] = 1;
        mean_d += ctx.d[i];
        ++count;
    }
    if (count == 0) return e;
    mean_d /= count;
    e.data_count = count;

    Lanczos u, z;
    start(ctx, u, z, count);
    Sketch sketch(ctx, static_cast<int>(count));
    const Search found = search(ctx, u, z, sketch, normals, count, e.noise_level);
    e.lanczos_steps = static_cast<int>(
        std::max({u.alpha[0].size(), u.alpha[1].size(), u.alpha[2].size()}));
    // The final grid around the minimizer, within the converged part.
    const double hi = std::min(found.converged_to, 2.5 * found.minimizer);
    const double lo = std::min(found.minimizer / 2.5, hi / 2);
    for (int g = 0; g < kGrid; ++g) e.grid.push_back(lo * std::pow(hi / lo, g / (kGrid - 1.0)));
    if (sketch.exact) {
        std::array<Ritz, 3> ru;
        for (int c = 0; c < 3; ++c) ru[c] = ritz(u.alpha[c], u.beta[c], size_of(u, c));
        for (double l : e.grid) {
            const Filter filter{l, p.steps, p.explicit_integration};
            std::array<Eigen::VectorXd, 3> y;
            for (int c = 0; c < 3; ++c) y[c] = displacement(ru[c], u.start_norm[c], filter);
            e.rss.push_back(sketch.rss(y));
        }
    } else {
        sketch = Sketch();
        z.previous = z.current = z.product = Positions();  // its tridiagonals suffice now
        e.rss = second_pass(ctx, u, normals, e.grid);
    }
    e.trace = traces(ctx, z, count, e.grid);
    choose(e);
    return e;
}

}  // namespace detail
}  // namespace fairing
