#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 42: meshes no study set holds for cap.py (CASES=): the two-density sphere at
# 205 k faces and a third draw of the 51 k one, the torus at 40 k and 160 k faces, a 51 k-face flat
# patch, and four larger scans (seed 3; the camel Loop-subdivided once), noise 0.1, 0.25 and 0.5
# edge along the normals. Writes the meshes and OUT/cases.txt.  Usage: heldout.sh OUT
set -euo pipefail
out=${1:?usage: heldout.sh OUT}
mkdir -p "$out"
cache=${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}
B=$cache/bench-build/bench/bin
M=$cache/bench-meshes
DT=$B/fairing-denoise-tool
cd "$out"
$DT make sphere2 6 sphere2_205k.ply
$DT make sphere2 5 sphere2_51k.ply
$DT make torus 40000 torus_40k.ply
$DT make torus 160000 torus_160k.ply
$DT make plane 160 plane_51k.ply
$B/fairing-bench-tool loop "$M/dn_camel_20k_clean.ply" camel_loop1_80k.ply 1
rm -f cases.txt
add() {  # SET NAME NOISE CLEAN TRUTH SEED
    local noisy=$PWD/dn_$2_n$3_s$6.ply
    $DT noise "$4" "$noisy" "$3" "$6" normal >/dev/null
    echo "$1 $2 n$3 $noisy $4 $5" >> cases.txt
}
for m in sphere2_205k:sphere torus_40k:torus:1:0.4 torus_160k:torus:1:0.4 plane_51k:plane; do
    for seed in 3 5; do for n in 0.1 0.25 0.5; do
        add ho-s$seed "${m%%:*}" $n "$PWD/${m%%:*}.ply" "${m#*:}" $seed
    done; done
done
for n in 0.1 0.25 0.5; do add ho-s3 sphere2_51k $n "$PWD/sphere2_51k.ply" sphere 3; done
for name in bunny_75k armadillo_52k diplodocus_48k camel_loop1_80k; do
    clean=$M/dn_${name}_clean.ply
    [ -f "$clean" ] || clean=$PWD/$name.ply
    for n in 0.1 0.25 0.5; do add ho-s3 $name $n "$clean" mesh 3; done
done
wc -l cases.txt
