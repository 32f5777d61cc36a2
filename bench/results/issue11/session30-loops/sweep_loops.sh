#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# sweep_loops.sh OUTDIR MESH...: the one-click settings (umbrella L2 x4, scale-dependent L2 x2,
# curvature L2 x4, automatic strength) with the fixed boundary and with SmoothCurve, one JSON file
# per case. BIN: the instrumented build's bin (instrumentation.diff); SUF: the inputs' seed suffix.
M=~/.cache/filter_implicit_fairing/bench-meshes; B=${BIN:?set BIN to the instrumented build's bin}; out=$1; shift; mkdir -p $out
for m in "$@"; do t=mesh; [ $m = plane_3k ] && t=plane
for nz in n0.1 n0.25 n0.5 iso0.25; do for cfg in "umbrella 2 4" "scale-dependent 2 2" "curvature 2 4"; do set -- $cfg
  for bd in fixed curve; do f=$out/${m}_${nz}_$1_$bd.json; [ -s $f ] && continue
    extra=; [ $bd = curve ] && extra=--smooth-boundary
    $B/fairing-denoise-tool sweep $M/dn_${m}_${nz}${SUF:-_s13}.ply $M/dn_${m}_clean.ply $t $1 $2 $3 1 --auto --ts 1e-9 $extra | grep '"auto"' > $f
  done; done; done; done
