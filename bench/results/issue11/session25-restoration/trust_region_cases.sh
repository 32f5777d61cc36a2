#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 25's trust-region rows: per case the curvature flow's L^2 automatic choice
# and error without and with FAIRING_TR=2 (trust-region.diff applied; BIN its bench tools).
#   trust_region_cases.sh BIN
set -euo pipefail
bin=$1
M=${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}/bench-meshes
row() {  # MESH NOISE STEPS SUFFIX TRUTH
  printf '%s %s %s' "$1" "$2" "$3"
  for tr in "" 2; do
    r=$(if [ -n "$tr" ]; then export FAIRING_TR=$tr; else unset FAIRING_TR; fi
        "$bin/fairing-denoise-tool" sweep "$M/dn_$1_$2$4.ply" "$M/dn_$1_clean.ply" "$5" curvature 2 "$3" 1 \
          --ts 1 --auto | grep '"auto"')
    python3 -c 'import json, sys; r = json.loads(sys.argv[1]); print(" | %.5g %.5f" % (r["time_step"], r["rms"]), end="")' "$r"
  done
  echo
}
for z in n0.1 n0.25 n0.5 iso0.25; do for st in 2 3 4; do row torus_10k $z $st "" torus:1:0.4; done; done
for m in elephant_6k fandisk_13k camel_20k elephant_loop1_22k; do
  for z in n0.1 n0.25 n0.5 iso0.25; do for st in 2 4; do row $m $z $st "" mesh; done; done
done
for m in turbine_18k man_35k diplodocus_48k; do
  for z in n0.1 n0.25 n0.5 iso0.25; do for st in 2 4; do row $m $z $st _s11 mesh; done; done
done
