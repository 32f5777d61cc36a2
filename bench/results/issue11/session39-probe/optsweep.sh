#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: every filter with one non-default option each on eight held-out noisy
# meshes (one click otherwise); prints ok or FAIL with the error. Measurement aid.
C=~/.cache/filter_implicit_fairing; M=$C/bench-meshes; I=${I:-build/bin/implicit-fairing}
for f in dn_b9_10k_n0.25_s17 dn_cheese_18k_n0.25_s17 dn_knot2_12k_n0.25_s17 dn_blade_16k_n0.25_s13 dn_shark_10k_n0.25_s13 dn_femur_8k_n0.5_s17 dn_lionhead_17k_iso0.25_s11 dn_turbine_18k_n0.5_s11; do
 for op in umbrella scale-dependent curvature; do
  for extra in "--no-volume" "--order 1" "--order 3" "--order 4" "--explicit" "--freeze" "--boundary virtual" "--boundary fixed" "--volume-restoration scale" "--area" "--steps 1" "--steps 16" "--normalized" "--keep-drift" "--uniform-offset" "--no-volume --order 1" "--no-volume --steps 16"; do
   out=$(OMP_NUM_THREADS=1 timeout 300 $I --operator $op $extra $M/$f.ply ${TMPDIR:-/tmp}/optsweep.ply 2>&1); rc=$?
   if [ $rc -ne 0 ]; then echo "FAIL rc=$rc $f $op $extra :: $(echo "$out" | grep -i "error" | head -2 | tr '\n' ' ')"; else echo "ok $f $op $extra"; fi
  done
 done
done
