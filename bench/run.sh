#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# End-to-end benchmark of the implicit fairing engine, its CLI and its MeshLab 2020.09 plugin
# against CGAL smooth_shape, OpenMesh's JacobiLaplaceSmootherT and MeshLab's own Laplacian,
# ScaleDependent Laplacian and Taubin smoothing, at equal diffusion time (bench/README.md).
#
#   bench/run.sh [--quick] [--no-micro] [--no-install] [--only NAMES] [--results DIR] [--repeat N]
#                [--issue12-only]
#
#   --quick        skip the >= 1M-face meshes (jittered torus 1M, bunny Loop x2 1.2M)
#   --no-micro     skip the Google Benchmark micro-benchmarks (bench/results/micro.md; target b)
#   --no-install   do not apt-get install the peers (libcgal-dev libopenmesh-dev gnuplot-nox)
#   --only NAMES   only these meshes, comma-separated: torus_10k, torus_100k, bunny_75k,
#                  bunny_loop1_302k, torus_1m, bunny_loop2_1.2m (e.g. --only torus_10k: ~1 min)
#   --results DIR  write results.md, runs.jsonl, micro.md, the plot into DIR instead of
#                  bench/results (for trial runs that must not touch the committed tables)
#   --repeat N     meshlab_filter_timer repetitions per MeshLab filter run (median; default 3).
#                  The CLI rows that targets a, c and d compare are the fastest of 3 runs.
#
# Needs scripts/setup.sh once (Debian packages, MeshLab 2020.09 SDK in the cache). Builds the
# engine, CLI and plugin of the current tree, the peers and bench tools into
# $FAIRING_CACHE/bench-build (never into build/), meshes into $FAIRING_CACHE/bench-meshes, runs
# into $FAIRING_CACHE/bench-runs, and writes bench/results/*.md (+ runs.jsonl, PNG plot).
# MeshLab's filters and our plugin are timed in-process by bench/tools/meshlab_filter_timer.cpp.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export FAIRING_CACHE=${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}
bb=$FAIRING_CACHE/bench-build
install=1 micro=1 args=() results=$root/bench/results
while [ $# -gt 0 ]; do
  case "$1" in
    --no-install) install=0 ;;
    --no-micro) micro=0 ;;
    --quick) args+=(--quick) ;;
    --issue12-only) args+=(--issue12-only) ;;
    --only|--repeat) [ $# -ge 2 ] || { echo "run.sh: $1 needs a value" >&2; exit 2; }
      args+=("$1" "$2"); shift ;;
    --results) [ $# -ge 2 ] || { echo "run.sh: $1 needs a value" >&2; exit 2; }
      mkdir -p "$2"; results=$(cd "$2" && pwd); shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 && !/SPDX/' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
args+=(--results "$results")

if [ "$install" = 1 ]; then
  "$root/scripts/ensure-packages.sh" libcgal-dev libopenmesh-dev libbenchmark-dev gnuplot-nox \
    time python3
fi

src=$("$root/scripts/meshlab-2020-sdk.sh")
sdk2025=$("$root/scripts/meshlab-2025-sdk.sh")  # the CLI reads meshes with its vcglib
echo "run.sh: building engine, CLI and plugin into $bb/main" >&2
cmake -S "$root" -B "$bb/main" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFAIRING_BUILD_TESTS=OFF \
  -DMESHLAB_2020_SOURCE="$src" -DMESHLAB_2025_SDK="$sdk2025" >/dev/null
cmake --build "$bb/main" -j2 >/dev/null
echo "run.sh: building bench tools and peers into $bb/bench" >&2
cmake -S "$root/bench" -B "$bb/bench" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHLAB_2020_SOURCE="$src" \
  >/dev/null
cmake --build "$bb/bench" -j2 >/dev/null

if [ "$micro" = 1 ]; then
  echo "run.sh: micro-benchmarks (a few minutes)" >&2
  "$bb/bench/bin/fairing-micro-bench" --benchmark_min_time=0.3 \
    --benchmark_out="$FAIRING_CACHE/bench-micro.json" --benchmark_out_format=json >&2
  python3 "$root/bench/report_micro.py" "$FAIRING_CACHE/bench-micro.json" > "$results/micro.md"
  args+=(--micro-json "$FAIRING_CACHE/bench-micro.json")
fi

exec python3 "$root/bench/run_bench.py" --root "$root" --build "$bb" --cache "$FAIRING_CACHE" "${args[@]}"
