#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The curvature default's automatic choice on session 33's probe inputs (seed 19), with the
# minimizer (0) and the one-standard-error rule (1), against session 33's oracles at 47e4aed.
#   BIN=BENCH/bin DATA=.../data/meshes P=probe-inputs session33_probe.sh
here=$(cd "$(dirname "$0")" && pwd)
# ENVS: the settings, labelled 0, 1, ... (session 37: "UNUSED=1 FAIRING_L2_PERSTEP=1"); LANE 0 or 1:
# every other case only.
envs=${ENVS:-"UNUSED=1 FAIRING_SE_L2=1"}
grep ' curvature input' "$here/../session33-probe/oracle_probe_47e4aed.txt" |
awk -v lane="${LANE:--1}" 'lane < 0 || NR % 2 == lane' |
while read -r m nz _ _ _ _ orms _ ots _ _ _ _ _ ratio; do
  src=$DATA/$m.off; [ -f "$src" ] || src=$DATA/$m.ply
  out=""
  se=0
  for e in $envs; do
    r=$(env $e timeout 600 "$BIN/fairing-denoise-tool" sweep "$P/${m}_${nz}_s19.ply" "$src" mesh \
        curvature 2 4 1 --auto --ts 1 2>/dev/null | grep '"auto"' | python3 -c "
import json, sys
a = json.loads(sys.stdin.read())
print('%.3f@%.3g' % (a['rms'] / $orms, a['time_step']))" 2>/dev/null)
    out="$out $se:${r:-FAIL}"
    se=$((se + 1))
  done
  echo "$m $nz oracle $orms@$ots committed $ratio $out"
done
