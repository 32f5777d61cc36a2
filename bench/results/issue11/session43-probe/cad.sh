#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 43: coarse CAD parts of libcgal-demo (DIR holds dn_NAME_clean.ply from
# `fairing-bench-tool convert data/meshes/NAME.off`, and dn_NAME_n0.1.ply, dn_NAME_n0.25.ply from
# `fairing-denoise-tool noise CLEAN OUT SIGMA 21 normal`): each default's one click with the CLI
# of 63d35fa (OLD=) and of 5482131 (NEW=), against the best fixed step of the same setting (the
# sweep's log search, with the engine of 5482131). Usage: DIR=… OLD=… NEW=… cad.sh NAME...
DT=$HOME/.cache/filter_implicit_fairing/bench-build/bench/bin/fairing-denoise-tool
OLD=${OLD:?}; NEW=${NEW:?}; T=${TMPDIR:-/tmp}
cd "${DIR:?}"
for n in "$@"; do for s in n0.1 n0.25; do for os in umbrella:8 scale-dependent:2 curvature:4; do
  op=${os%:*}; st=${os#*:}
  $OLD dn_${n}_$s.ply $T/o_old.ply --operator $op --threads 1 -q --json > $T/j_old 2>/dev/null
  $NEW dn_${n}_$s.ply $T/o_new.ply --operator $op --threads 1 -q --json > $T/j_new 2>/dev/null
  best=$($DT sweep dn_${n}_$s.ply dn_${n}_clean.ply mesh $op 2 $st 1 2>/dev/null | /usr/bin/python3 -c 'import json,sys; print(min(json.loads(l)["rms"] for l in sys.stdin if l.startswith("{") and json.loads(l)["rms"] is not None))')
  ev=$($DT eval dn_${n}_clean.ply mesh dn_${n}_$s.ply $T/o_old.ply $T/o_new.ply | /usr/bin/python3 -c 'import json,sys; print(" ".join("%.4f"%json.loads(l)["rms"] for l in sys.stdin if l.startswith("{")))')
  sig=$(for j in $T/j_old $T/j_new; do tail -1 $j | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); print("%.3f"%d["noise_level_edges"], end=" ")'; done)
  echo "$n $s $op sigma(old new) $sig rms(old new) $ev best $best" | /usr/bin/python3 -c '
import sys; t=sys.stdin.read().split(); b=float(t[-1]); o=float(t[-4]); w=float(t[-3])
print(" ".join(t), " ratio %.3f -> %.3f" % (o/b, w/b))'
done; done; done
