#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 51: the sketch's draw against its layout or its rows. CLI is a build of
# 6e22706 with runs_and_seed.patch (KNOB=XRUN: the run length, 1 a row per vertex as at 6e22706,
# 512 the runs) or rows_and_seed.patch (KNOB=XROWS: the sketch's rows, 8192 at 6e22706); XSEED
# offsets the sketch's hashes. Each draw's one click (the curvature flow's default, on THREADS
# threads) and its RMS distance to the known surface (fairing-denoise-tool eval), on the mesh
# MESH of the cost set.
# Usage: CLI=/tmp/cli_hook KNOB=XRUN VALUES="1 512" SEEDS="0 1 2" sh seeds.sh
M=${M:-$HOME/.cache/filter_implicit_fairing/bench-meshes}
DT=${DT:-$HOME/.cache/filter_implicit_fairing/bench-build/bench/bin/fairing-denoise-tool}
MESH=${MESH:-torus_1m}
TRUTH=${TRUTH:-torus:1:0.4}
THREADS=${THREADS:-2}
export OMP_NUM_THREADS=$THREADS
out=$(mktemp --suffix=.ply)
KNOB=${KNOB:-XRUN}
for value in ${VALUES:-1 512}; do
  for seed in ${SEEDS:-0 1 2 3 4 5}; do
    ts=$(env XSEED="$seed" "$KNOB=$value" "$CLI" "$M/dn_${MESH}_n0.25.ply" "$out" --operator curvature \
           --threads "$THREADS" --json -q | tail -1 |
         python3 -c 'import sys,json; d=json.load(sys.stdin); print(d["time_step"], d["strength_iterations"])')
    rms=$("$DT" eval "$M/dn_${MESH}_clean.ply" "$TRUTH" "$M/dn_${MESH}_n0.25.ply" "$out" |
          python3 -c 'import sys,json; print(json.load(sys.stdin)["rms"])')
    echo "$MESH $KNOB=$value seed $seed: time step, Lanczos $ts  rms $rms"
  done
done
rm -f "$out"
