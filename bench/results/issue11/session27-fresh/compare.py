#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 27's comparison of two runs' automatic rows (auto-gap.md section 27), a measurement aid,
# not part of the product: each automatic row of AFTER against the same row of BEFORE and the
# oracle (lowest fixed-step error of ours) of ORACLE; prints the rows that moved by more than 2 %
# or across 10 % of the oracle, then the counts.
#   compare.py ORACLE.jsonl BEFORE.jsonl AFTER.jsonl
import json
import math
import sys


def rows(path, kind):
    out = {}
    with open(path) as f:
        for line in f:
            r = json.loads(line)
            if r.get('method') != 'ours' or r.get('kind') != kind or 'op' not in r:
                continue
            k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
            if kind == 'fixed':
                out[k] = min(out.get(k, (math.inf, 0)), (r['rms'], r['time_step']))
            else:
                out[k] = (r['rms'], r['time_step'], r.get('strength_iterations', 0))
    return out


oracle = rows(sys.argv[1], 'fixed')
before, after = rows(sys.argv[2], 'auto'), rows(sys.argv[3], 'auto')
logs, changed, missed, steps = [], 0, [0, 0], [0, 0]
for k in sorted(after):
    if k not in before or k not in oracle:
        continue
    a, b = before[k][0] / oracle[k][0], after[k][0] / oracle[k][0]
    logs.append(math.log(after[k][0] / before[k][0]))
    missed[0] += a > 1.1
    missed[1] += b > 1.1
    steps[0] += before[k][2]
    steps[1] += after[k][2]
    if before[k][0] == after[k][0]:
        continue
    changed += 1
    if abs(b / a - 1) > 0.02 or (a > 1.1) != (b > 1.1):
        print('%s %s %s L%s x%d: %.3f -> %.3f of the oracle, time step %.4g -> %.4g, '
              'Lanczos steps %d -> %d' % (k[0], k[1], k[2], '' if k[3] == 1 else '2', k[4], a, b,
                                          before[k][1], after[k][1], before[k][2], after[k][2]))
print('%d rows, %d changed; past 10 %% of the oracle %d -> %d; errors %.4f of before in geometric '
      'mean; Lanczos steps %d -> %d' % (len(logs), changed, missed[0], missed[1],
                                        math.exp(sum(logs) / len(logs)), steps[0], steps[1]))
