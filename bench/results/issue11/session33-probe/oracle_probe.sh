#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The automatic choice against the oracle (fairing-denoise-tool sweep's log search) at each
# filter's default order and steps, on noisy inputs made by session32-probe/probe.sh.
#   BIN=.../bench/bin DATA=.../data/meshes OUT=dir [SEED=19] MESHES="bones handle" \
#     [SPECS="umbrella:2:8:10 ..."] oracle_probe.sh
# SPECS: OP:ORDER:STEPS:X0 each (default: the defaults of session 33, umbrella 4 steps).
set -u
seed=${SEED:-19}
for m in $MESHES; do
  src=$DATA/$m.off; [ -f "$src" ] || src=$DATA/$m.ply
  for nz in n0.1 n0.25 n0.5 iso0.25; do
    noisy=$OUT/${m}_${nz}_s$seed.ply; [ -f "$noisy" ] || continue
    for spec in ${SPECS:-umbrella:2:4:10 scale-dependent:2:2:2.5 curvature:2:4:22.5}; do
      IFS=: read -r op o s x0 <<< "$spec"
      OMP_NUM_THREADS=1 timeout 900 "$BIN/fairing-denoise-tool" sweep "$noisy" "$src" mesh $op $o $s $x0 --auto \
        2>/dev/null | M=$m NZ=$nz OP=$op S=$s python3 -c "
import json, os, sys
rows = [json.loads(l) for l in sys.stdin]
fixed = [r for r in rows if r['kind'] == 'fixed' and r.get('rms') is not None]
auto = [r for r in rows if r['kind'] == 'auto' and r.get('rms') is not None]
inp = [r for r in rows if r['kind'] == 'input']
tag = '%s %s %s' % (os.environ['M'], os.environ['NZ'], os.environ['OP'])
tag += ' x%s' % os.environ['S'] if os.environ.get('SPECS') else ''
if not fixed or not auto:
    print(tag, 'FAILED'); sys.exit()
b, a = min(fixed, key=lambda r: r['rms']), auto[0]
print(tag, 'input %.4f oracle %.4f ts %.3g auto %.4f ts %.3g ratio %.3f'
      % (inp[0]['rms'] if inp else -1, b['rms'], b['time_step'], a['rms'], a['time_step'], a['rms'] / b['rms']))"
    done
  done
done
