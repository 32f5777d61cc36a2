// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Volume and area of mesh components, and their exact restoration (sections 3.1-3.2).
//
// Conventions: the volume of a closed, outward-oriented component is positive (eq. 10); it is
// computed on coordinates relative to a reference point of the component so that it stays
// accurate far from the origin. Restoration acts on one component at a time.
#pragma once

#include "fairing/fairing.h"
#include "fairing/half_edge.h"

namespace fairing {

// Eq. 10: V = 1/6 sum_k g_k . N_k over the component's faces, summed in fixed blocks of faces
// (the same bits on any number of threads; threads as Options::threads, one below 50 k faces).
double component_volume(const HalfEdgeMesh& mesh, const Component& component,
                        const Positions& positions, int threads = 1);
double component_area(const HalfEdgeMesh& mesh, const Component& component,
                      const Positions& positions, int threads = 1);

// The centroid restore_measure scales about: of the enclosed solid (closed component) or of the
// surface (open one).
Vec3 component_centroid(const HalfEdgeMesh& mesh, const Component& component,
                        const Positions& positions);

// The largest relative change of the measure VolumeRestoration::NormalOffset restores by an
// offset on a component without fixed vertices; beyond it (a collapsing component, whose offset
// surface would fold over itself) the component is scaled.
constexpr double kMaxOffsetChange = 0.1;

// Restores `target` (volume for closed components, area for open ones) on one component.
// With fixed vertices, or with VolumeRestoration::NormalOffset while |target/now - 1| <=
// max_offset_change (kMaxOffsetChange unless given): offsets every free vertex of the component
// by t * n_i (area-weighted vertex normal) with t solved to machine precision, so fixed vertices
// do not move. Otherwise (or if no t is found and nothing is fixed): scales about the centroid
// (the solid's for volume, the surface's for area) by (target/now)^(1/3) or ^(1/2). Returns the
// method used. Throws Error if a component with fixed vertices cannot be restored. `threads` as
// for component_volume (the result does not depend on it). `shape` (per vertex, optional): the
// offset is t shape_i n_i (Options::shaped_offset); the measure is restored as exactly.
Restoration restore_measure(const HalfEdgeMesh& mesh, const Component& component,
                            const std::vector<char>& free, double target, Positions& positions,
                            VolumeRestoration how = VolumeRestoration::NormalOffset,
                            int threads = 1, const std::vector<double>* shape = nullptr,
                            double max_offset_change = kMaxOffsetChange);

}  // namespace fairing
