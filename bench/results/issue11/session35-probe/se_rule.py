#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The automatic choice of an L^2 filter with and without the one-standard-error rule, against the
best fixed step of a committed study extract (its fixed rows: the engine change moves only the
choice). A build with throwaway.patch reads FAIRING_SE_L2=k (the rule at k standard errors for the
curvature flow's several L^2 steps; unset: the minimizer, as at d653704). SE_ENV names another
such variable (session 36: FAIRING_SE_UMB, the umbrella's); ORDER another order than 2.
  BIN=BENCH/bin M=MESHES [SE_ENV=NAME] [ORDER=1] se_rule.py EXTRACT.jsonl SUFFIX OP STEPS SCALES \
      [NOISES]
SUFFIX: the inputs' seed suffix ('' for seed 1, _s2, ...); SCALES: e.g. 0,1 (0: unset);
NOISES: comma-separated noise:file pairs (default n0.1, n0.25, n0.5, iso0.25 as named)."""
import json, os, subprocess, sys

order = os.environ.get('ORDER', '2')

src, suffix, op, steps, scales = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), \
    sys.argv[5].split(',')
noises = [tuple(x.split(':')) if ':' in x else (x, x) for x in
          (sys.argv[6] if len(sys.argv) > 6 else 'n0.1,n0.25,n0.5,iso0.25').split(',')]
rows = [json.loads(l) for l in open(src)]
truth = {m['name']: m['truth'] for m in rows[0]['meta']['meshes']}
rows = rows[1:]
tool = os.path.join(os.environ['BIN'], 'fairing-denoise-tool')
meshes = os.environ['M']
for m in truth:
    for nz, fn in noises:
        fixed = [r for r in rows if r.get('mesh') == m and r.get('noise') == nz
                 and r.get('method') == 'ours' and r.get('op') == op
                 and r.get('order') == int(order) and r.get('steps') == steps
                 and r['kind'] == 'fixed' and r.get('rms')]
        if not fixed:
            continue
        best = min(fixed, key=lambda r: r['rms'])
        noisy = os.path.join(meshes, 'dn_%s_%s%s.ply' % (m, fn, suffix))
        clean = os.path.join(meshes, 'dn_%s_clean.ply' % m)
        out = []
        for k in scales:
            env = dict(os.environ)
            if k != '0':
                env[os.environ.get('SE_ENV', 'FAIRING_SE_L2')] = k
            lines = subprocess.run([tool, 'sweep', noisy, clean, truth[m], op, order, str(steps),
                                    '1', '--auto', '--ts', '1'], capture_output=True, text=True,
                                   env=env).stdout.splitlines()
            a = [json.loads(l) for l in lines if '"auto"' in l][0]
            out.append('%s:%.3f@%.4g' % (k, a['rms'] / best['rms'], a['time_step']))
        print('%-20s %-8s oracle %.5f@%.4g  %s' % (m, nz, best['rms'], best['time_step'],
                                                   '  '.join(out)), flush=True)
