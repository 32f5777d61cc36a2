#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: measurement aid, not part of any build (see README.md here).
import os
import numpy as np
# The set-up's cache, and each committed set's extract with its noisy meshes' suffix (run from the
# repository root).
CACHE=os.path.expanduser('~/.cache/filter_implicit_fairing'); MESHES=CACHE+'/bench-meshes'
SETS={'results':('bench/results/denoise.jsonl',''),'denoise-seed2':('bench/results/denoise-seed2/denoise.jsonl','_s2'),
 'denoise-seed8':('bench/results/denoise-seed8/denoise.jsonl','_s8'),'heldout-s11':('bench/results/heldout-s11/denoise.jsonl','_s11'),
 'heldout-s13':('bench/results/heldout-s13/denoise.jsonl','_s13'),'heldout-s17':('bench/results/heldout-s17/denoise.jsonl','_s17'),
 'denoise-noise':('bench/results/denoise-noise/denoise.jsonl','_s7')}
def read_ply(path):
    with open(path,'rb') as f:
        hdr=[]
        while True:
            l=f.readline().decode('ascii','replace').strip(); hdr.append(l)
            if l=='end_header': break
        data=f.read()
    nv=nf=0; vprops=[]; cur=None; fprops=None
    for l in hdr:
        t=l.split()
        if t[:2]==['element','vertex']: nv=int(t[2]); cur='v'
        elif t[:2]==['element','face']: nf=int(t[2]); cur='f'
        elif t[0]=='property':
            if cur=='v': vprops.append((t[-1],t[1]))
            elif cur=='f': fprops=t
    tmap={'float':'<f4','double':'<f8','uchar':'u1','int':'<i4','uint':'<u4','float32':'<f4','float64':'<f8'}
    vd=np.dtype([(n,tmap[ty]) for n,ty in vprops])
    V=np.frombuffer(data,dtype=vd,count=nv)
    X=np.stack([V['x'],V['y'],V['z']],1).astype(np.float64)
    off=nv*vd.itemsize
    cnt_t=tmap[fprops[2]]; idx_t=tmap[fprops[3]]
    fd=np.dtype([('n',cnt_t),('i',idx_t,(3,))])
    F=np.frombuffer(data,dtype=fd,count=nf,offset=off)
    assert (F['n']==3).all()
    return X,F['i'].astype(np.int64)
def write_ply(path,X,F):
    with open(path,'wb') as f:
        f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'%(len(X),len(F))).encode())
        f.write(np.ascontiguousarray(X,dtype='<f8').tobytes())
        fd=np.dtype([('n','u1'),('i','<i4',(3,))]); a=np.zeros(len(F),fd); a['n']=3; a['i']=F; f.write(a.tobytes())
def volume(X,F):
    a,b,c=X[F[:,0]],X[F[:,1]],X[F[:,2]]
    return np.einsum('ij,ij->i',a,np.cross(b,c)).sum()/6
def normals(X,F):
    a,b,c=X[F[:,0]],X[F[:,1]],X[F[:,2]]
    fn=np.cross(b-a,c-a)  # area-weighted *2
    n=np.zeros_like(X)
    for k in range(3): np.add.at(n,F[:,k],fn)
    return n/np.linalg.norm(n,axis=1)[:,None]
def umbrella_smooth(s,F,passes,nv):
    # half-passes of uniform averaging of a scalar over edges
    E=np.concatenate([F[:,[0,1]],F[:,[1,2]],F[:,[2,0]]]); E=np.unique(np.sort(E,1),axis=0)
    deg=np.bincount(E.ravel(),minlength=nv).astype(float)
    for _ in range(passes):
        acc=np.zeros(nv); np.add.at(acc,E[:,0],s[E[:,1]]); np.add.at(acc,E[:,1],s[E[:,0]])
        s=0.5*s+0.5*acc/deg
    return s
def restore(A,F,w,V0):
    n=normals(A,F)
    t=0.0
    for _ in range(30):
        v=volume(A+t*w[:,None]*n,F)
        h=1e-6*(abs(t)+1e-3)
        d=(volume(A+(t+h)*w[:,None]*n,F)-v)/h
        dt=(V0-v)/d; t+=dt
        if abs(dt)<1e-14*(1+abs(t)): break
    return A+t*w[:,None]*n
