#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The automatic choice against the oracle with two builds of the bench tools: OLD (37780b2, one
# restoration factor for the whole sketch) and NEW (40d8e79, a factor per component's rows), on
# the multi-component meshes: bones and blobby_3cc (inputs of session32-probe/probe.sh, seed 19)
# and the held-out b9_10k (seed 17).
#   OLD=.../bin NEW=.../bin P=probe-dir DATA=.../data/meshes M=$FAIRING_CACHE/bench-meshes old_new.sh
set -u
run() {  # label noisy clean
  for spec in umbrella:2:4:10 scale-dependent:2:2:2.5 curvature:2:4:22.5; do
    IFS=: read -r op o s x0 <<< "$spec"
    for v in old new; do
      bin=$OLD; [ $v = new ] && bin=$NEW
      OMP_NUM_THREADS=1 "$bin/fairing-denoise-tool" sweep "$2" "$3" mesh $op $o $s $x0 --auto 2>/dev/null |
        TAG="$1 $op $v" python3 -c "
import json, os, sys
rows = [json.loads(l) for l in sys.stdin]
b = min((r for r in rows if r['kind'] == 'fixed'), key=lambda r: r['rms'])
a = [r for r in rows if r['kind'] == 'auto'][0]
print(os.environ['TAG'], 'oracle %.4f auto %.4f ts %.3g ratio %.3f' % (b['rms'], a['rms'], a['time_step'], a['rms'] / b['rms']))"
    done
  done
}
for nz in n0.1 n0.25 n0.5 iso0.25; do
  run bones_$nz "$P/bones_${nz}_s19.ply" "$DATA/bones.off"
  run blobby3cc_$nz "$P/blobby_3cc_${nz}_s19.ply" "$DATA/blobby_3cc.off"
  run b9_$nz "$M/dn_b9_10k_${nz}_s17.ply" "$M/dn_b9_10k_clean.ply"
done
