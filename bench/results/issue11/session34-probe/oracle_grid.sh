#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The automatic choice against the best of a fixed log grid of time steps (factor 1.12 or
# GRID_FACTOR, from GRID_LO to GRID_HI): an oracle that no local search can miss.
#   BIN=BENCH/bin oracle_grid.sh NOISY CLEAN TRUTH OP ORDER STEPS LABEL
# TRUTH as fairing-denoise-tool's (sphere, torus:1:0.4, mesh). ENVS: environment for the tool.
set -eu
noisy=$1 clean=$2 truth=$3 op=$4 order=$5 steps=$6 label=$7
grid=$(python3 -c "
x, out = ${GRID_LO:-0.01}, []
while x < ${GRID_HI:-2e5}: out.append('%.4g' % x); x *= ${GRID_FACTOR:-1.12}
print(','.join(out))")
env ${ENVS:-X=1} "$BIN/fairing-denoise-tool" sweep "$noisy" "$clean" "$truth" "$op" "$order" \
    "$steps" 1 --auto --ts "$grid" 2>/dev/null |
    LABEL="$label $op $order $steps" python3 -c "
import json, os, sys
rows = [json.loads(l) for l in sys.stdin]
a = [r for r in rows if r.get('kind') == 'auto'][0]
b = min((r for r in rows if r.get('kind') == 'fixed' and r.get('rms') is not None),
        key=lambda r: r['rms'])
print(os.environ['LABEL'], 'auto %.5f ts %.4g  oracle %.5f ts %.4g  ratio %.3f tsr %.2f'
      % (a['rms'], a['time_step'], b['rms'], b['time_step'], a['rms'] / b['rms'],
         a['time_step'] / b['time_step']))"
