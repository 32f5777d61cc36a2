#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 40: each filter's one click (no option) on every noisy bench mesh with two
# CLIs, OLD and NEW; prints same (byte-identical output files), DIFF, or RC with both errors.
# PATTERN (an extended regular expression, optional): only the meshes whose path matches it.
M=~/.cache/filter_implicit_fairing/bench-meshes; T=${TMPDIR:-/tmp}
for f in $(ls $M/dn_*.ply | grep -v "_clean\|_1m_\|1.2m" | grep -E "${PATTERN:-.}"); do
 for op in umbrella scale-dependent curvature; do
  b=$(basename $f .ply)
  OMP_NUM_THREADS=1 $OLD -q --operator $op $f $T/o_old.ply 2>$T/e_old; ro=$?
  OMP_NUM_THREADS=1 $NEW -q --operator $op $f $T/o_new.ply 2>$T/e_new; rn=$?
  if [ $ro -eq 0 ] && [ $rn -eq 0 ]; then
    if cmp -s $T/o_old.ply $T/o_new.ply; then echo "same $b $op"; else echo "DIFF $b $op"; fi
  else echo "RC $ro $rn $b $op :: $(head -c 300 $T/e_old) || $(head -c 300 $T/e_new)"; fi
  rm -f $T/o_old.ply $T/o_new.ply
 done
done
