#include "fairing/operators.h"

#include "geometry.h"
#include "kernels.h"

#include <cmath>

namespace fairing {
namespace {

// Undirected edge (i, j) with its weight, one per edge of the mesh.
struct WeightedEdge {
    int i, j;
    double w;
};

SparseOperator from_edges(int n, const std::vector<WeightedEdge>& edges,
                          std::vector<double> mass) {
    SparseOperator op;
    op.row_start.assign(n + 1, 0);
    for (const WeightedEdge& e : edges) {
        ++op.row_start[e.i + 1];
        ++op.row_start[e.j + 1];
    }
    for (int i = 0; i < n; ++i) op.row_start[i + 1] += op.row_start[i];
    op.column.resize(op.row_start[n]);
    op.weight.resize(op.row_start[n]);
    std::vector<int> fill(op.row_start.begin(), op.row_start.end() - 1);
    for (const WeightedEdge& e : edges) {
        op.column[fill[e.i]] = e.j;
        op.weight[fill[e.i]++] = e.w;
        op.column[fill[e.j]] = e.i;
        op.weight[fill[e.j]++] = e.w;
    }
    op.mass = std::move(mass);
    return op;
}

// Edges shorter than this fraction of the mean edge are lengthened to it where 1/|e| is taken:
// duplicated vertices would otherwise give infinite weights.
constexpr double kEdgeFloor = 1e-4;

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

double mean_edge_length(const HalfEdgeMesh& mesh, const Positions& positions) {
    double sum = 0;
    long long count = 0;
    for (int h = 0; h < mesh.num_half_edges(); ++h) {
        if (mesh.twin(h) >= 0 && mesh.twin(h) < h) continue;
        sum += (positions.row(mesh.to(h)) - positions.row(mesh.from(h))).norm();
        ++count;
    }
    return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

SparseOperator assemble(Operator op, const HalfEdgeMesh& mesh, const Positions& positions,
                        bool normalized, AssemblyReport* report) {
    const int n = mesh.num_vertices();
    AssemblyReport local;
    AssemblyReport& r = report ? *report : local;
    r = AssemblyReport{};

    // Cotangents of the corners opposite each half-edge (eq. 14), zero on faces of zero area,
    // which the paper says to skip (section 5.4).
    std::vector<double> cot_opposite;
    std::vector<double> area;
    if (op == Operator::CurvatureFlow) {
        cot_opposite.assign(mesh.num_half_edges(), 0.0);
        area.assign(n, 0.0);
        for (int f = 0; f < mesh.num_faces(); ++f) {
            const Triangle& t = mesh.faces()[f];
            const Vec3 p[3] = {detail::row(positions, t[0]), detail::row(positions, t[1]),
                               detail::row(positions, t[2])};
            if (detail::is_zero_area(p[0], p[1], p[2])) {
                ++r.zero_area_faces;
                continue;
            }
            const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
            double largest_cot = 0;
            for (int k = 0; k < 3; ++k) {
                // Half-edge 3f+k runs p[k] -> p[k+1]; its opposite corner is p[k+2].
                const Vec3& c = p[(k + 2) % 3];
                const Vec3 u = p[k] - c, v = p[(k + 1) % 3] - c;
                cot_opposite[3 * f + k] = u.dot(v) / twice_area;
                largest_cot = std::max(largest_cot, std::abs(cot_opposite[3 * f + k]));
                area[t[k]] += 0.5 * twice_area;
            }
            if (largest_cot > 1e4) ++r.needle_faces;
        }
    }

    const double mean_edge = mean_edge_length(mesh, positions);
    std::vector<WeightedEdge> edges;
    edges.reserve(mesh.num_half_edges() / 2 + 1);
    std::vector<double> length_sum(op == Operator::ScaleDependent ? n : 0, 0.0);
    for (int h = 0; h < mesh.num_half_edges(); ++h) {
        const int t = mesh.twin(h);
        if (t >= 0 && t < h) continue;
        const int i = mesh.from(h), j = mesh.to(h);
        double w = 1.0;
        if (op == Operator::ScaleDependent) {
            double length = (positions.row(j) - positions.row(i)).norm();
            if (!(length >= kEdgeFloor * mean_edge)) {
                length = kEdgeFloor * mean_edge;
                ++r.floored_edges;
            }
            w = 1.0 / length;
            length_sum[i] += length;
            length_sum[j] += length;
        } else if (op == Operator::CurvatureFlow) {
            w = cot_opposite[h] + (t >= 0 ? cot_opposite[t] : 0.0);
        }
        edges.push_back({i, j, w});
    }

    std::vector<double> mass(n, 0.0);
    if (normalized) {
        for (const WeightedEdge& e : edges) {
            mass[e.i] += e.w;
            mass[e.j] += e.w;
        }
    } else if (op == Operator::Umbrella) {
        for (const WeightedEdge& e : edges) {
            mass[e.i] += 1;
            mass[e.j] += 1;
        }
    } else if (op == Operator::ScaleDependent) {
        for (int i = 0; i < n; ++i) mass[i] = 0.5 * length_sum[i];  // E/2, eq. 11
    } else {
        for (int i = 0; i < n; ++i) mass[i] = 4.0 * area[i];  // 4A, eq. 14
    }

    // A vertex without mass cannot take part; drop its edges so that K stays symmetric and the
    // system stays positive definite (its neighbours then see it as a missing neighbour).
    std::vector<char> massless(n, 0);
    for (int i = 0; i < n; ++i)
        if (!(mass[i] > 0) && !mesh.is_isolated(i)) {
            massless[i] = 1;
            mass[i] = 0;
            ++r.massless_vertices;
        }
    if (r.massless_vertices > 0) {
        std::vector<WeightedEdge> kept;
        kept.reserve(edges.size());
        for (const WeightedEdge& e : edges)
            if (!massless[e.i] && !massless[e.j]) kept.push_back(e);
        edges.swap(kept);
    }
    return from_edges(n, edges, std::move(mass));
}

SparseOperator assemble_boundary_curve(const HalfEdgeMesh& mesh, const Positions& positions) {
    const int n = mesh.num_vertices();
    const double mean_edge = mean_edge_length(mesh, positions);
    std::vector<WeightedEdge> edges;
    std::vector<double> mass(n, 0.0);
    for (int h = 0; h < mesh.num_half_edges(); ++h) {
        if (!mesh.is_boundary(h)) continue;
        const int i = mesh.from(h), j = mesh.to(h);
        const double length =
            std::max((positions.row(j) - positions.row(i)).norm(), kEdgeFloor * mean_edge);
        edges.push_back({i, j, 1.0 / length});
        mass[i] += 0.5 * length;  // E/2 over the two boundary neighbours
        mass[j] += 0.5 * length;
    }
    return from_edges(n, edges, std::move(mass));
}

}  // namespace fairing
