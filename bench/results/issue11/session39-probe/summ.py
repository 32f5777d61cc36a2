#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: measurement aid, not part of any build (see README.md here).
import json,sys,math,collections
rows=[json.loads(l) for l in open(sys.argv[1])]
def g(xs): return math.exp(sum(map(math.log,xs))/len(xs)) if xs else float('nan')
by=collections.defaultdict(list)
for r in rows:
    lv=r['noise']
    by[lv].append(r)
print('noise  n  est/orc gmean worst >1.1 | true/orc gmean worst >1.1')
for lv in sorted(by):
    rs=by[lv]; e=[r['est']/r['oracle'] for r in rs]; t=[r['true']/r['oracle'] for r in rs]
    print('%-8s %3d  %.4f %.3f %d | %.4f %.3f %d'%(lv,len(rs),g(e),max(e),sum(x>1.1 for x in e),g(t),max(t),sum(x>1.1 for x in t)))
e=[r['est']/r['oracle'] for r in rows]; t=[r['true']/r['oracle'] for r in rows]
print('all %d  %.4f %.3f %d | %.4f %.3f %d'%(len(rows),g(e),max(e),sum(x>1.1 for x in e),g(t),max(t),sum(x>1.1 for x in t)))
if len(sys.argv)>2:
    for r in rows:
        if r['noise'] in sys.argv[2].split(','): print('%-14s %-18s %-8s est %.3f (ts %.3g sig %.3f) true %.3f (ts %.3g) orc_ts %.3g'%(r['set'],r['mesh'],r['noise'],r['est']/r['oracle'],r['est_ts'],r['est_sig'],r['true']/r['oracle'],r['true_ts'],r['oracle_ts']))
