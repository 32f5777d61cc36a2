// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "fairing/operators.h"

#include "geometry.h"
#include "kernels.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace fairing {
namespace {

// Where 1/|e| is taken (eq. 11) an edge counts as at least kShortEdge (operators.h) times the mean
// edge long. Duplicated vertices would give infinite weights, and edges that strong steps
// collapse ill-condition the later steps past what double precision can solve: scale-dependent
// L^2 x4 at time steps of 2.5-10 on CGAL's camel (20 k faces, every noise case of the study)
// collapses the legs; after three steps 859 of its edges were under 1 % of the mean (the
// shortest 6e-4) and the fourth solve stalled at residuals of 2e-8 to 1e-6 ("did not converge",
// with every preconditioner). At 1 % of the mean the same steps converge, and the weights of the
// study's noisy inputs stay exact but for one edge (0.7 % of the mean, the camel at a quarter
// edge of noise, seed 2; its clean scans have a few, the dragon four down to 0.3 %). Sweeps of
// the study's meshes and noises (scale-dependent, orders 1 and 2, 1 / 2 / 4 steps, 3,273 time
// steps from 2 / 2.5 up): 11 failures -> none, 193 results moved by at most 0.87 %, every best
// error the same to 1e-6; a floor at 5 % of the mean moved 1,060 of them, by up to 7.7 %.

// The mean edge length adds one partial sum per chunk of this many half-edges, then the partial
// sums in order: the result depends on the mesh only, not on the number of threads (and on a mesh
// of one chunk it is the plain running sum).
constexpr int kLengthChunk = 1 << 14;

int length_chunks(const HalfEdgeMesh& mesh) {
    return (mesh.num_half_edges() + kLengthChunk - 1) / kLengthChunk;
}

// The representative of an undirected edge is its smaller half-edge.
bool is_representative(const HalfEdgeMesh& mesh, int h) {
    return mesh.twin(h) < 0 || mesh.twin(h) > h;
}

// Called by every thread of a region: sum[c] and count[c] of the edges of chunk c. No barrier.
void edge_length_chunks(const HalfEdgeMesh& mesh, const Positions& positions, double* sum,
                        int* count) {
    const int num_half_edges = mesh.num_half_edges();
    const int chunks = length_chunks(mesh);
    FAIRING_PRAGMA(omp for schedule(static) nowait)
    for (int c = 0; c < chunks; ++c) {
        double s = 0;
        int k = 0;
        for (int h = c * kLengthChunk; h < std::min(num_half_edges, (c + 1) * kLengthChunk); ++h) {
            if (!is_representative(mesh, h)) continue;
            s += (positions.row(mesh.to(h)) - positions.row(mesh.from(h))).norm();
            ++k;
        }
        sum[c] = s;
        count[c] = k;
    }
}

double mean_of_chunks(const std::vector<double>& sum, const std::vector<int>& count) {
    double total = 0;
    long long edges = 0;
    for (std::size_t c = 0; c < sum.size(); ++c) {
        total += sum[c];
        edges += count[c];
    }
    return edges > 0 ? total / static_cast<double>(edges) : 0.0;
}

// Called by every thread of a region: the rows of K for the undirected edges whose half-edge h
// (from i, to j) satisfies is_edge(h), in increasing h in every row, as a serial scatter over h
// gives them. fill(h, i, j, a, b) then writes the entries a of row i and b of row j beyond their
// column; op.column and op.weight are sized by one thread in between, which also calls
// sized(entries). Ends with a barrier.
template <class IsEdge, class Sized, class Fill>
void scatter_rows(const HalfEdgeMesh& mesh, IsEdge is_edge, Sized sized, Fill fill,
                  detail::BucketFill& rows, const detail::Team& team, SparseOperator& op) {
    const int n = mesh.num_vertices();
    const int f0 = team.begin(mesh.num_faces()), f1 = team.end(mesh.num_faces());
    const std::vector<Triangle>& faces = mesh.faces();
    int* position = rows.clear(team, n);
    for (int f = f0; f < f1; ++f)
        for (int k = 0; k < 3; ++k)
            if (is_edge(3 * f + k)) {
                ++position[faces[f][k]];
                ++position[faces[f][(k + 1) % 3]];
            }
    rows.to_positions(team, op.row_start.data());
    FAIRING_PRAGMA(omp single)
    {
        op.column.resize(op.row_start[n]);
        op.weight.resize(op.row_start[n]);
        sized(op.row_start[n]);
    }
    for (int f = f0; f < f1; ++f)
        for (int k = 0; k < 3; ++k)
            if (is_edge(3 * f + k)) {
                const int i = faces[f][k], j = faces[f][(k + 1) % 3];
                const int a = position[i]++, b = position[j]++;
                op.column[a] = j;
                op.column[b] = i;
                fill(3 * f + k, i, j, a, b);
            }
    detail::barrier();
}

// Insertion sort of a vertex's few faces.
void sort_small(std::vector<int>& v) {
    for (std::size_t i = 1; i < v.size(); ++i) {
        const int x = v[i];
        std::size_t j = i;
        for (; j > 0 && v[j - 1] > x; --j) v[j] = v[j - 1];
        v[j] = x;
    }
}

}  // namespace

double SparseOperator::diagonal(int i) const {
    double sum = 0;
    for (int k = row_start[i]; k < row_start[i + 1]; ++k) sum += weight[k];
    return -sum;
}

void SparseOperator::apply_k(const Positions& x, Positions& y) const {
    y.resize(size(), 3);
    double* ys = y.data();
    detail::for_each_k_row(*this, x, [ys](int i, double s0, double s1, double s2) {
        ys[3 * i] = s0;
        ys[3 * i + 1] = s1;
        ys[3 * i + 2] = s2;
    });
}

void SparseOperator::apply_l(const Positions& x, Positions& y) const {
    y.resize(size(), 3);
    double* ys = y.data();
    const double* m = mass.data();
    detail::for_each_k_row(*this, x, [ys, m](int i, double s0, double s1, double s2) {
        const double inverse = m[i] > 0 ? 1.0 / m[i] : 0.0;
        ys[3 * i] = s0 * inverse;
        ys[3 * i + 1] = s1 * inverse;
        ys[3 * i + 2] = s2 * inverse;
    });
}

double mean_edge_length(const HalfEdgeMesh& mesh, const Positions& positions, int threads) {
    const int team_size = detail::threads_for(mesh.num_vertices(), threads);
    (void)team_size;
    std::vector<double> sum(length_chunks(mesh));
    std::vector<int> count(sum.size());
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1))
    edge_length_chunks(mesh, positions, sum.data(), count.data());
    return mean_of_chunks(sum, count);
}

namespace {

// Sliver faces (an angle below 3 degrees or above 177) give cotangent weights many times those of
// their neighbours, of either sign, and the linear solves crawl on them; needles (an angle below
// 0.01 rad) give up to a million times, and CG stalled near 1e-7 on CGAL's camel (20 k faces,
// the curvature flow's one-click settings, noise 0.1 / 0.5 / 0.25 iso edge) uncapped and with a
// cap of 1e3. Every cotangent of eq. 14 is therefore clamped to +-kCotangentCap (operators.h),
// pmp-library's bound. It was 100, for needles only; at 19.1 the slivers between the two (0-0.8 %
// of the faces of the study's noisy scans, at most one on its shapes with noise along the
// normals) no longer stall the solves, and the study's best errors moved by -2.8 % to +2.3 %
// (bench/results/issue12/preconditioners.md, "Slivers"). The one-click curvature flow, two
// threads: 1 M-face torus with 0.25 edge of noise in all directions 24.1 -> 16.3 s (Gauss-Seidel
// 237 / 343 / 343 / 333 iterations; now 204, then V-cycles 52 / 51 / 48: the later steps are no
// longer needle-rich, solver.cpp), the raw-triangulation dragon (1.3 M faces, noise along the
// normals) 23.2 -> 18.5 s.

// Caps a sliver's cotangents at +-kCotangentCap, keeping its share of the stiffness positive
// semi-definite: a triangle's cotangent form is so iff c0 c1 + c1 c2 + c2 c0 >= 0 (it is 1 for
// exact cotangents), and if capping broke that, its negative weights (the obtuse corner's) are
// dropped, which leaves non-negative ones.
void cap_sliver(double* cot) {
    for (int k = 0; k < 3; ++k) cot[k] = std::max(-kCotangentCap, std::min(kCotangentCap, cot[k]));
    if (cot[0] * cot[1] + cot[1] * cot[2] + cot[2] * cot[0] >= 0) return;
    for (int k = 0; k < 3; ++k) cot[k] = std::max(0.0, cot[k]);
}

// Cotangents of the corners opposite each half-edge of this thread's share of the faces (eq. 14),
// and twice their area (into twice_area, one thread per face) or their area added to their
// vertices (into area, one thread only); faces of zero area, which the paper says to skip
// (section 5.4), get zeros and are counted, as are needles (|cot| > kNeedleCotangent); every
// sliver's cotangents are capped (cap_sliver).
void cotangent_pass(const HalfEdgeMesh& mesh, const Positions& positions, const detail::Team& team,
                    double* cot_opposite, double* twice_area, double* area, long long& zero_area,
                    long long& needles) {
    const std::vector<Triangle>& faces = mesh.faces();
    const int num_faces = mesh.num_faces();
    for (int f = team.begin(num_faces), f1 = team.end(num_faces); f < f1; ++f) {
        const Triangle& t = faces[f];
        const Vec3 p[3] = {detail::row(positions, t[0]), detail::row(positions, t[1]),
                           detail::row(positions, t[2])};
        if (detail::is_zero_area(p[0], p[1], p[2])) {
            ++zero_area;
            for (int k = 0; k < 3; ++k) cot_opposite[3 * f + k] = 0;
            if (twice_area) twice_area[f] = 0;
            continue;
        }
        const double twice = (p[1] - p[0]).cross(p[2] - p[0]).norm();
        double largest_cot = 0;
        for (int k = 0; k < 3; ++k) {
            // Half-edge 3f+k runs p[k] -> p[k+1]; its opposite corner is p[k+2].
            const Vec3& c = p[(k + 2) % 3];
            const Vec3 u = p[k] - c, v = p[(k + 1) % 3] - c;
            cot_opposite[3 * f + k] = u.dot(v) / twice;
            largest_cot = std::max(largest_cot, std::abs(cot_opposite[3 * f + k]));
        }
        if (largest_cot > kNeedleCotangent) ++needles;
        if (largest_cot > kCotangentCap) cap_sliver(cot_opposite + 3 * f);
        if (twice_area) twice_area[f] = twice;
        else if (area)
            for (int k = 0; k < 3; ++k) area[t[k]] += 0.5 * twice;
    }
}

// Area of the faces around a vertex, added in increasing face order (so the same on any number
// of threads), from the leaving faces of its row's entries (see assemble); star is work space.
double star_area(const HalfEdgeMesh& mesh, const int* leaving_face, int entries,
                 const double* twice_area, std::vector<int>& star) {
    star.clear();
    for (int k = 0; k < entries; ++k) {
        const int f = leaving_face[k];
        if (f >= 0) {
            star.push_back(f);
        } else if (f <= -2) {
            star.push_back(HalfEdgeMesh::face(-2 - f));
            star.push_back(HalfEdgeMesh::face(mesh.twin(-2 - f)));
        }
    }
    sort_small(star);
    double sum = 0;
    for (int f : star) sum += 0.5 * twice_area[f];
    return sum;
}

// M_ii of row v: eq. 7, 11 or 14, or section 5.5 when normalized (the area of the curvature
// flow from `area`, or gathered from the row's leaving faces when gather_area). The
// scale-dependent row's weights, |e| until now, become 1/|e|.
double vertex_mass(Operator op, bool normalized, bool gather_area, int v, SparseOperator& result,
                   const double* area, const HalfEdgeMesh& mesh, const int* leaving_face,
                   const double* twice_area, std::vector<int>& star) {
    const int begin = result.row_start[v], end = result.row_start[v + 1];
    double mass = 0;
    if (op == Operator::ScaleDependent) {
        for (int k = begin; k < end; ++k) {
            mass += result.weight[k];
            result.weight[k] = 1.0 / result.weight[k];
        }
        mass *= 0.5;  // E/2, eq. 11
    }
    if (normalized) {  // section 5.5
        mass = 0;
        for (int k = begin; k < end; ++k) mass += result.weight[k];
    } else if (op == Operator::Umbrella) {
        mass = end - begin;  // the valence
    } else if (op == Operator::CurvatureFlow && !gather_area) {
        mass = 4.0 * area[v];  // 4A, eq. 14
    } else if (op == Operator::CurvatureFlow) {
        mass = 4.0 * star_area(mesh, leaving_face + begin, end - begin, twice_area, star);
    }
    return mass;
}

// Sorts row v of K by column, after its mass has added its weights up in the order they came:
// the Gauss-Seidel sweeps (sweeps.h) take a row's couplings before and after the
// diagonal as two runs, and the products gather their neighbours in increasing order.
void sort_row(SparseOperator& result, int v) {
    int* column = result.column.data();
    double* weight = result.weight.data();
    for (int k = result.row_start[v] + 1; k < result.row_start[v + 1]; ++k) {
        const int j = column[k];
        const double w = weight[k];
        int l = k;
        for (; l > result.row_start[v] && column[l - 1] > j; --l) {
            column[l] = column[l - 1];
            weight[l] = weight[l - 1];
        }
        column[l] = j;
        weight[l] = w;
    }
}

// Drops the edges of massless vertices so that K stays symmetric and the system stays positive
// definite (their neighbours then see them as missing neighbours). Rare: serial.
void drop_massless(SparseOperator& result) {
    const int n = result.size();
    int kept = 0;
    for (int v = 0; v < n; ++v) {
        const int begin = result.row_start[v], end = result.row_start[v + 1];
        result.row_start[v] = kept;
        if (result.mass[v] == 0) continue;
        for (int k = begin; k < end; ++k)
            if (result.mass[result.column[k]] != 0) {
                result.column[kept] = result.column[k];
                result.weight[kept++] = result.weight[k];
            }
    }
    result.row_start[n] = kept;
    result.column.resize(kept);
    result.weight.resize(kept);
}

// Counts the vertices whose mass is below kNegligibleArea times the mean positive mass as
// massless (mass 0) and returns how many there were. Serial, in vertex order: the same on any
// number of threads.
int drop_negligible_masses(SparseOperator& result) {
    double sum = 0;
    int with_mass = 0;
    for (double m : result.mass)
        if (m > 0) {
            sum += m;
            ++with_mass;
        }
    if (with_mass == 0) return 0;
    const double least = kNegligibleArea * (sum / with_mass);
    int dropped = 0;
    for (double& m : result.mass)
        if (m > 0 && m < least) {
            m = 0;
            ++dropped;
        }
    return dropped;
}

}  // namespace

// One parallel region: per-face cotangents, the rows of K by a counting sort on the edges' end
// points (each edge weighed once, in increasing order, where it is scattered), then the mass
// row by row. Each vertex so adds its terms in the order of the serial loops (edges by
// increasing half-edge, faces by increasing index for the area) on any number of threads.
SparseOperator assemble(Operator op, const HalfEdgeMesh& mesh, const Positions& positions,
                        bool normalized, AssemblyReport* report, int threads) {
    const int n = mesh.num_vertices();
    const int num_faces = mesh.num_faces();
    AssemblyReport local;
    AssemblyReport& r = report ? *report : local;
    r = AssemblyReport{};
    const bool curvature = op == Operator::CurvatureFlow;
    const bool scale_dependent = op == Operator::ScaleDependent;
    const bool area_mass = curvature && !normalized;
    const int team_size = detail::threads_for(n, threads);
    (void)team_size;

    // Cotangents of the corners opposite each half-edge (eq. 14) and twice the area of each
    // face, zero on faces of zero area, which the paper says to skip (section 5.4).
    const std::vector<Triangle>& faces = mesh.faces();
    // Plain arrays: each thread first touches its own part, rather than one thread zeroing all.
    std::unique_ptr<double[]> cot_opposite(new double[curvature ? mesh.num_half_edges() : 0]);
    // The area around each vertex adds its faces in increasing order. One thread scatters them
    // from the face pass. Several gather them row by row: per entry of K, the face around the
    // row's vertex that holds the edge's half-edge leaving that vertex (-1 for none, -2 - h when
    // both half-edges leave it, the orientation being inconsistent), sorted.
    const bool gather_area = area_mass && team_size > 1;
    std::vector<double> area(area_mass && !gather_area ? n : 0);
    std::unique_ptr<double[]> twice_area(new double[gather_area ? num_faces : 0]);
    std::unique_ptr<int[]> leaving_face;
    std::vector<double> length_sum(scale_dependent ? length_chunks(mesh) : 0);
    std::vector<int> length_count(length_sum.size());
    SparseOperator result;
    result.row_start.resize(n + 1);
    result.mass.resize(n);
    detail::BucketFill rows(n, team_size);
    long long zero_area = 0, needles = 0, floored = 0, massless = 0;
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1)
                   reduction(+ : zero_area, needles, floored))
    {
        const detail::Team team = detail::this_team();
        if (curvature)
            cotangent_pass(mesh, positions, team, cot_opposite.get(),
                           gather_area ? twice_area.get() : nullptr,
                           area_mass && !gather_area ? area.data() : nullptr, zero_area, needles);
        double mean_edge = 0;
        if (scale_dependent) {
            edge_length_chunks(mesh, positions, length_sum.data(), length_count.data());
            detail::barrier();
            mean_edge = mean_of_chunks(length_sum, length_count);
        }
        const auto is_edge = [&mesh](int h) { return is_representative(mesh, h); };
        const auto fill = [&](int h, int i, int j, int a, int b) {
            const int t = mesh.twin(h);
            double w = 1.0;
            if (scale_dependent) {
                double length = (positions.row(j) - positions.row(i)).norm();
                if (!(length >= kDuplicateEdge * mean_edge)) ++floored;
                if (!(length >= kShortEdge * mean_edge)) length = kShortEdge * mean_edge;
                w = length;  // 1/length once the row has added it up
            } else if (curvature) {
                w = cot_opposite[h] + (t >= 0 ? cot_opposite[t] : 0.0);
                if (gather_area) {
                    const int f = HalfEdgeMesh::face(h), g = HalfEdgeMesh::face(t);
                    const bool twin_leaves_from = t >= 0 && faces[g][t % 3] == i;
                    leaving_face[a] = twin_leaves_from ? -2 - h : f;
                    leaving_face[b] = t >= 0 && !twin_leaves_from ? g : -1;
                }
            }
            result.weight[a] = result.weight[b] = w;
        };
        const auto sized = [&](int entries) {
            if (gather_area) leaving_face.reset(new int[entries]);
        };
        scatter_rows(mesh, is_edge, sized, fill, rows, team, result);

        std::vector<int> star;  // faces around the vertex, increasing
        FAIRING_PRAGMA(omp for schedule(static) reduction(+ : massless))
        for (int v = 0; v < n; ++v) {
            double mass = vertex_mass(op, normalized, gather_area, v, result,
                                      area.empty() ? nullptr : area.data(), mesh,
                                      leaving_face.get(), twice_area.get(), star);
            // A vertex without mass cannot take part; its edges are dropped below.
            if (!(mass > 0) && !mesh.is_isolated(v)) {
                mass = 0;
                ++massless;
            }
            result.mass[v] = mass;
            sort_row(result, v);
        }
    }
    r.zero_area_faces = static_cast<int>(zero_area);
    r.needle_faces = static_cast<int>(needles);
    r.floored_edges = static_cast<int>(floored);
    r.massless_vertices = static_cast<int>(massless);
    if (area_mass) r.negligible_vertices = drop_negligible_masses(result);

    if (massless > 0 || r.negligible_vertices > 0) drop_massless(result);
    result.unit_weights = op == Operator::Umbrella &&
                          std::all_of(result.weight.begin(), result.weight.end(),
                                      [](double w) { return w == 1.0; });
    return result;
}

SparseOperator assemble_boundary_curve(const HalfEdgeMesh& mesh, const Positions& positions,
                                       int threads) {
    const int n = mesh.num_vertices();
    const int team_size = detail::threads_for(n, threads);
    (void)team_size;
    std::vector<double> length_sum(length_chunks(mesh));
    std::vector<int> length_count(length_sum.size());
    SparseOperator result;
    result.row_start.resize(n + 1);
    result.mass.resize(n);
    detail::BucketFill rows(n, team_size);
    FAIRING_PRAGMA(omp parallel num_threads(team_size) if(team_size > 1))
    {
        const detail::Team team = detail::this_team();
        edge_length_chunks(mesh, positions, length_sum.data(), length_count.data());
        detail::barrier();
        const double mean_edge = mean_of_chunks(length_sum, length_count);
        const auto fill = [&](int, int i, int j, int a, int b) {
            result.weight[a] = result.weight[b] = std::max(
                (positions.row(j) - positions.row(i)).norm(), kShortEdge * mean_edge);
        };
        scatter_rows(mesh, [&mesh](int h) { return mesh.is_boundary(h); }, [](int) {}, fill,
                     rows, team, result);
        FAIRING_PRAGMA(omp for schedule(static))
        for (int v = 0; v < n; ++v) {
            double mass = 0;
            for (int k = result.row_start[v]; k < result.row_start[v + 1]; ++k) {
                mass += 0.5 * result.weight[k];  // E/2 over the two boundary neighbours
                result.weight[k] = 1.0 / result.weight[k];
            }
            result.mass[v] = mass;
        }
    }
    return result;
}

}  // namespace fairing
