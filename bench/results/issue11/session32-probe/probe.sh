#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# One-click CLI runs (each filter's defaults, automatic strength) on meshes no session tuned on,
# four noises each, one line per run: mesh, noise, filter, input error, result error, largest
# distance, seconds (or FAILED and the CLI's message). Measurement aid, not built.
#   CLI=.../implicit-fairing BIN=.../bench/bin DATA=.../data/meshes OUT=dir MESHES="femur b9_mesh" \
#     [SEED=17] probe.sh
# DATA: libcgal-demo's data/meshes (apt-get download libcgal-demo; dpkg -x; tar xzf
# usr/share/doc/libcgal-dev/data.tar.gz data/meshes); a mesh NAME is DATA/NAME.off or .ply.
set -u
seed=${SEED:-17}
mkdir -p "$OUT"
for m in $MESHES; do
  src=$DATA/$m.off; [ -f "$src" ] || src=$DATA/$m.ply
  for nz in n0.1:0.1:normal n0.25:0.25:normal n0.5:0.5:normal iso0.25:0.25:iso; do
    IFS=: read -r tag s kind <<< "$nz"
    noisy=$OUT/${m}_${tag}_s$seed.ply
    [ -f "$noisy" ] || "$BIN/fairing-denoise-tool" noise "$src" "$noisy" "$s" "$seed" "$kind" >/dev/null
    for op in umbrella scale-dependent curvature; do
      out=$OUT/out_${m}_${tag}_$op.ply; rm -f "$out"
      t0=$(date +%s.%N)
      timeout 600 "$CLI" --operator $op --json -q --threads 1 "$noisy" "$out" \
        > /dev/null 2> "$OUT/err_${m}_${tag}_$op.txt"
      t1=$(date +%s.%N)
      if [ -f "$out" ]; then
        e=$("$BIN/fairing-denoise-tool" eval "$src" mesh "$noisy" "$noisy" "$out" | python3 -c "
import sys, json
a = [json.loads(l) for l in sys.stdin]
print('%.4f %.4f max %.3f' % (a[0]['rms'], a[1]['rms'], a[1]['max']))")
      else
        e="FAILED: $(head -c 300 "$OUT/err_${m}_${tag}_$op.txt")"
      fi
      echo "$m $tag $op $e $(echo "$t1 - $t0" | bc)s"
    done
  done
done
