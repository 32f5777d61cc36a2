#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# the umbrella's one-click run on >= 1 M faces: 8 steps (the new default) against 4, CLI, one thread
set -e
C=~/.cache/filter_implicit_fairing
DT=$C/bench-build/bench/bin/fairing-denoise-tool; BT=$C/bench-build/bench/bin/fairing-bench-tool
CLI=$C/bench-build/main/bin/implicit-fairing; M=$C/bench-meshes
[ -f $M/dn_torus_1m_clean.ply ] || $DT make torus 1000000 $M/dn_torus_1m_clean.ply
[ -f $M/dn_torus_1m_n0.25.ply ] || $DT noise $M/dn_torus_1m_clean.ply $M/dn_torus_1m_n0.25.ply 0.25 1 normal
[ -f $M/dn_bunny_loop2_1.2m_clean.ply ] || $BT loop $M/bunny00.off $M/dn_bunny_loop2_1.2m_clean.ply 2
[ -f $M/dn_bunny_loop2_1.2m_n0.25.ply ] || $DT noise $M/dn_bunny_loop2_1.2m_clean.ply $M/dn_bunny_loop2_1.2m_n0.25.ply 0.25 1 normal
for rep in 1 2; do
for name in torus_1m bunny_loop2_1.2m; do
  for steps in 4 8; do
    /usr/bin/time -f "%e s wall %M KB" $CLI $M/dn_${name}_n0.25.ply /tmp/s38/out_${name}_$steps.ply --operator umbrella \
      --steps $steps --threads 1 --json -q > /tmp/s38/cost_${name}_$steps.json 2> /tmp/s38/cost_${name}_$steps.time
    python3 - "$name" "$steps" <<'PY'
import json, sys
j = [json.loads(l) for l in open("/tmp/s38/cost_%s_%s.json" % tuple(sys.argv[1:3])) if l.strip().startswith("{")][-1]
keys = ("time_step", "noise_level_edges", "seconds_engine", "strength_seconds", "cg_iterations")
print(sys.argv[1], "steps", sys.argv[2], {k: j.get(k) for k in keys}, open("/tmp/s38/cost_%s_%s.time" % tuple(sys.argv[1:3])).read().strip())
PY
  done
  echo "error: $($DT eval $M/dn_${name}_clean.ply $( [ $name = torus_1m ] && echo torus:1:0.4 || echo mesh ) $M/dn_${name}_n0.25.ply /tmp/s38/out_${name}_4.ply /tmp/s38/out_${name}_8.ply | tr '\n' ' ')"
done
done
