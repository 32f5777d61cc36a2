#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 46: where the curvature flow's one-click estimate spends its time on the
# 1 M-face torus at a quarter edge (bench/denoise.py's COST_MESHES), one thread. Three rounds of
# the one click, --recompute (the recomputed estimate alone), --freeze (the frozen one alone) and
# the chosen time step given, in turn, so that the machine's load falls on all alike; the least
# of each is printed. Then perf's flat profile of one one-click run.
# Usage: CLI=build/bin/implicit-fairing DT=<bench build>/bin/fairing-denoise-tool sh cost_profile.sh
CLI=${CLI:-build/bin/implicit-fairing}
DT=${DT:-fairing-denoise-tool}
W=${W:-$(mktemp -d)}
export OMP_NUM_THREADS=1
[ -f "$W/torus_1m.ply" ] || "$DT" make torus 1000000 "$W/torus_1m.ply"
[ -f "$W/torus_n0.25.ply" ] || "$DT" noise "$W/torus_1m.ply" "$W/torus_n0.25.ply" 0.25 1 normal
run() {
  "$CLI" "$W/torus_n0.25.ply" "$W/out.ply" --operator curvature --threads 1 --json -q "$@" | tail -1
}
ts=$(run | python3 -c 'import sys,json; print(repr(json.load(sys.stdin)["time_step"]))')
for round in 1 2 3; do
  for mode in one-click --recompute --freeze explicit; do
    case $mode in
      one-click) j=$(run) ;;
      explicit) j=$(run --time-step "$ts") ;;
      *) j=$(run "$mode") ;;
    esac
    echo "$mode $(echo "$j" | python3 -c 'import sys,json; d=json.load(sys.stdin); print(d["strength_seconds"], d["seconds_engine"], d["steps"], d["time_step"])')"
  done
done | python3 -c '
import sys, collections
best = collections.OrderedDict()
for line in sys.stdin:
    mode, est, total, steps, ts = line.split()
    b = best.setdefault(mode, [1e99, 1e99, int(steps), float(ts)])
    b[0], b[1] = min(b[0], float(est)), min(b[1], float(total))
step = best["explicit"][1] / best["explicit"][2]
for mode, (est, total, steps, ts) in best.items():
    print("%-11s time step %9.1f  estimate %5.2f s  whole run %5.2f s  estimate / one explicit step %.2f"
          % (mode, ts, est, total, est / step))
'
perf record -q -o "$W/perf.data" "$CLI" "$W/torus_n0.25.ply" "$W/out.ply" --operator curvature \
  --threads 1 --json -q >/dev/null 2>&1
perf report -i "$W/perf.data" --no-children --sort symbol 2>/dev/null | grep '%' | grep -v '^#' |
  sed 's/  */ /g; s/(anonymous namespace):://g; s/fairing::detail:://g' | cut -c1-110 | head -16
