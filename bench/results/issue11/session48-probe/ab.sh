#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# A/B timing of two CLIs on a cost mesh (auto-gap.md section 48): BASE and NEW alternate ROUNDS
# times, on THREADS threads (1 by default); each run prints its strength_seconds, seconds_engine,
# time step and Lanczos steps; then whether the two outputs are the same bytes. Extra arguments
# go to both.
# Usage: BASE=<cli at HEAD> NEW=<cli with the change> sh ab.sh --recompute
M=$HOME/.cache/filter_implicit_fairing/bench-meshes
mesh=${MESH:-bunny_loop2_1.2m}
export OMP_NUM_THREADS=${THREADS:-1}
for r in $(seq ${ROUNDS:-2}); do
for b in base new; do
  if [ $b = new ]; then C=${NEW:-build/bin/implicit-fairing}; else C=$BASE; fi
  $C $M/dn_${mesh}_n0.25.ply /tmp/ab_$b.ply --operator ${OP:-curvature} --threads ${THREADS:-1} --json -q "$@" | tail -1 | python3 -c "import sys,json; d=json.load(sys.stdin); print('$b', d['strength_seconds'], d['seconds_engine'], d['time_step'], d['strength_iterations'] if 'strength_iterations' in d else '')"
done; done
cmp /tmp/ab_base.ply /tmp/ab_new.ply && echo identical
