// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The tool's vcg mesh type. It mirrors MeshLab's CMeshO where the result depends on it (float
// coordinates, per-vertex quality and flags), so a run gives the positions the filter gives in
// MeshLab; normals and colours are there to be carried from the input to the output.
#pragma once

#include <vcg/complex/complex.h>

#include <vector>

namespace implicit_fairing {

class CVertex;
class CFace;
struct CUsedTypes : public vcg::UsedTypes<vcg::Use<CVertex>::AsVertexType,
                                          vcg::Use<CFace>::AsFaceType> {};
class CVertex : public vcg::Vertex<CUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                   vcg::vertex::Color4b, vcg::vertex::Qualityf,
                                   vcg::vertex::BitFlags> {};
class CFace : public vcg::Face<CUsedTypes, vcg::face::VertexRef, vcg::face::Normal3f,
                               vcg::face::Color4b, vcg::face::BitFlags> {};
class CMesh : public vcg::tri::TriMesh<std::vector<CVertex>, std::vector<CFace>> {};

}  // namespace implicit_fairing
