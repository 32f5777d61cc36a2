# SPDX-License-Identifier: GPL-3.0-or-later
# Compare two pilot_eval outputs: per-case ratio to the oracle, misses, geometric means.
import json, math, sys
def load(f): return {tuple(r['case']): r for r in map(json.loads, open(f)) if 'ratio' in r}
a, b = load(sys.argv[1]), load(sys.argv[2])
ks = sorted(set(a) & set(b))
def gm(v): return math.exp(sum(map(math.log, v)) / len(v)) if v else float('nan')
for grp in ['scale-dependent', 'curvature', '']:
    kk = [k for k in ks if grp in k[2]]
    if not kk: continue
    ra = [a[k]['ratio'] for k in kk]; rb = [b[k]['ratio'] for k in kk]
    print('%-16s n=%3d  A: gm %.4f worst %.3f miss %2d | B: gm %.4f worst %.3f miss %2d | B/A gm %.4f range %.3f-%.3f' % (
        grp or 'all', len(kk), gm(ra), max(ra), sum(r > 1.1 for r in ra), gm(rb), max(rb), sum(r > 1.1 for r in rb),
        gm([y / x for x, y in zip(ra, rb)]), min(y / x for x, y in zip(ra, rb)), max(y / x for x, y in zip(ra, rb))))
if len(sys.argv) > 3:
    for k in sorted(ks, key=lambda k: b[k]['ratio'] / a[k]['ratio']):
        if abs(b[k]['ratio'] / a[k]['ratio'] - 1) > float(sys.argv[3]):
            print('  %-60s %.3f -> %.3f' % (k, a[k]['ratio'], b[k]['ratio']))
