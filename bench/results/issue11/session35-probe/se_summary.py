#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Geometric mean and worst of auto / best per rule scale, shapes with a known surface and scans
apart, and the cases past 10 %, over se_rule.py outputs.   se_summary.py OUT.txt..."""
import collections, math, sys

logs, worst, misses = collections.defaultdict(list), collections.defaultdict(float), \
    collections.Counter()
for name in sys.argv[1:]:
    for line in open(name):
        t = line.split()
        if len(t) < 5 or t[2] != 'oracle':
            continue
        kind = 'known' if t[0].split('_')[0] in ('sphere2', 'torus', 'plane') else 'scan'
        for item in t[4:]:
            k, rest = item.split(':')
            r = float(rest.split('@')[0])
            for key in ((k, kind), (k, 'all')):
                logs[key].append(math.log(r))
                worst[key] = max(worst[key], r)
            misses[k] += r > 1.1
for key in sorted(logs):
    print('scale %s %-5s cases %3d gmean %.4f worst %.3f' % (key + (len(logs[key]),
          math.exp(sum(logs[key]) / len(logs[key])), worst[key])))
print('past 10 %:', dict(misses))
