#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 40: every filter's one click at the paper's higher orders (--order 3, 4) on
# every noisy bench mesh; prints ok, frozen (a later recomputed step kept the last operator that
# solved), loops-held (the loops stayed in place; since session 41) or FAIL with the error.
# Measurement aid; I= the CLI to run; FROM= (optional) only the meshes named after it in
# alphabetical order (session 41: FROM=dn_man_35k_n0.5_s11, where this run had stopped).
C=~/.cache/filter_implicit_fairing; M=$C/bench-meshes; I=${I:-build/bin/implicit-fairing}
OUT=${TMPDIR:-/tmp}/orders.ply
for f in $(ls $M/dn_*.ply | grep -v "_clean\|_1m_\|1.2m"); do
 b=$(basename $f .ply)
 [[ "$b" > "${FROM:-}" ]] || continue
 for op in umbrella scale-dependent curvature; do
  for order in 3 4; do
   out=$(OMP_NUM_THREADS=1 timeout 600 $I --operator $op --order $order $f $OUT 2>&1); rc=$?
   if [ $rc -ne 0 ]; then echo "FAIL rc=$rc $b $op $order :: $(echo "$out" | grep -o "error: .\{160\}" | head -1)"
   elif echo "$out" | grep -q "kept the operator"; then echo "frozen $b $op $order :: $(echo "$out" | grep -o "steps\? [0-9-]* kept the operator of step [0-9]*")"
   elif echo "$out" | grep -q "Close Holes"; then echo "loops-held $b $op $order"
   else echo "ok $b $op $order"; fi
  done
 done
done
