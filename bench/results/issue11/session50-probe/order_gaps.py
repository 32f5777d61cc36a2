# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: the index gaps of a binary PLY's edges in its own order, along the engine's
# former Z-order curve and breadth-first; with an output path, writes the mesh renumbered
# breadth-first (from a far end, as vertex_order.cpp now does). Needs numpy (/usr/bin/python3).
# Usage: /usr/bin/python3 order_gaps.py MESH.ply [OUT.ply]
import numpy as np, sys
from collections import deque
def read(p):
    b=open(p,'rb').read(); h=b.index(b'end_header\n')+11
    hdr=b[:h].decode().split('\n'); nv=int([l for l in hdr if l.startswith('element vertex')][0].split()[2]); nf=int([l for l in hdr if l.startswith('element face')][0].split()[2])
    v=np.frombuffer(b,dtype='<f8',count=nv*3,offset=h).reshape(nv,3)
    f=np.frombuffer(b,dtype=np.dtype([('n','u1'),('i','<i4',3)]),count=nf,offset=h+nv*24)['i']
    return v.copy(),f.copy()
def write(p,v,f):
    with open(p,'wb') as o:
        o.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"%(len(v),len(f))).encode())
        o.write(v.astype('<f8').tobytes())
        a=np.zeros(len(f),dtype=np.dtype([('n','u1'),('i','<i4',3)])); a['n']=3; a['i']=f; o.write(a.tobytes())
def spread(x):
    x=x.astype(np.uint64)&np.uint64(0x1fffff)
    for s,m in [(32,0x1f00000000ffff),(16,0x1f0000ff0000ff),(8,0x100f00f00f00f00f),(4,0x10c30c30c30c30c3),(2,0x1249249249249249)]:
        x=(x|(x<<np.uint64(s)))&np.uint64(m)
    return x
def morton(v):
    lo=v.min(0); ext=v.max(0)-lo; u=((v-lo)/ext*((1<<21)-1)).astype(np.uint64)
    key=spread(u[:,0])|(spread(u[:,1])<<np.uint64(1))|(spread(u[:,2])<<np.uint64(2))
    return np.argsort(key,kind='stable')
def gaps(order,f):
    rank=np.empty(len(order),int); rank[order]=np.arange(len(order))
    e=np.concatenate([f[:,[0,1]],f[:,[1,2]],f[:,[2,0]]]); g=np.abs(rank[e[:,0]]-rank[e[:,1]])
    return np.percentile(g,[50,90,99,99.9]), (g>4096).mean(), (g>16384).mean()
v,f=read(sys.argv[1]); n=len(v)
print("input", gaps(np.arange(n),f))
print("morton", gaps(morton(v),f))

e=np.concatenate([f[:,[0,1]],f[:,[1,2]],f[:,[2,0]],f[:,[1,0]],f[:,[2,1]],f[:,[0,2]]])
o=np.argsort(e[:,0],kind='stable'); e=e[o]; start=np.searchsorted(e[:,0],np.arange(n+1)); col=e[:,1].tolist(); st=start.tolist()
deg=np.diff(start)
seen=bytearray(n); order=[]
# start from a min-degree vertex far away (pseudo-peripheral: BFS twice)
def bfs(s0):
    seen=bytearray(n); q=deque([s0]); seen[s0]=1; out=[]
    while q:
        u=q.popleft(); out.append(u)
        for k in range(st[u],st[u+1]):
            w=col[k]
            if not seen[w]: seen[w]=1; q.append(w)
    return out
o1=bfs(0); o2=bfs(o1[-1])
bfs_order=np.array(o2)
print("bfs", gaps(bfs_order,f))
if len(sys.argv)>2:
    rank=np.empty(n,int); rank[bfs_order]=np.arange(n)
    write(sys.argv[2],v[bfs_order],rank[f])
