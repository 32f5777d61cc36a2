// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Adapters between a vcg TriMesh (MeshLab's CMeshO or any mesh type built from vcg components
// with coordinates, bit flags and, for quality weights, per-vertex quality) and the engine.
//
//   vcg_adapters::IndexMap map;
//   fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m, map);      // live elements only
//   vcg_adapters::ConstraintSettings cs; cs.onlySelected = ...;
//   fairing::Constraints c = vcg_adapters::makeConstraints(m, map, cs);   // throws on misuse
//   fairing::Result r = fairing::fair(tm, c, options);                    // may throw
//   vcg_adapters::writePositions(m, map, r.positions);                    // only after success
//   vcg_adapters::updateNormalsAndBox(m);                                 // or MeshModel's own
//
// No numerics happen here. Everything that can fail (validation, the engine) runs before the
// mesh is written, so a failure leaves the vcg mesh bit-identical. Errors are fairing::Error.
#pragma once

#include <fairing/fairing.h>

#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace vcg_adapters {

// Row i of the engine's arrays is vertex rowToVertex[i] of the vcg mesh; deleted vertices have
// no row (vertexToRow == -1).
struct IndexMap {
    std::vector<int> vertexToRow;
    std::vector<std::size_t> rowToVertex;
    std::size_t liveFaces = 0;
};

// Copies the live (non-deleted) vertices and faces, converting coordinates to double once.
template <class MeshType>
fairing::TriangleMesh toTriangleMesh(const MeshType& m, IndexMap& map)
{
    map.vertexToRow.assign(m.vert.size(), -1);
    map.rowToVertex.clear();
    map.rowToVertex.reserve(m.vert.size());
    for (std::size_t i = 0; i < m.vert.size(); ++i) {
        if (m.vert[i].IsD()) continue;
        map.vertexToRow[i] = static_cast<int>(map.rowToVertex.size());
        map.rowToVertex.push_back(i);
    }

    fairing::TriangleMesh tm;
    tm.positions.resize(static_cast<Eigen::Index>(map.rowToVertex.size()), 3);
    for (std::size_t r = 0; r < map.rowToVertex.size(); ++r) {
        const auto& p = m.vert[map.rowToVertex[r]].cP();
        for (int k = 0; k < 3; ++k)
            tm.positions(static_cast<Eigen::Index>(r), k) = static_cast<double>(p[k]);
    }

    tm.triangles.reserve(m.face.size());
    for (std::size_t f = 0; f < m.face.size(); ++f) {
        const auto& face = m.face[f];
        if (face.IsD()) continue;
        if (face.VN() != 3)
            throw fairing::Error("a face with " + std::to_string(face.VN()) +
                                 " vertices: only triangle meshes are supported");
        fairing::Triangle t;
        for (int k = 0; k < 3; ++k) {
            const std::size_t vi = vcg::tri::Index(m, face.cV(k));
            if (vi >= m.vert.size() || map.vertexToRow[vi] < 0)
                throw fairing::Error("a face refers to a deleted or foreign vertex; run "
                                     "Filters > Cleaning and Repairing > Remove Unreferenced "
                                     "Vertices / compact the mesh first");
            t[k] = map.vertexToRow[vi];
        }
        tm.triangles.push_back(t);
    }
    map.liveFaces = tm.triangles.size();
    return tm;
}

template <class MeshType>
std::size_t countSelectedVertices(const MeshType& m)
{
    std::size_t n = 0;
    for (const auto& v : m.vert)
        if (!v.IsD() && v.IsS()) ++n;
    return n;
}

template <class MeshType>
std::size_t countSelectedFaces(const MeshType& m)
{
    std::size_t n = 0;
    for (const auto& f : m.face)
        if (!f.IsD() && f.IsS()) ++n;
    return n;
}

// True when something is selected (vertices or faces). Counted here: cm.svn / cm.sfn can be
// stale after other filters.
template <class MeshType>
bool hasSelection(const MeshType& m)
{
    return countSelectedVertices(m) > 0 || countSelectedFaces(m) > 0;
}

struct ConstraintSettings {
    // Only the selection moves: every other vertex is a hard constraint. The vertex selection is
    // used when there is one; otherwise the face selection is turned into a vertex selection the
    // way MeshLab's smoothers do (tri::UpdateSelection::VertexFromFaceStrict: a vertex is
    // selected when all its faces are), without touching the mesh's flags.
    bool onlySelected = false;
    // Per-vertex quality as soft-constraint weight (section 2.7): clamped to [0, 1], 0 = fixed.
    bool qualityWeights = false;
    bool invertQuality = false;     // weight = 1 - clamp(quality)
    bool qualityMeaningful = true;  // host says whether the quality holds data (MM_VERTQUALITY)
};

// What makeConstraints found, for the log.
struct ConstraintReport {
    std::string selectionSource;    // "", "vertex selection", "face selection"
    std::size_t movable = 0;        // vertices allowed to move by the selection
    std::size_t fixedBySelection = 0;
    std::size_t qualityClamped = 0; // quality values outside [0, 1]
    std::size_t zeroWeights = 0;    // weight 0: hard constraints from quality
};

template <class MeshType>
fairing::Constraints makeConstraints(const MeshType& m, const IndexMap& map,
                                     const ConstraintSettings& s, ConstraintReport* report = nullptr)
{
    ConstraintReport rep;
    fairing::Constraints c;
    const std::size_t n = map.rowToVertex.size();

    if (s.onlySelected) {
        std::vector<char> movable(n, 0);
        if (countSelectedVertices(m) > 0) {
            rep.selectionSource = "vertex selection";
            for (std::size_t r = 0; r < n; ++r)
                movable[r] = m.vert[map.rowToVertex[r]].IsS() ? 1 : 0;
        } else if (countSelectedFaces(m) > 0) {
            rep.selectionSource = "face selection";
            // strict: touched by at least one selected face and by no unselected face
            std::vector<char> bySelected(n, 0), byUnselected(n, 0);
            for (const auto& f : m.face) {
                if (f.IsD()) continue;
                for (int k = 0; k < f.VN(); ++k) {
                    const int r = map.vertexToRow[vcg::tri::Index(m, f.cV(k))];
                    if (r < 0) continue;
                    (f.IsS() ? bySelected : byUnselected)[static_cast<std::size_t>(r)] = 1;
                }
            }
            for (std::size_t r = 0; r < n; ++r) movable[r] = bySelected[r] && !byUnselected[r];
        } else {
            throw fairing::Error("\"Affect only selection\" is checked but nothing is selected; "
                                 "select vertices or faces first, or uncheck it");
        }
        c.fixed.assign(n, 0);
        for (std::size_t r = 0; r < n; ++r) {
            if (movable[r]) ++rep.movable;
            else { c.fixed[r] = 1; ++rep.fixedBySelection; }
        }
        if (rep.movable == 0)
            throw fairing::Error("\"Affect only selection\" is checked but the " +
                                 rep.selectionSource + " leaves no vertex free to move (a face "
                                 "selection moves only vertices whose faces are all selected)");
    }

    if (s.qualityWeights) {
        if (!s.qualityMeaningful)
            throw fairing::Error("\"Use vertex quality as smoothing weight\" is checked but the "
                                 "mesh has no vertex quality; compute one first (Filters > "
                                 "Quality Measure and Computations) or uncheck it");
        std::size_t nonFinite = 0, firstNonFinite = 0;
        for (std::size_t r = 0; r < n; ++r)
            if (!std::isfinite(static_cast<double>(m.vert[map.rowToVertex[r]].cQ())) &&
                nonFinite++ == 0)
                firstNonFinite = map.rowToVertex[r];
        if (nonFinite > 0)
            throw fairing::Error(std::to_string(nonFinite) +
                                 (nonFinite == 1 ? " vertex has" : " vertices have") +
                                 " a non-finite quality (NaN or Inf; the first is vertex " +
                                 std::to_string(firstNonFinite) + "): quality weights need "
                                 "finite values. Set them with Filters > Quality Measure and "
                                 "Computations > 'Per Vertex Quality Function', or uncheck "
                                 "\"Use vertex quality as smoothing weight\"");
        c.weights.resize(n);
        for (std::size_t r = 0; r < n; ++r) {
            const double q = static_cast<double>(m.vert[map.rowToVertex[r]].cQ());
            double w = q;
            if (w < 0.0) { w = 0.0; ++rep.qualityClamped; }
            else if (w > 1.0) { w = 1.0; ++rep.qualityClamped; }
            if (s.invertQuality) w = 1.0 - w;
            if (w == 0.0) ++rep.zeroWeights;
            c.weights[r] = w;
        }
    }
    if (report) *report = rep;
    return c;
}

// Writes the engine's positions back (double -> the host's scalar, converted once per
// coordinate). Checks everything first, so a bad result writes nothing.
template <class MeshType>
void writePositions(MeshType& m, const IndexMap& map, const fairing::Positions& positions)
{
    using Scalar = typename MeshType::ScalarType;
    if (static_cast<std::size_t>(positions.rows()) != map.rowToVertex.size())
        throw fairing::Error("internal error: the engine returned " +
                             std::to_string(positions.rows()) + " positions for " +
                             std::to_string(map.rowToVertex.size()) + " vertices");
    if (map.vertexToRow.size() != m.vert.size())
        throw fairing::Error("internal error: the mesh changed while it was being faired");
    std::vector<Scalar> converted(static_cast<std::size_t>(positions.rows()) * 3);
    for (Eigen::Index r = 0; r < positions.rows(); ++r)
        for (int k = 0; k < 3; ++k) {
            const Scalar x = static_cast<Scalar>(positions(r, k));
            if (!std::isfinite(x))
                throw fairing::Error("the result has a non-finite coordinate (vertex " +
                                     std::to_string(map.rowToVertex[static_cast<std::size_t>(r)]) +
                                     "); the mesh was left unchanged");
            converted[static_cast<std::size_t>(r) * 3 + static_cast<std::size_t>(k)] = x;
        }
    for (std::size_t r = 0; r < map.rowToVertex.size(); ++r) {
        auto& p = m.vert[map.rowToVertex[r]].P();
        for (int k = 0; k < 3; ++k) p[k] = converted[r * 3 + static_cast<std::size_t>(k)];
    }
}

// What MeshModel::UpdateBoxAndNormals does, for hosts without a MeshModel (command-line tools).
template <class MeshType>
void updateNormalsAndBox(MeshType& m)
{
    vcg::tri::UpdateBounding<MeshType>::Box(m);
    if (m.fn > 0) {
        vcg::tri::UpdateNormal<MeshType>::PerFaceNormalized(m);
        vcg::tri::UpdateNormal<MeshType>::PerVertexAngleWeighted(m);
    }
}

}  // namespace vcg_adapters
