#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Denoising study (issue 11): for each mesh and noise case, the error of our filters at the best
# time step of a sweep ("oracle"), of the automatic strength (when the engine / CLI have it) and
# of each peer at its own best setting, in one run. See bench/README.md, "Denoising study".
#
#   bench/denoise.sh [--quick] [--only NAMES] [--results DIR] [--jobs N] [--seed N] [--build DIR]
#                    [--no-install] [--no-cost] [--ours-only --peers-from RUN.jsonl]
#                    [--auto-from RUN.jsonl] [--add SETTINGS --onto EXTRACT] [--noise CASES]
#
#   --quick        4 small meshes (sphere 3k, flat patch 3k, elephant 6k, fandisk 13k), no cost row
#   --only NAMES   only these meshes, comma-separated (names: bench/denoise.py, ALL)
#   --results DIR  write denoise.md, denoise_oracle.md, denoise.jsonl and the PNGs into DIR
#                  instead of bench/results (bench/results/denoise-quick with --quick)
#   --jobs N       parallel runs (default 2; the runs themselves are single-threaded)
#   --seed N       the noise's seed (default 1, the study's; other seeds are other draws of the
#                  same noise, their inputs and full rows kept apart in the cache)
#   --noise CASES  noise cases instead of the study's four (n0.1, n0.25, n0.5 along the normals,
#                  iso0.25 in all directions): TAG:SIGMA:KIND,... with SIGMA in mean edges and
#                  KIND normal or iso, e.g. n0.05:0.05:normal,n1.0:1.0:normal,iso0.5:0.5:iso
#   --build DIR    build directory (default $FAIRING_CACHE/bench-build, as bench/run.sh)
#   --no-install   do not apt-get install the peers (libcgal-dev libopenmesh-dev gnuplot-nox)
#   --no-cost      skip the >= 1 M-face cost rows (Loop x2 bunny, 1 M-face torus)
#   --auto-from F  only the automatic strength (and the invariants, the cost row) against the
#                  oracles in F, the full rows of an earlier run (engine gained auto since)
#   --add S        only these settings of our filters (OP:ORDER:STEPS,..., e.g. umbrella:2:8), each
#                  a sweep and the automatic choice, and the CLI's one-click rows (the defaults'),
#                  no cost rows; the report merges them onto
#   --onto F       the extract (RESULTS_DIR/denoise.jsonl) of an earlier run of the same meshes and
#                  seed: copy it out of RESULTS_DIR first, the report rewrites that file
#   --ours-only    run only our filters (engine changed, peers did not) and take the peers' rows
#   --peers-from F from F, the full rows of an earlier run on the same meshes
#                  ($FAIRING_CACHE/denoise-runs/denoise-full[-quick].jsonl; seeded inputs, so equal)
#
# Meshes are generated or fetched from Debian's libcgal-demo (apt-get download) into
# $FAIRING_CACHE/bench-meshes, never committed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export FAIRING_CACHE=${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}
bb=$FAIRING_CACHE/bench-build
install=1 args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --no-install) install=0 ;;
    --quick|--no-cost|--ours-only) args+=("$1") ;;
    --peers-from|--auto-from|--onto) [ $# -ge 2 ] || { echo "denoise.sh: $1 needs a value" >&2; exit 2; }
      args+=("$1" "$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"); shift ;;
    --only|--jobs|--seed|--noise|--add) [ $# -ge 2 ] || { echo "denoise.sh: $1 needs a value" >&2; exit 2; }
      args+=("$1" "$2"); shift ;;
    --results) [ $# -ge 2 ] || { echo "denoise.sh: $1 needs a value" >&2; exit 2; }
      mkdir -p "$2"; args+=(--results "$(cd "$2" && pwd)"); shift ;;
    --build) [ $# -ge 2 ] || { echo "denoise.sh: $1 needs a value" >&2; exit 2; }
      bb=$2; shift ;;
    -h|--help) sed -n 2,37p "$0"; exit 0 ;;
    *) echo "denoise.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

if [ "$install" = 1 ]; then
  "$root/scripts/ensure-packages.sh" libcgal-dev libopenmesh-dev gnuplot-nox python3
fi
src=$("$root/scripts/meshlab-2020-sdk.sh")
sdk2025=$("$root/scripts/meshlab-2025-sdk.sh")  # the CLI reads meshes with its vcglib
echo "denoise.sh: building the CLI of the current tree into $bb/main" >&2
cmake -S "$root" -B "$bb/main" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFAIRING_BUILD_TESTS=OFF \
  -DMESHLAB_2020_SOURCE="$src" -DMESHLAB_2025_SDK="$sdk2025" >/dev/null
# The CLI only serves the one-click rows (--time-step auto) and the cost row: a tree whose CLI does
# not build still gets its study, with those rows marked n/a.
cmake --build "$bb/main" -j2 --target implicit-fairing >/dev/null ||
  echo "denoise.sh: warning: the CLI did not build; its rows will be n/a" >&2
echo "denoise.sh: building the study's tools and peers into $bb/bench" >&2
cmake -S "$root/bench" -B "$bb/bench" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHLAB_2020_SOURCE="$src" \
  >/dev/null
cmake --build "$bb/bench" -j2 --target fairing-denoise-tool fairing-bench-tool meshlab_filter_timer \
  cgal_denoise openmesh_denoise >/dev/null

exec python3 "$root/bench/denoise.py" --root "$root" --build "$bb" --cache "$FAIRING_CACHE" "${args[@]}"
