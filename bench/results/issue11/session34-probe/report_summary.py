#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""From a study report (denoise.md): the automatic rows within 10 % of the oracle, each filter's
one-click default (L^2, 8 / 2 / 4 steps since session 38, 4 / 2 / 4 before: --steps 4/2/4)
within 10 % with its misses, and per mesh the range of the best one-click result of ours over the
best peer at its best setting.
  report_summary.py [--steps U/S/C] DENOISE.md..."""
import sys, re, collections
args = sys.argv[1:]
steps = '8/2/4'
if args[:1] == ['--steps']:
    steps, args = args[1], args[2:]
DEF = set(zip(('umbrella', 'scale-dep.', 'curvature'), ('2', '2', '2'), steps.split('/')))
for path in args:
    lines = open(path).read().split('\n')
    allrows = [l for l in lines if '| all rows |' in l]
    print('==', path); print(allrows[0].split('|')[3].strip() if allrows else '?')
    # the per-row automatic table: | mesh | noise | filter | order | steps | oracle | oracle ts
    # | auto | auto ts | ratio | estimate |
    d = collections.defaultdict(list)
    for l in lines:
        c = [x.strip() for x in l.split('|')]
        if len(c) == 13 and (c[3], c[4], c[5]) in DEF:
            try: d[c[3]].append((float(c[10]), c[1], c[2]))
            except ValueError: pass
    for f, v in d.items():
        ok = sum(1 for r in v if r[0] <= 1.10)
        w = max(v)
        misses = ', '.join('%s %s %.3f' % (r[1], r[2], r[0])
                           for r in sorted(v, reverse=True) if r[0] > 1.10)
        print('  default %s: %d of %d within 10%%, worst %.3f (%s %s); misses: %s'
              % (f, ok, len(v), w[0], w[1], w[2], misses))
    # per case vs peers: ratio column
    per = collections.defaultdict(list)
    for l in lines:
        c = [x.strip() for x in l.split('|')]
        if len(c) == 14 and re.match(r'^[0-9.]+$', c[11] or ''):
            per[c[1]].append(float(c[11]))
    for m, v in per.items():
        print('  vs best peer %s: %.3f-%.3f' % (m, min(v), max(v)))
