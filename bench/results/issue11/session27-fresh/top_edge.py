#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 27's scan of the curvature flow's L^2 choices (auto-gap.md section 27), a measurement
# aid, not part of the product: the 76 automatic runs of curvature L^2 x2-x4 on eight of the study's
# meshes at its four noises, with FAIR_FRESH=1 FAIR_RISK=1 of a build of risk-trace.diff; prints
# whether the final grid's risk is lowest at its top edge, its last slope and curvature there,
# and the committed study's automatic error over its oracle and the oracle's time step over the
# choice.
#   TOOL=BUILD/bin/fairing-denoise-tool top_edge.py
import json
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
CACHE = os.environ.get('FAIRING_CACHE', os.path.expanduser('~/.cache/filter_implicit_fairing'))
MESHES = os.path.join(CACHE, 'bench-meshes')
oracle, auto = {}, {}
with open(os.path.join(HERE, '../../denoise.jsonl')) as f:
    for line in f:
        r = json.loads(line)
        if r.get('method') != 'ours' or 'op' not in r:
            continue
        k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
        if r['kind'] == 'fixed':
            oracle[k] = min(oracle.get(k, (float('inf'), 0)), (r['rms'], r['time_step']))
        else:
            auto[k] = (r['rms'], r['time_step'])
truths = {'sphere2_3k': 'sphere', 'sphere2_13k': 'sphere', 'torus_10k': 'torus:1:0.4'}
for mesh in ('sphere2_3k', 'sphere2_13k', 'torus_10k', 'elephant_6k', 'fandisk_13k', 'camel_20k',
             'dragon_20k', 'elephant_loop1_22k'):
    for noise in ('n0.1', 'n0.25', 'n0.5', 'iso0.25'):
        for steps in (2, 3, 4):
            k = (mesh, noise, 'curvature', 2, steps)
            if k not in auto:
                continue
            err = subprocess.run([os.environ['TOOL'], 'sweep', f'{MESHES}/dn_{mesh}_{noise}.ply',
                                  f'{MESHES}/dn_{mesh}_clean.ply', truths.get(mesh, 'mesh'),
                                  'curvature', '2', str(steps), '1', '--auto', '--ts', '1'],
                                 env=dict(os.environ, FAIR_FRESH='1', FAIR_RISK='1'),
                                 capture_output=True, text=True, check=True).stderr.splitlines()
            head = [x for x in err if x.startswith('risk:')][-1]
            risk = []
            for x in err[err.index(head) + 1:]:
                if not x.startswith('  ') or 'recomputed' in x:
                    break
                risk.append(float(x.split()[-1]))
            f = head.split()
            print('%s %s x%d: top %d, last slope %+.1e, curvature %+.1e, converged to %s, search '
                  'minimizer %s, chosen %s; auto / oracle %.3f, oracle time step / chosen %.2f' % (
                      mesh, noise, steps, risk.index(min(risk)) == len(risk) - 1,
                      risk[-1] - risk[-2], risk[-1] - 2 * risk[-2] + risk[-3], f[8], f[10], f[2],
                      auto[k][0] / oracle[k][0], oracle[k][1] / auto[k][1]), flush=True)
