#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's extended final grid (auto-gap.md section 26), a measurement aid, not part of the
# product: the automatic choice of grid_top.py's 80 runs and the 51 k sphere's two first-order
# curvature steps in all directions, with and without FAIR_EXTEND of a fairing-denoise-tool built
# from grid-extend.diff (the final grid re-evaluated up to converged_to when its minimum is on its
# top edge); prints the runs that changed, against the committed study's oracle.
#   TOOL=BUILD3/bin/fairing-denoise-tool extend.py
import json
import math
import os
import subprocess

from study_rows import MESHES, best_rows

oracle = best_rows()
meshes = MESHES


def automatic(args, env):
    out = subprocess.run([os.environ['TOOL'], 'sweep'] + args + ['1', '--auto', '--ts', '1'],
                         env=dict(os.environ, **env), capture_output=True, text=True, check=True).stdout
    r = [json.loads(x) for x in out.splitlines() if '"auto"' in x][0]
    return r['time_step'], r['rms']


cases = [(m, t, noise, op, order, steps)
         for m, t in (('sphere2_3k', 'sphere'), ('sphere2_13k', 'sphere'), ('torus_10k', 'torus:1:0.4'),
                      ('elephant_6k', 'mesh'), ('fandisk_13k', 'mesh'))
         for noise in ('n0.1', 'n0.25', 'n0.5', 'iso0.25')
         for op, order, steps in (('umbrella', 2, 4), ('scale-dependent', 2, 2), ('curvature', 2, 4),
                                  ('curvature', 1, 2))]
cases.append(('sphere2_51k', 'sphere', 'iso0.25', 'curvature', 1, 2))
logs, changed = [], 0
for m, truth, noise, op, order, steps in cases:
    args = [f'{meshes}/dn_{m}_{noise}.ply', f'{meshes}/dn_{m}_clean.ply', truth, op, str(order), str(steps)]
    before, after = automatic(args, {}), automatic(args, {'FAIR_EXTEND': '1'})
    logs.append(math.log(after[1] / before[1]))
    if before != after:
        changed += 1
        k = (m, noise, op, order, steps)
        print('%s %s %s %d x%d: time step %.4g -> %.4g, auto / oracle %.3f -> %.3f' % (
            m, noise, op, order, steps, before[0], after[0], before[1] / oracle[k][0], after[1] / oracle[k][0]))
print('%d of %d changed, errors %.4f of before in geometric mean' % (
    changed, len(cases), math.exp(sum(logs) / len(logs))))
