#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 33's probe inputs (seed 19): the curvature default's automatic choice with the switch on
# the steps' total (UNUSED=1: 5af7ce3) and per step (FAIRING_L2_PERSTEP=1), over session 33's
# oracles at 47e4aed. s33_perstep.sh LANE (0 or 1: every other case); BIN, DATA (libcgal-demo's
# data/meshes) and P (the probe inputs, ../session32-probe/probe.sh SEED=19) as below.
here=$(cd "$(dirname "$0")" && pwd)
BIN=${BIN:-/tmp/s37/bb/bin}; DATA=${DATA:-/tmp/cgd/data/meshes}; P=${P:-/tmp/s33/probe}
grep ' curvature input' "$here/../session33-probe/oracle_probe_47e4aed.txt" | awk -v lane=$1 'NR%2==lane' |
while read -r m nz _ _ _ _ orms _ ots _ _ _ _ _ ratio; do
  src=$DATA/$m.off; [ -f "$src" ] || src=$DATA/$m.ply
  out=""
  for e in UNUSED=1 FAIRING_L2_PERSTEP=1; do
    r=$(env $e timeout 600 "$BIN/fairing-denoise-tool" sweep "$P/${m}_${nz}_s19.ply" "$src" mesh \
        curvature 2 4 1 --auto --ts 1 2>/dev/null | grep '"auto"' | python3 -c "
import json, sys
a = json.loads(sys.stdin.read())
print('%.3f@%.3g' % (a['rms'] / $orms, a['time_step']))" 2>/dev/null)
    out="$out ${e%%=*}:${r:-FAIL}"
  done
  echo "$m $nz oracle $orms@$ots committed $ratio $out"
done
