#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Every committed set's automatic and one-click rows again against the oracles of its committed
# extract (bench/README.md, "An engine change that moves only the automatic choice"). Run from the
# repository root: sh bench/results/issue11/session49-probe/rerun_sets.sh [SET ...]
# SET: study (with the cost rows), seed2, seed8, noise, s11, s13, s17 (default: all of them).
set -eu
sets=${*:-study seed2 seed8 noise s11 s13 s17}
for set in $sets; do
  case $set in
    study) dir=bench/results; args="" ;;
    seed2) dir=bench/results/denoise-seed2; args="--no-cost --seed 2 --only elephant_6k,fandisk_13k,camel_20k,dragon_20k,elephant_loop1_22k,torus_10k,sphere2_3k,sphere2_13k,sphere2_51k,plane_3k" ;;
    seed8) dir=bench/results/denoise-seed8; args="--no-cost --seed 8 --only armadillo_52k,bunny_75k,dragon_20k,sphere2_3k,sphere2_13k,torus_10k,plane_3k" ;;
    noise) dir=bench/results/denoise-noise; args="--no-cost --seed 7 --noise n0.05:0.05:normal,n1.0:1.0:normal,iso0.5:0.5:iso --only armadillo_52k,bunny_75k,dragon_20k,fandisk_13k,sphere2_3k,sphere2_13k,torus_10k,plane_3k" ;;
    s11) dir=bench/results/heldout-s11; args="--no-cost --seed 11 --only diplodocus_48k,turbine_18k,lionhead_17k,man_35k" ;;
    s13) dir=bench/results/heldout-s13; args="--no-cost --seed 13 --only bear_28k,mannequin_26k,shark_10k,bull_12k,blade_16k" ;;
    s17) dir=bench/results/heldout-s17; args="--no-cost --seed 17 --only femur_8k,b9_10k,cheese_18k,knot2_12k,homer_10k" ;;
    *) echo "rerun_sets.sh: unknown set $set" >&2; exit 2 ;;
  esac
  cp "$dir/denoise.jsonl" "/tmp/extract-$set.jsonl"
  # shellcheck disable=SC2086
  bench/denoise.sh --auto-from "/tmp/extract-$set.jsonl" $args --results "$dir"
done
