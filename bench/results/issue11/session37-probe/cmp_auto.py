#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The automatic rows that moved between two study extracts, per filter setting, against the old
extract's oracles: cmp_auto.py OLD.jsonl NEW.jsonl [v]. load() serves count.py too."""
import json, sys, math, collections
def load(f):
    rows=[json.loads(l) for l in open(f)][1:]
    auto={}; fixed={}
    for r in rows:
        if r.get('method')!='ours' or 'rms' not in r or r.get('kind') not in ('auto','fixed'): continue
        k=(r['mesh'],r['noise'],r['op'],r['order'],r['steps'])
        if r['kind']=='auto': auto[k]=r['rms']
        else: fixed[k]=min(fixed.get(k,9),r['rms'])
    return auto,fixed
if __name__ == '__main__':
    a0,f0=load(sys.argv[1]); a1,f1=load(sys.argv[2])
    moved=collections.defaultdict(list)
    for k in a0:
        if k not in a1 or k not in f0: continue
        r0=a0[k]/f0[k]; r1=a1[k]/f0[k]
        if abs(r1/r0-1)>1e-6: moved[(k[2],k[3],k[4])].append((k,r0,r1))
    for s,v in sorted(moved.items()):
        g0=math.exp(sum(math.log(x[1]) for x in v)/len(v)); g1=math.exp(sum(math.log(x[2]) for x in v)/len(v))
        print('%s: %d rows moved, gmean %.4f -> %.4f, past 10%% %d -> %d' % (s,len(v),g0,g1,sum(x[1]>1.1 for x in v),sum(x[2]>1.1 for x in v)))
        if len(sys.argv)>3:
            for k,r0,r1 in sorted(v):
                print('   %-20s %-8s %.3f -> %.3f' % (k[0],k[1],r0,r1))
