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
src = sys.argv[1]; suffix = sys.argv[2] if len(sys.argv) > 2 else ''
only = os.environ.get('ONLY', '')
rows = [json.loads(l) for l in open(src)]
meta = rows[0]['meta']; rows = rows[1:]
truth = {m['name']: m['truth'] for m in meta['meshes']}
M = os.environ['M'] + '/'
B = os.path.join(os.environ['BIN'], 'fairing-denoise-tool')
def run(args, env=None):
    e = dict(os.environ); e.update(env or {})
    p = subprocess.run([B, 'sweep'] + args, capture_output=True, text=True, env=e)
    return [json.loads(l) for l in p.stdout.splitlines()], p.stderr
for op, steps in [('umbrella', 4), ('scale-dependent', 2), ('curvature', 4)]:
    if only and op not in only.split(','): continue
    for m in truth:
        for nz in ['n0.1', 'n0.25', 'n0.5', 'iso0.25']:
            sel = [r for r in rows if r.get('mesh') == m and r.get('noise') == nz and r.get('method') == 'ours'
                   and r.get('op') == op and r.get('order') == 2 and r.get('steps') == steps]
            fx = [r for r in sel if r['kind'] == 'fixed' and r.get('rms')]
            if not fx: continue
            best = min(fx, key=lambda r: r['rms'])
            noisy = M + 'dn_%s_%s%s.ply' % (m, nz, suffix); clean = M + 'dn_%s_clean.ply' % m
            if not os.path.exists(noisy): continue
            base = [noisy, clean, truth[m], op, '2', str(steps), '1']
            out, err = run(base + ['--auto', '--ts', '1'], {'FAIRING_WIDE': '1'})
            auto = [r for r in out if r['kind'] == 'auto'][0]
            wide = []; sigma = n = None
            for l in err.splitlines():
                if not l.startswith('wide: '): continue
                t = l.split()
                if t[1] == 'sigma':
                    if sigma is not None: break  # the surface's only
                    sigma = float(t[2]); n = float(t[4]); continue
                wide.append(tuple(map(float, t[1:4])))
            if not wide: continue
            sure = min(wide, key=lambda w: w[1] + 2 * sigma ** 2 * w[2])
            gcv = min(wide, key=lambda w: n * w[1] / max(1e-300, (n - w[2])) ** 2 if w[2] < n - 0.5 else 1e300)
            s2 = gcv[1] / (n - gcv[2])
            out2, _ = run(base + ['--ts', '%.6g,%.6g' % (sure[0], gcv[0])])
            fxd = [r for r in out2 if r['kind'] == 'fixed']
            print('%-22s %-8s %-15s oracle %.5f@%.4g auto %.3f@%.4g sureW %.3f@%.4g gcv %.3f@%.4g sig_gcv/sig %.3f'
                  % (m, nz, op, best['rms'], best['time_step'], auto['rms'] / best['rms'], auto['time_step'],
                     fxd[0]['rms'] / best['rms'], sure[0], fxd[1]['rms'] / best['rms'], gcv[0],
                     math.sqrt(max(s2, 0)) / sigma), flush=True)
