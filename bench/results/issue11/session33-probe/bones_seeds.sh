#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The umbrella's automatic choice on `bones` against the oracle on three more noise draws (seeds
# 20-22), with the OLD (37780b2) and NEW (40d8e79) bench tools, as old_new.sh.
#   OLD=.../bin NEW=.../bin DATA=.../data/meshes OUT=dir bones_seeds.sh
set -u
mkdir -p "$OUT"
for seed in 20 21 22; do
  for nz in n0.25:0.25:normal n0.5:0.5:normal iso0.25:0.25:iso; do
    IFS=: read -r tag s kind <<< "$nz"
    f=$OUT/bones_${tag}_s$seed.ply
    [ -f "$f" ] || "$NEW/fairing-denoise-tool" noise "$DATA/bones.off" "$f" "$s" "$seed" "$kind" > /dev/null
    for v in old new; do
      bin=$OLD; [ $v = new ] && bin=$NEW
      OMP_NUM_THREADS=1 "$bin/fairing-denoise-tool" sweep "$f" "$DATA/bones.off" mesh umbrella 2 4 10 --auto \
        2>/dev/null | TAG="s$seed $tag umbrella $v" python3 -c "
import json, os, sys
rows = [json.loads(l) for l in sys.stdin]
b = min((r for r in rows if r['kind'] == 'fixed'), key=lambda r: r['rms'])
a = [r for r in rows if r['kind'] == 'auto'][0]
print(os.environ['TAG'], 'oracle %.4f auto %.4f ts %.3g ratio %.3f iters %s'
      % (b['rms'], a['rms'], a['time_step'], a['rms'] / b['rms'], a.get('strength_iterations')))"
    done
  done
done
