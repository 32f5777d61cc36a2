# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Throwaway: SURE on loops with noisy weights and the divergence by Monte-Carlo (probes along normals)
import numpy as np, sys
import os
exec(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'loopsure.py')).read().split("name,nz,variant=")[0])
name,nz,probes=sys.argv[1],sys.argv[2],int(sys.argv[3])
Vc,F=read_ply(M+'dn_%s_clean.ply'%name); Vy,_=read_ply(M+'dn_%s_n%s_s13.ply'%(name,nz))
h=mean_edge(Vy,F); unit=h**4; sigma=float(nz)*mean_edge(Vc,F); steps=4
Nc,_=area_normals(Vc,F); Nr=robust_normals(Vy,F)
grid=np.logspace(-4,3,57)
def filt(P, Y):  # operator at P applied to Y, all grid
    K,m=curve_op(P,h); C=K@np.diag(1/m)@K
    G=np.diag(m**-0.5)@C@np.diag(m**-0.5); g,U=np.linalg.eigh(G); g=np.maximum(g,0); D=np.sqrt(m)
    Yt=U.T@(D[:,None]*Y)
    return [ (U@(((1+t*unit*g)**(-steps))[:,None]*Yt))/D[:,None] for t in grid ]
rng=np.random.default_rng(5)
rss=np.zeros(len(grid)); div=np.zeros((probes,len(grid))); en=np.zeros(len(grid)); eb=np.zeros(len(grid)); N=0
for L in loops(F):
    L=np.array(L); n=len(L); Y=Vy[L]; X=Vc[L]; nr=Nr[L]; N+=n
    T=np.roll(X,-1,0)-np.roll(X,1,0); T/=np.linalg.norm(T,axis=1)[:,None]
    nc=Nc[L]-(Nc[L]*T).sum(1)[:,None]*T; nc/=np.linalg.norm(nc,axis=1)[:,None]; bc=np.cross(T,nc)
    base=filt(Y,Y); eps=0.01*sigma
    for k,Xp in enumerate(base):
        rss[k]+=(((Xp-Y)*nr).sum(1)**2).sum(); E=Xp-X
        en[k]+=((E*nc).sum(1)**2).sum(); eb[k]+=((E*bc).sum(1)**2).sum()
    for p in range(probes):
        b=rng.choice([-1.0,1.0],n)
        Yp=Y+eps*b[:,None]*nr
        pert=filt(Yp,Yp)
        for k in range(len(grid)):
            div[p,k]+=((b[:,None]*nr*(pert[k]-base[k])).sum())/eps
s2=sigma**2
for p in range(probes):
    sure=rss+2*s2*div[p]-N*s2
    i=np.argmin(sure); print("probe %d argmin %.3g true_n there %.4f (best %.4f at %.3g)"%(p,grid[i],en[i]/N/s2,en.min()/N/s2,grid[np.argmin(en)]))
sure=rss+2*s2*div.mean(0)-N*s2; i=np.argmin(sure)
print("mean of probes: argmin %.3g true_n %.4f"%(grid[i],en[i]/N/s2))
