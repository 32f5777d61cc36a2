#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 28: for each case, RISKMIN (the minimum of RSS + 2 sigma^2 tr H over N sigma^2,
# printed by a build of riskmin.diff in BUILD) and the automatic error of umbrella L^2 x4, L^3 x2
# and L^3 x1. Usage: T=BUILD/bin/fairing-denoise-tool riskmin.sh (measurement aid).
M=~/.cache/filter_implicit_fairing/bench-meshes
T=${T:?set T to the fairing-denoise-tool of a riskmin.diff build}
for sfx in "" _s2; do
for mesh in elephant_6k fandisk_13k camel_20k dragon_20k elephant_loop1_22k torus_10k sphere2_13k; do
  truth=mesh; [ $mesh = torus_10k ] && truth=torus:1:0.4; [ $mesh = sphere2_13k ] && truth=sphere
  for noise in n0.1 n0.25 n0.5 iso0.25; do
    line="$mesh$sfx $noise"
    for cfg in "2 4" "3 2" "3 1"; do
      out=$(FAIR_RISKMIN=1 OMP_NUM_THREADS=1 $T sweep $M/dn_${mesh}_${noise}${sfx}.ply $M/dn_${mesh}_clean.ply $truth umbrella $cfg 1 --auto --ts 1 2>&1)
      r=$(echo "$out" | grep RISKMIN | tail -1 | awk '{print $2}')
      e=$(echo "$out" | grep '"kind":"auto"' | sed 's/.*"rms":\([0-9.e-]*\).*/\1/')
      line="$line | $r $e"
    done
    echo "$line"
  done
done
done
