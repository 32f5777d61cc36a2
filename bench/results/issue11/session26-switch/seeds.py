#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 26's fresh noise draws (auto-gap.md section 26), a measurement aid, not part of the
# product: for noise draws the study never made (seeds 2 and 8), the automatic choice's error over
# the best fixed step's (fairing-denoise-tool sweep's log search) for first-order curvature steps,
# with the switch on the steps' total (FAIR_SWITCH_TOTAL=1) and per step (as committed), from a
# fairing-denoise-tool built from switch-factor.diff.
#   TOOL=BUILD2/bin/fairing-denoise-tool seeds.py OUT_DIR
# Meshes: the study's clean meshes ($FAIRING_CACHE/bench-meshes); the noisy ones go to OUT_DIR.
import json
import math
import os
import subprocess
import sys

from study_rows import MESHES

meshes = MESHES
tool = os.environ['TOOL']
out_dir = sys.argv[1]
os.makedirs(out_dir, exist_ok=True)


def sweep(noisy, clean, truth, steps, extra, env):
    out = subprocess.run([tool, 'sweep', noisy, clean, truth, 'curvature', '1', str(steps)] + extra,
                         env=dict(os.environ, **env), capture_output=True, text=True, check=True).stdout
    return [json.loads(x) for x in out.splitlines() if x.startswith('{')]


logs = {'total': [], 'per step': []}
for mesh, truth in (('torus_10k', 'torus:1:0.4'), ('sphere2_3k', 'sphere'), ('sphere2_13k', 'sphere'),
                    ('elephant_6k', 'mesh')):
    clean = f'{meshes}/dn_{mesh}_clean.ply'
    for seed in (2, 8):
        for noise in ('n0.1', 'n0.25', 'n0.5', 'iso0.25'):
            noisy = f'{out_dir}/dn_{mesh}_{noise}_s{seed}.ply'
            if not os.path.exists(noisy):
                subprocess.run([tool, 'noise', clean, noisy, noise.lstrip('iso').lstrip('n'), str(seed),
                                'iso' if noise.startswith('iso') else 'normal'], check=True,
                               capture_output=True)
            for steps in (2, 3, 4):
                auto = {}
                for name, env in (('total', {'FAIR_SWITCH_TOTAL': '1'}), ('per step', {})):
                    r = [x for x in sweep(noisy, clean, truth, steps, ['1', '--auto', '--ts', '1'], env)
                         if x['kind'] == 'auto'][0]
                    auto[name] = (r['time_step'], r['rms'])
                start = auto['per step'][0]
                best = min(x['rms'] for x in sweep(noisy, clean, truth, steps, [str(start)], {})
                           if x['kind'] == 'fixed')
                for name in auto:
                    logs[name].append(math.log(auto[name][1] / best))
                print('%s s%d %s L x%d: best %.5f; total %.4g %.3f; per step %.4g %.3f' % (
                    mesh, seed, noise, steps, best, auto['total'][0], auto['total'][1] / best,
                    auto['per step'][0], auto['per step'][1] / best), flush=True)
for name, v in logs.items():
    print('%s: geometric mean %.4f, worst %.3f, past 10 %%: %d of %d' % (
        name, math.exp(sum(v) / len(v)), math.exp(max(v)), sum(x > math.log(1.1) for x in v), len(v)))
