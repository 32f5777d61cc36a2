#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Generalized cross-validation (Craven & Wahba 1979) against SURE on the estimate's own curves:
a build with throwaway.patch prints, with FAIRING_WIDE=1, the residual and the divergence on a
wide grid (the minimizer / 3000 to the converged end). For each mesh, noise and default filter of
a committed extract: SURE's minimizer on that grid (sureW), GCV's, N RSS / (N - div)^2, and each
one's error at its step against the extract's best fixed step; sig_gcv/sig: GCV's implied noise
level, RSS / (N - div) at its minimizer, over the estimate's.
  BIN=BENCH/bin M=MESHES [ONLY=umbrella,...] gcv.py EXTRACT.jsonl [SUFFIX]"""
import json, math, os, subprocess, sys

src = sys.argv[1]
suffix = sys.argv[2] if len(sys.argv) > 2 else ''
only = os.environ.get('ONLY', '')
rows = [json.loads(l) for l in open(src)]
truth = {m['name']: m['truth'] for m in rows[0]['meta']['meshes']}
rows = rows[1:]
meshes = os.environ['M']
tool = os.path.join(os.environ['BIN'], 'fairing-denoise-tool')


def run(args, env=None):
    e = dict(os.environ)
    e.update(env or {})
    p = subprocess.run([tool, 'sweep'] + args, capture_output=True, text=True, env=e)
    return [json.loads(l) for l in p.stdout.splitlines()], p.stderr


def curves(err):
    """The surface's wide grid (the first printed): noise level, data rows, (t, rss, div)."""
    wide, sigma, n = [], None, None
    for line in err.splitlines():
        if not line.startswith('wide: '):
            continue
        t = line.split()
        if t[1] == 'sigma':
            if sigma is not None:
                break
            sigma, n = float(t[2]), float(t[4])
            continue
        wide.append(tuple(map(float, t[1:4])))
    return sigma, n, wide


for op, steps in [('umbrella', 4), ('scale-dependent', 2), ('curvature', 4)]:
    if only and op not in only.split(','):
        continue
    for m in truth:
        for nz in ['n0.1', 'n0.25', 'n0.5', 'iso0.25']:
            fixed = [r for r in rows if r.get('mesh') == m and r.get('noise') == nz
                     and r.get('method') == 'ours' and r.get('op') == op and r.get('order') == 2
                     and r.get('steps') == steps and r['kind'] == 'fixed' and r.get('rms')]
            noisy = os.path.join(meshes, 'dn_%s_%s%s.ply' % (m, nz, suffix))
            if not fixed or not os.path.exists(noisy):
                continue
            best = min(fixed, key=lambda r: r['rms'])
            clean = os.path.join(meshes, 'dn_%s_clean.ply' % m)
            base = [noisy, clean, truth[m], op, '2', str(steps), '1']
            out, err = run(base + ['--auto', '--ts', '1'], {'FAIRING_WIDE': '1'})
            auto = [r for r in out if r['kind'] == 'auto'][0]
            sigma, n, wide = curves(err)
            if not wide:
                continue
            sure = min(wide, key=lambda w: w[1] + 2 * sigma ** 2 * w[2])
            gcv = min(wide, key=lambda w: n * w[1] / (n - w[2]) ** 2 if w[2] < n - 0.5 else 1e300)
            s2 = gcv[1] / (n - gcv[2])
            out2, _ = run(base + ['--ts', '%.6g,%.6g' % (sure[0], gcv[0])])
            at = [r['rms'] / best['rms'] for r in out2 if r['kind'] == 'fixed']
            print('%-22s %-8s %-15s oracle %.5f@%.4g auto %.3f@%.4g sureW %.3f@%.4g gcv %.3f@%.4g '
                  'sig_gcv/sig %.3f' % (m, nz, op, best['rms'], best['time_step'],
                                        auto['rms'] / best['rms'], auto['time_step'], at[0],
                                        sure[0], at[1], gcv[0], math.sqrt(max(s2, 0)) / sigma),
                  flush=True)
