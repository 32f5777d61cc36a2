#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 51: what the sketch's rows cost. CLIS are builds with rows_and_seed.patch
# (of 6e22706, and of 5fdf95d for the prefetch); per round, each CLI's one click (the curvature
# flow's default) on each cost mesh with XROWS=8192 (the engine's sketch) and each of ROWS in
# turn, ROUNDS rounds, on THREADS threads (1 by default); each run prints the mesh, the CLI, the
# rows, strength_seconds, seconds_engine, the time step and the Lanczos steps.
# Usage: CLIS="/tmp/cli_rows /tmp/cli_rows_pf" ROWS="32768" ROUNDS=2 sh rows_ab.sh [mesh ...]
M=${M:-$HOME/.cache/filter_implicit_fairing/bench-meshes}
THREADS=${THREADS:-1}
export OMP_NUM_THREADS=$THREADS
out=$(mktemp --suffix=.ply)
for mesh in ${*:-bunny_loop2_1.2m torus_1m}; do
  for round in $(seq "${ROUNDS:-2}"); do
    for C in $CLIS; do
      for rows in 8192 ${ROWS:-32768}; do
        XROWS=$rows "$C" "$M/dn_${mesh}_n0.25.ply" "$out" --operator curvature --threads "$THREADS" \
          --json -q | tail -1 | python3 -c "import sys,json; d=json.load(sys.stdin); print('$mesh', '$C', 'rows $rows', d['strength_seconds'], d['seconds_engine'], d['time_step'], d['strength_iterations'])"
      done
    done
  done
done
rm -f "$out"
