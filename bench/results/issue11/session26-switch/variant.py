#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's switch-factor table (auto-gap.md section 26), a measurement aid, not part of the
# product: the automatic choice's error over the best fixed step's (the committed study's
# oracle) for each case of cases.txt, with a fairing-denoise-tool built from
# switch-factor.diff and the given environment (FAIR_SWITCH_TOTAL=1, FAIR_SWITCH_FACTOR=F,
# FAIR_SWITCH_L2=1).
#   TOOL=BUILD/bin/fairing-denoise-tool variant.py [NAME=VALUE ...]
# Meshes: the study's cache ($FAIRING_CACHE/bench-meshes, made by bench/denoise.sh).
import json
import math
import os
import subprocess
import sys

from study_rows import HERE, MESHES, best_rows

env = dict(os.environ)
for a in sys.argv[1:]:
    k, v = a.split('=')
    env[k] = v
oracle = best_rows()
meshes = MESHES
tool = os.environ['TOOL']
rows, logs = [], []
with open(os.path.join(HERE, 'cases.txt')) as f:
    for line in f:
        m, noise, op, order, steps = line.split()
        truth = 'sphere' if m.startswith('sphere') else 'torus:1:0.4' if m.startswith('torus') else 'mesh'
        out = subprocess.run([tool, 'sweep', f'{meshes}/dn_{m}_{noise}.ply', f'{meshes}/dn_{m}_clean.ply',
                              truth, op, order, steps, '1', '--auto', '--ts', '1'],
                             env=env, capture_output=True, text=True, check=True).stdout
        r = [json.loads(x) for x in out.splitlines() if '"auto"' in x][0]
        q = r['rms'] / oracle[(m, noise, op, int(order), int(steps))][0]
        logs.append(math.log(q))
        rows.append('%s %s %s L%s x%s %.3f' % (m, noise, op, order, steps, q))
print(' '.join(sys.argv[1:]) or 'as committed', 'geometric mean %.4f, worst %.3f, past 10 %%: %d of %d'
      % (math.exp(sum(logs) / len(logs)), math.exp(max(logs)), sum(q > math.log(1.1) for q in logs), len(logs)))
for r in rows:
    print('  ' + r)
