#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: the Z-order and the breadth-first numbering on a larger scattered mesh,
# the bunny Loop-subdivided three times (2.4 M vertices) at a quarter edge: four curvature L^2
# steps at time step 20, BASE and NEW alternating ROUNDS times on one thread; each run prints its
# CG iterations and engine seconds.
# Usage: BASE=<cli of 0d68cf9> NEW=<cli of 00e8039> sh big_order.sh
B=${B:-$HOME/.cache/filter_implicit_fairing/bench-build/bench/bin}
M=$HOME/.cache/filter_implicit_fairing/bench-meshes
in=/tmp/bunny_l3_n0.25.ply
if [ ! -f "$in" ]; then
  "$B/fairing-bench-tool" loop "$M/bunny00.off" /tmp/bunny_l3_clean.ply 3
  "$B/fairing-denoise-tool" noise /tmp/bunny_l3_clean.ply "$in" 0.25 1 normal
fi
export OMP_NUM_THREADS=1
for r in $(seq "${ROUNDS:-2}"); do
  for which in base new; do
    if [ $which = base ]; then C=$BASE; else C=$NEW; fi
    "$C" "$in" /tmp/big_$which.ply --operator curvature --time-step 20 --threads 1 --json -q |
      tail -1 | python3 -c "import sys,json; d=json.load(sys.stdin); print('$which', d['cg_iterations'], d['seconds_engine'])"
  done
done
