#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The umbrella's L^2 with 4, 8 and 16 frozen steps: oracle (log search) and automatic choice on
# the study's inputs (seed 1).  BIN=.../bench/bin M=$FAIRING_CACHE/bench-meshes MESHES="elephant_6k" steps.sh
set -u
for m in $MESHES; do
  truth=mesh; case $m in sphere2*) truth=sphere;; torus_10k) truth=torus:1:0.4;; esac
  for nz in n0.1 n0.25 n0.5 iso0.25; do
    f=$M/dn_${m}_${nz}.ply; [ -f "$f" ] || continue
    for s in 4 8 16; do
      OMP_NUM_THREADS=1 "$BIN/fairing-denoise-tool" sweep "$f" "$M/dn_${m}_clean.ply" $truth umbrella 2 $s \
        "$(echo "4/$s" | bc -l)" --auto 2>/dev/null | TAG="$m $nz $s" python3 -c "
import json, os, sys
rows = [json.loads(l) for l in sys.stdin]
b = min((r for r in rows if r['kind'] == 'fixed'), key=lambda r: r['rms'])
a = [r for r in rows if r['kind'] == 'auto'][0]
print(os.environ['TAG'], 'oracle %.5f ts %.4g auto %.5f ts %.4g sec %.3f'
      % (b['rms'], b['time_step'], a['rms'], a['time_step'], a.get('seconds', 0)))"
    done
  done
done
