#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The curvature default's automatic choice on session 33's probe inputs (seed 19), with the
# minimizer (0) and the one-standard-error rule (1), against session 33's oracles at 47e4aed.
#   BIN=BENCH/bin DATA=.../data/meshes P=probe-inputs session33_probe.sh
here=$(cd "$(dirname "$0")" && pwd)
grep ' curvature input' "$here/../session33-probe/oracle_probe_47e4aed.txt" |
while read -r m nz _ _ _ _ orms _ ots _ _ _ _ _ ratio; do
  src=$DATA/$m.off; [ -f "$src" ] || src=$DATA/$m.ply
  out=""
  for se in 0 1; do
    if [ $se = 1 ]; then e="FAIRING_SE_L2=1"; else e="UNUSED=1"; fi
    r=$(env $e timeout 600 "$BIN/fairing-denoise-tool" sweep "$P/${m}_${nz}_s19.ply" "$src" mesh \
        curvature 2 4 1 --auto --ts 1 2>/dev/null | grep '"auto"' | python3 -c "
import json, sys
a = json.loads(sys.stdin.read())
print('%.3f@%.3g' % (a['rms'] / $orms, a['time_step']))" 2>/dev/null)
    out="$out $se:${r:-FAIL}"
  done
  echo "$m $nz oracle $orms@$ots committed $ratio $out"
done
