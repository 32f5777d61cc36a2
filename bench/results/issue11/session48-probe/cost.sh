#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 48: what the curvature flow's one-click estimate costs on the study's cost
# meshes (bench/denoise.py's COST_MESHES at a quarter edge: the 1.2 M-face Loop bunny and the
# 1 M-face torus), on THREADS threads (1 by default). ROUNDS rounds of the one click, --recompute
# (the recomputed estimate alone), --freeze (the frozen one alone) and the chosen time step given,
# in turn, so that the machine's load falls on all alike; the least of each is printed with its
# Lanczos steps.
# Usage: CLI=build/bin/implicit-fairing sh cost.sh [mesh ...]
CLI=${CLI:-build/bin/implicit-fairing}
M=${M:-$HOME/.cache/filter_implicit_fairing/bench-meshes}
ROUNDS=${ROUNDS:-3}
OP=${OP:-curvature}
THREADS=${THREADS:-1}
export OMP_NUM_THREADS=$THREADS
out=$(mktemp --suffix=.ply)
for mesh in ${*:-bunny_loop2_1.2m torus_1m}; do
  in=$M/dn_${mesh}_n0.25.ply
  run() { "$CLI" "$in" "$out" --operator "$OP" --threads "$THREADS" --json -q "$@" | tail -1; }
  for round in $(seq "$ROUNDS"); do
    for mode in one-click --recompute --freeze explicit; do
      case $mode in
        one-click)  # its chosen time step is the one given in this round's explicit run
          j=$(run)
          ts=$(echo "$j" | python3 -c 'import sys,json; print(repr(json.load(sys.stdin)["time_step"]))') ;;
        explicit) j=$(run --time-step "$ts") ;;
        *) j=$(run "$mode") ;;
      esac
      echo "$mode $(echo "$j" | python3 -c 'import sys,json; d=json.load(sys.stdin); print(d["strength_seconds"], d["seconds_engine"], d["steps"], d["time_step"], d.get("strength_iterations", 0))')"
    done
  done | python3 -c '
import sys, collections
best = collections.OrderedDict()
for line in sys.stdin:
    mode, est, total, steps, ts, its = line.split()
    b = best.setdefault(mode, [1e99, 1e99, int(steps), float(ts), its])
    b[0], b[1] = min(b[0], float(est)), min(b[1], float(total))
step = best["explicit"][1] / best["explicit"][2]
print(sys.argv[1])
for mode, (est, total, steps, ts, its) in best.items():
    print("  %-11s time step %9.2f  Lanczos %4s  estimate %5.2f s  whole run %5.2f s  estimate / one step %.2f"
          % (mode, ts, its, est, total, est / step))
 ' "$mesh $OP, $THREADS thread(s)"
done
rm -f "$out"
