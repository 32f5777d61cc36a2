#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Automatic rows within 10 % of the oracle per filter, and the worst: count.py EXTRACT..."""
import sys, collections
from cmp_auto import load
for f in sys.argv[1:]:
    auto, fixed = load(f)
    c=collections.Counter(); t=collections.Counter(); worst=collections.defaultdict(lambda:(0,None))
    for k,a in auto.items():
        if k not in fixed: continue
        r=a/fixed[k]; t[k[2]]+=1; c[k[2]]+= r<=1.1
        if r>worst[k[2]][0]: worst[k[2]]=(r,k)
    print(f, sum(c.values()), 'of', sum(t.values()), {op:(c[op],t[op],'%.3f'%worst[op][0],worst[op][1][:2]+worst[op][1][3:]) for op in t})
