#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
import sys, math, re
vals={}
for f in sys.argv[1:]:
    for l in open(f):
        for m in re.finditer(r'x(\d+) ([0-9.]+) ([0-9.]+)', l):
            vals.setdefault(m.group(1),[]).append((float(m.group(3)), f+l.split()[0], l.split()[1], float(m.group(2))))
base={ (a[1],a[2]):a[3] for a in vals['4']}
for k,v in sorted(vals.items(), key=lambda x:int(x[0])):
    r=[x[0] for x in v]; g=math.exp(sum(map(math.log,r))/len(r))
    rel=[x[3]/base[(x[1],x[2])] for x in v]; gr=math.exp(sum(map(math.log,rel))/len(rel))
    print('x%s: %d cases gmean one-click/peer %.4f, <=1.000 %d, <=1.01 %d, worst %.3f; umbrella auto vs x4 gmean %.4f range %.3f-%.3f' % (k,len(r),g,sum(x<=1 for x in r),sum(x<=1.01 for x in r),max(r),gr,min(rel),max(rel)))
