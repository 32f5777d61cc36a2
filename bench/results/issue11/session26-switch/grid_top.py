#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's scan for automatic choices at the top edge of the estimate's final grid (auto-gap.md
# section 26), a measurement aid, not part of the product: the three defaults and curvature L x2
# on five of the study's meshes at four noises, with FAIR_RISK of a fairing-denoise-tool built from
# switch-factor.diff; prints the runs whose risk is lowest at the grid's top, with the committed
# study's automatic error over its oracle.
#   TOOL=BUILD2/bin/fairing-denoise-tool grid_top.py
import os
import subprocess

from study_rows import MESHES, best_rows

fixed_rows, auto_rows = best_rows('fixed'), best_rows('auto')
meshes = MESHES
top = total = 0
for mesh, truth in (('sphere2_3k', 'sphere'), ('sphere2_13k', 'sphere'), ('torus_10k', 'torus:1:0.4'),
                    ('elephant_6k', 'mesh'), ('fandisk_13k', 'mesh')):
    for noise in ('n0.1', 'n0.25', 'n0.5', 'iso0.25'):
        for op, order, steps in (('umbrella', 2, 4), ('scale-dependent', 2, 2), ('curvature', 2, 4),
                                 ('curvature', 1, 2)):
            err = subprocess.run([os.environ['TOOL'], 'sweep', f'{meshes}/dn_{mesh}_{noise}.ply',
                                  f'{meshes}/dn_{mesh}_clean.ply', truth, op, str(order), str(steps), '1',
                                  '--auto', '--ts', '1'], env=dict(os.environ, FAIR_RISK='1'),
                                 capture_output=True, text=True, check=True).stderr.splitlines()
            risk = [float(x.split()[-1]) for x in err if x.startswith('  ')]
            head = [x.split() for x in err if x.startswith('risk:')]
            if not risk:
                continue
            total += 1
            if risk.index(min(risk)) == len(risk) - 1:
                top += 1
                auto = auto_rows[(mesh, noise, op, order, steps)]
                fixed = fixed_rows[(mesh, noise, op, order, steps)]
                print('%s %s %s %d x%d: chosen %s, converged to %s, search minimizer %s; auto / oracle %.3f, '
                      'oracle time step %.4g' % (mesh, noise, op, order, steps, head[-1][2], head[-1][8],
                                                 head[-1][10], auto[0] / fixed[0], fixed[1]))
print('%d of %d at the top edge' % (top, total))
