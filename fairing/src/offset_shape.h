// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Where the curvature flow's volume restoration puts the volume back (Options::shaped_offset;
// not installed).
//
// The flow of eq. 14 moves each vertex by its mean curvature, so a step takes the volume from
// the convex, strongly curved parts (the outer rim of a torus, a thin limb) and a uniform normal
// offset puts it back everywhere: on the torus with a quarter edge of noise the restored result
// errs 12 % more than one restored where the volume went (bench/results/issue11/auto-gap.md,
// section 23). The offset fair() then uses is t w_i n_i with w_i from the input alone:
//   1. a pilot: the input after one implicit first-order curvature step at time step
//      kPilotTimeStep (lambda_dt in mean edges squared), its volume restored by the uniform
//      offset, as fair() would;
//   2. its mean curvature, H_i = -n_i . (L x)_i (eq. 14's L at the pilot, cotangents clamped as
//      the operator clamps them; area-weighted vertex normals), smoothed over the mesh's edges
//      by kShapeSmoothingPasses half steps to the one-ring mean;
//   3. shrunk towards its component's mean by the share of its variance that the noise does not
//      explain (James and Stein's shrinkage, with the noise's part measured, not modelled): the
//      same recipe on the input plus a second draw of Gaussian noise along the normals at the
//      estimated level gives a second field, and var(second - first) / var(first) is the noise's
//      share. A share kept below kLeastShare counts as none: on a sphere sampled at two densities
//      the discrete curvature's own variation with the sampling reads as signal (up to 0.46 kept
//      on the study's spheres, whose offset should be uniform; the torus and the scans keep 0.64
//      and more, but at 1 edge of noise the torus 0.04);
//   4. clamped at 0 (no vertex is pushed inwards to restore volume) and scaled to mean 1 over the
//      component's data vertices.
// A component whose share counts as none keeps the uniform offset (w = 1 exactly), so a sphere
// restores as before, bit for bit.
//
// The automatic strength models this offset for the first-order flow only, whose loss per step is
// its mean curvature times the step, the field this shape follows: there the model restores as
// fair() will, and the choice follows the shape's lower errors (the study's first-order curvature
// rows 0.968 of the uniform model's errors in geometric mean, the torus's down to 0.65;
// auto-gap.md, section 25). The L^2 flow's loss is a fourth-order field that the shape follows
// less well: on a torus the shape makes strong L^2 steps nearly harmless to the estimate's linear
// model while the true error still rises, so a modelled shape let the choice run away (the demo's
// torus: 794 instead of 69, twice the error; section 24). There the estimate models the uniform
// offset, and at its choice the shape restores 3-8 % closer on tori, up to 4 % on scans.
//
// Conventions: rows past `data_vertices` (virtual vertices) are not data and get no weight; only
// vertices of restored closed components (component_of >= 0) get one; the others' entries are 1.
#pragma once

#include "fairing/fairing.h"
#include "fairing/half_edge.h"
#include "fairing/operators.h"

#include <functional>
#include <vector>

namespace fairing {
namespace detail {

// The pilot's time step and smoothing, and the least share of variance counted as signal:
// chosen in session 23 and 24 on the denoising study's meshes (auto-gap.md, sections 23-24).
constexpr double kPilotTimeStep = 8;
constexpr int kShapeSmoothingPasses = 64;
constexpr double kLeastShare = 0.6;

struct OffsetShapeProblem {
    const HalfEdgeMesh* mesh = nullptr;       // the data vertices' mesh
    const SparseOperator* op = nullptr;       // the curvature operator at x (all rows of x)
    const Positions* x = nullptr;             // positions, virtual vertices after the data
    const std::vector<char>* free = nullptr;  // the surface system's unknowns (mass > 0)
    const std::vector<double>* weight = nullptr;  // soft weights of the data vertices; null: 1
    int data_vertices = 0;
    double mean_edge = 0;        // of x's data vertices
    double noise_level = 0;      // sigma along the normals, in the mesh's units
    // Per data vertex the restored closed component's index, -1 for none; `components` of them.
    std::vector<int> component_of;
    int components = 0;
    // The curvature operator at other positions (same rows), and fair()'s uniform restoration of
    // the restored components' volume (false: it failed; the offset then stays uniform).
    std::function<SparseOperator(const Positions&)> assemble_at;
    std::function<bool(Positions&)> restore;
    double tolerance = 1e-6;
    int max_iterations = 2000;
    std::function<void(double)> progress;  // fraction of the shape's work done, in [0, 1]
};

// What the shape found: w per data vertex (empty when every component keeps the uniform
// offset), and per component the share of the field's variance kept as signal (0: uniform; for
// tests and studies).
struct OffsetShape {
    std::vector<double> weight;
    std::vector<double> kept_share;
};

// Throws Error when a pilot's solve produces non-finite values; a pilot that does not converge
// or an operator that loses a free row's mass leaves the offset uniform.
OffsetShape curvature_offset_shape(const OffsetShapeProblem& p);

}  // namespace detail
}  // namespace fairing
