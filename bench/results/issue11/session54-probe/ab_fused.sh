#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 54: the one click's estimate on the 1.2 M-face bunny (a quarter edge, the
# curvature flow's default, one thread) with the sketch's pass folded into the operator's
# (fused-settle-ahead.patch, switched on by FUSED=1) and without, alternating ROUNDS times;
# each line: mode, strength_seconds, seconds_engine, time step, Lanczos steps. Then whether the
# two outputs are the same bytes.
# Usage: CLI=<the CLI built with the patch> sh ab_fused.sh
M=${M:-$HOME/.cache/filter_implicit_fairing/bench-meshes}
export OMP_NUM_THREADS=1
for r in $(seq "${ROUNDS:-3}"); do
  for mode in two-pass fused; do
    if [ $mode = fused ]; then export FUSED=1; else unset FUSED; fi
    "$CLI" "$M/dn_bunny_loop2_1.2m_n0.25.ply" "/tmp/ab_$mode.ply" --operator curvature \
      --threads 1 --json -q | tail -1 | python3 -c "import sys,json; d=json.load(sys.stdin); \
print('$mode', d['strength_seconds'], d['seconds_engine'], d['time_step'], d['strength_iterations'])"
  done
done
cmp /tmp/ab_two-pass.ply /tmp/ab_fused.ply && echo identical
