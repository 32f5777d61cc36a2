#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
import json, sys, collections
for f in sys.argv[1:]:
    rows=[json.loads(l) for l in open(f)][1:]
    auto={}; fixed={}
    for r in rows:
        if r.get('method')!='ours' or 'rms' not in r or r.get('kind') not in ('auto','fixed'): continue
        k=(r['mesh'],r['noise'],r['op'],r['order'],r['steps'])
        if r['kind']=='auto': auto[k]=r['rms']
        else: fixed[k]=min(fixed.get(k,9),r['rms'])
    c=collections.Counter(); t=collections.Counter(); worst=collections.defaultdict(lambda:(0,None))
    for k,a in auto.items():
        if k not in fixed: continue
        r=a/fixed[k]; t[k[2]]+=1; c[k[2]]+= r<=1.1
        if r>worst[k[2]][0]: worst[k[2]]=(r,k)
    print(f, sum(c.values()), 'of', sum(t.values()), {op:(c[op],t[op],'%.3f'%worst[op][0],worst[op][1][:2]+worst[op][1][3:]) for op in t})
