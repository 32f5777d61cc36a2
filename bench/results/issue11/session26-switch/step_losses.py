#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's per-step volume changes (auto-gap.md section 26), a measurement aid, not part of the
# product: three first-order curvature steps at the committed study's best fixed step, each
# restoration's change (FAIR_DBG of a fairing-denoise-tool built from switch-factor.diff).
#   TOOL=BUILD2/bin/fairing-denoise-tool step_losses.py
import os
import subprocess

from study_rows import MESHES, best_rows

meshes = MESHES
steps = 3
best = best_rows()
for mesh, truth in (('torus_10k', 'torus:1:0.4'), ('sphere2_3k', 'sphere'), ('elephant_6k', 'mesh')):
    for noise in ('n0.1', 'n0.25', 'n0.5'):
        time_step = best[(mesh, noise, 'curvature', 1, steps)][1]
        err = subprocess.run([os.environ['TOOL'], 'sweep', f'{meshes}/dn_{mesh}_{noise}.ply',
                              f'{meshes}/dn_{mesh}_clean.ply', truth, 'curvature', '1', str(steps), '1',
                              '--ts', str(time_step)], env=dict(os.environ, FAIR_DBG='1'),
                             capture_output=True, text=True, check=True).stderr
        ratios = [float(x.split()[2]) for x in err.splitlines() if x.startswith('restore:')][-steps:]
        changes = [100 * (x - 1) for x in ratios]
        print('%s %s time step %.3g: changes %s %%, last / first %.2f' % (
            mesh, noise, time_step, ' / '.join('%.2f' % c for c in changes), changes[-1] / changes[0]))
