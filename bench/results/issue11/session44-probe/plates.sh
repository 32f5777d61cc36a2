#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 44: the umbrella's and the scale-dependent filter's one click with two CLIs
# (OLD=, NEW=) on thin plates (plate.py: 16 and 24 cells a side, 0.1-1.5 cells thick, noise of 0.1,
# 0.25 and 0.5 edge along the normals, seed 1): the chosen time step, the restoration, and the
# error against the clean plate (fairing-denoise-tool eval, DT=). One line per case.
# Usage: OLD=… NEW=… DT=… sh plates.sh > plates.txt
set -e
here=$(dirname "$0")
tmp=$(mktemp -d)
for N in 16 24; do for T in 0.1 0.2 0.4 0.8 1.5; do
  python3 "$here/plate.py" $N $T $tmp/clean.ply
  for n in 0.1 0.25 0.5; do
    "$DT" noise $tmp/clean.ply $tmp/noisy.ply $n 1 normal
    for op in umbrella scale-dependent; do
      line="$N $T $n $op"
      for cli in "$OLD" "$NEW"; do
        j=$("$cli" $tmp/noisy.ply $tmp/out.ply --operator $op --threads 1 --json -q | tail -1)
        e=$("$DT" eval $tmp/clean.ply mesh $tmp/noisy.ply $tmp/out.ply | tail -1)
        line="$line | $(printf '%s\n%s\n' "$j" "$e" | python3 -c "
import json, sys
j, e = (json.loads(l) for l in sys.stdin)
print('%.4g %s %.4f' % (j['time_step'], j['volume_restoration'][0].split()[0], e['rms']))")"
      done
      echo "$line"
    done
  done
done; done
rm -r $tmp
