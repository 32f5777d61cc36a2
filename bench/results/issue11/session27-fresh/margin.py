#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 27's check that the L^2 choices have converged (auto-gap.md section 27), a measurement
# aid, not part of the product: the three defaults and curvature L^2 x2 on six of the study's
# meshes at its four noises, with the search stopping at converged_to >= 2 x the minimizer (as
# committed) and >= 8 x (FAIR_MARGIN=8 of a build of risk-trace.diff), both with FAIR_FRESH=1.
#   TOOL=BUILD/bin/fairing-denoise-tool margin.py
import json
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
CACHE = os.environ.get('FAIRING_CACHE', os.path.expanduser('~/.cache/filter_implicit_fairing'))
M = os.path.join(CACHE, 'bench-meshes')
T = os.environ['TOOL']
oracle = {}
for line in open(os.path.join(HERE, '../../denoise.jsonl')):
    r = json.loads(line)
    if r.get('method') == 'ours' and 'op' in r and r['kind'] == 'fixed':
        k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
        oracle[k] = min(oracle.get(k, (float('inf'), 0)), (r['rms'], r['time_step']))
truths = {'sphere2_3k': 'sphere', 'sphere2_13k': 'sphere', 'torus_10k': 'torus:1:0.4'}
def run(mesh, noise, op, order, steps, env):
    out = subprocess.run([T, 'sweep', f'{M}/dn_{mesh}_{noise}.ply', f'{M}/dn_{mesh}_clean.ply',
                          truths.get(mesh, 'mesh'), op, str(order), str(steps), '1', '--auto',
                          '--ts', '1'], env=dict(os.environ, FAIR_FRESH='1', **env),
                         capture_output=True, text=True, check=True).stdout
    r = [json.loads(x) for x in out.splitlines() if '"auto"' in x][0]
    return r['time_step'], r['rms'], r['strength_iterations']
ops = [('curvature', 2, 4), ('curvature', 2, 2), ('scale-dependent', 2, 2), ('umbrella', 2, 4)]
for mesh in ('sphere2_3k', 'sphere2_13k', 'torus_10k', 'elephant_6k', 'fandisk_13k', 'camel_20k'):
    for noise in ('n0.1', 'n0.25', 'n0.5', 'iso0.25'):
        for op, order, steps in ops:
            k = (mesh, noise, op, order, steps)
            a = run(*k, {}); b = run(*k, {'FAIR_MARGIN': '8'})
            o = oracle[k][0]
            print('%-12s %-7s %-15s L%d x%d: ts %.4g -> %.4g, auto/oracle %.3f -> %.3f, '
                  'steps %d -> %d' % (k + (a[0], b[0], a[1] / o, b[1] / o, a[2], b[2])), flush=True)
