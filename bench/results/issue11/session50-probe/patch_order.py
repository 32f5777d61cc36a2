#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: three numberings of a binary PLY compared by the index gaps of its edges
# and the share of edges inside one sweep block of 8,192 rows (sweeps.h): the former Z-order
# curve, breadth-first (the engine's now), and patches of 4,096 or 8,192 vertices grown
# breadth-first in that order. Needs numpy (/usr/bin/python3).
# Usage: /usr/bin/python3 patch_order.py MESH.ply
import numpy as np, sys
from collections import deque
src=open(__import__('os').path.join(__import__('os').path.dirname(__import__('os').path.abspath(__file__)), 'order_gaps.py')).read()
src=src[:src.index('v,f=read(sys.argv[1])')]
exec(src)
v,f=read(sys.argv[1]); n=len(v)
e=np.concatenate([f[:,[0,1]],f[:,[1,2]],f[:,[2,0]],f[:,[1,0]],f[:,[2,1]],f[:,[0,2]]])
o=np.argsort(e[:,0],kind='stable'); e=e[o]; st=np.searchsorted(e[:,0],np.arange(n+1)).tolist(); col=e[:,1].tolist()
def bfs(s0,seen,mark,out):
    q=deque([s0]); seen[s0]=mark; last=s0
    while q:
        u=q.popleft(); out.append(u); last=u
        for k in range(st[u],st[u+1]):
            w=col[k]
            if seen[w]!=mark: seen[w]=mark; q.append(w)
    return last
seen=[0]*n; order=[]
for i in range(n):
    if seen[i]: continue
    probe=[]; far=bfs(i,seen,1,probe); bfs(far,seen,2,order)
def patches(order,P):
    taken=bytearray(n); out=[]
    for s in order:
        if taken[s]: continue
        first=len(out); out.append(s); taken[s]=1; h=first
        while h<len(out):
            u=out[h]; h+=1
            for k in range(st[u],st[u+1]):
                w=col[k]
                if not taken[w] and len(out)-first<P: taken[w]=1; out.append(w)
    return out
def stats(name,ordr):
    ordr=np.array(ordr); rank=np.empty(n,int); rank[ordr]=np.arange(n)
    a=rank[f[:,[0,1,2]]]; g=np.concatenate([np.abs(a[:,0]-a[:,1]),np.abs(a[:,1]-a[:,2]),np.abs(a[:,2]-a[:,0])])
    b=a//8192; inb=np.concatenate([b[:,0]==b[:,1],b[:,1]==b[:,2],b[:,2]==b[:,0]]).mean()
    print(name,'gap pct50/90/99/99.9',np.percentile(g,[50,90,99,99.9]).astype(int),'>4096 %.4f >65536 %.4f'%((g>4096).mean(),(g>65536).mean()),'in-block %.3f'%inb)
stats('morton',morton(v)); stats('bfs',order)
for P in (4096,8192): stats('patch%d'%P,patches(order,P))
