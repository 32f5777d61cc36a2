#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 45: what the one-click defaults' choice costs on >= 1 M faces now that the
# curvature flow and the scale-dependent filter estimate frozen and recomputed steps: per filter,
# the one click (its strength_seconds), the same with --recompute (one estimate), and the chosen
# time step given explicitly (with --freeze where the one click froze), one thread each, on the
# study's cost meshes (bench/denoise.py's COST_MESHES, noisy at a quarter edge).
# Usage: CLI=build/bin/implicit-fairing sh cost_defaults.sh
CLI=${CLI:-build/bin/implicit-fairing}
M=${M:-$HOME/.cache/filter_implicit_fairing/bench-meshes}
export OMP_NUM_THREADS=1
for mesh in bunny_loop2_1.2m torus_1m; do
  for op in curvature scale-dependent; do
    in=$M/dn_${mesh}_n0.25.ply
    a=$("$CLI" "$in" /tmp/cost45.ply --operator $op --threads 1 --json -q | tail -1)
    r=$("$CLI" "$in" /tmp/cost45.ply --operator $op --threads 1 --json -q --recompute | tail -1)
    ts=$(echo "$a" | python3 -c 'import sys,json; print(repr(json.load(sys.stdin)["time_step"]))')
    fz=$(echo "$a" | python3 -c 'import sys,json; print("--freeze" if json.load(sys.stdin)["operator_frozen"] else "")')
    e=$("$CLI" "$in" /tmp/cost45.ply --operator $op --threads 1 --json -q --time-step "$ts" $fz | tail -1)
    python3 - "$mesh" "$op" "$a" "$r" "$e" <<'PY'
import json, sys
mesh, op = sys.argv[1:3]
a, r, e = (json.loads(x) for x in sys.argv[3:6])
print("%s %s: frozen %s (risks %s / %s); one click %.1f s, its estimate %.1f s; --recompute's "
      "estimate %.1f s; the chosen step given %.1f s for %d steps: estimate / filter %.2f, / one "
      "step %.2f" % (mesh, op, a["operator_frozen"], a["recomputed_risk"], a["frozen_risk"],
                     a["seconds_engine"], a["strength_seconds"], r["strength_seconds"],
                     e["seconds_engine"], e["steps"], a["strength_seconds"] / e["seconds_engine"],
                     a["strength_seconds"] * e["steps"] / e["seconds_engine"]))
PY
  done
done
rm -f /tmp/cost45.ply
