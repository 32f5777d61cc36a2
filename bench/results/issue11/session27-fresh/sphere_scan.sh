#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 27's scan of fresh noise draws on the two-density spheres (auto-gap.md section 27), a
# measurement aid, not part of the product: each automatic choice with the stored converged points
# (as before) and judged afresh (FAIR_FRESH=1 of a build of risk-trace.diff); prints the runs that
# chose differently as "level seed kind operator order steps | time step, error, Lanczos steps
# before | after".
#   TOOL=BUILD/bin/fairing-denoise-tool sphere_scan.sh WORKDIR
set -eu
T=$TOOL
mkdir -p "$1"
cd "$1"
auto() {
    "$T" sweep "$@" 1 --auto --ts 1 2>/dev/null | grep '"auto"' |
        sed 's/.*time_step":\([^,]*\),"rms":\([^,]*\),.*strength_iterations":\([0-9]*\).*/\1 \2 \3/'
}
run() {  # level seeds configurations...
    local level=$1 seeds=$2
    shift 2
    [ -f s$level.ply ] || "$T" make sphere2 "$level" s$level.ply
    for seed in $seeds; do
        for kind in iso normal; do
            [ -f n$level-$seed-$kind.ply ] ||
                "$T" noise s$level.ply n$level-$seed-$kind.ply 0.25 "$seed" "$kind"
            for cfg in "$@"; do
                # shellcheck disable=SC2086
                a=$(auto n$level-$seed-$kind.ply s$level.ply sphere $cfg)
                # shellcheck disable=SC2086
                b=$(FAIR_FRESH=1 auto n$level-$seed-$kind.ply s$level.ply sphere $cfg)
                if [ "$a" != "$b" ]; then echo "$level $seed $kind $cfg | $a | $b"; fi
            done
        done
    done
}
for level in 3 4; do
    run $level "1 2 3 4 5 6" "curvature 1 2" "curvature 1 1" "scale-dependent 1 1" "curvature 2 4"
done
run 5 "2 3 4 5 6" "curvature 1 2" "curvature 1 1" "curvature 1 4" "scale-dependent 1 1"
