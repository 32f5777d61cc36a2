# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Throwaway: exact SURE on the boundary loops (dense eig per loop), vs the true errors.
import numpy as np, sys, collections
M='/root/.cache/filter_implicit_fairing/bench-meshes/'
def read_ply(p):
    b=open(p,'rb').read(); i=b.index(b'end_header\n')+11; hdr=b[:i].decode()
    nv=int(hdr.split('element vertex ')[1].split()[0]); nf=int(hdr.split('element face ')[1].split()[0])
    V=np.frombuffer(b[i:i+24*nv],dtype='<f8').reshape(nv,3).astype(float)
    F=np.frombuffer(b[i+24*nv:], dtype=np.dtype([('n','u1'),('v','<i4',3)]), count=nf)['v']
    return V,F.astype(int)
def area_normals(V,F):
    N=np.zeros_like(V); fn=np.cross(V[F[:,1]]-V[F[:,0]],V[F[:,2]]-V[F[:,0]])
    for k in range(3): np.add.at(N,F[:,k],fn)
    return N/np.maximum(np.linalg.norm(N,axis=1),1e-300)[:,None], fn
def robust_normals(V,F):  # one-ring average of area normals
    N,fn=area_normals(V,F); A=np.zeros_like(V)
    for k in range(3): np.add.at(A,F[:,k],fn)
    S=A.copy(); s=A[F[:,0]]+A[F[:,1]]+A[F[:,2]]
    for k in range(3): np.add.at(S,F[:,k],s)
    return S/np.linalg.norm(S,axis=1)[:,None]
def loops(F):
    c=collections.Counter(); 
    for f in F:
        for k in range(3): a,b=f[k],f[(k+1)%3]; c[(min(a,b),max(a,b))]+=1
    # directed boundary edges
    nxt={}
    for f in F:
        for k in range(3):
            a,b=f[k],f[(k+1)%3]
            if c[(min(a,b),max(a,b))]==1: nxt[a]=b
    seen=set(); out=[]
    for s in nxt:
        if s in seen: continue
        L=[s]; seen.add(s); v=nxt[s]
        while v!=s: L.append(v); seen.add(v); v=nxt[v]
        out.append(L)
    return out
def mean_edge(V,F):
    return np.mean(np.concatenate([np.linalg.norm(V[F[:,k]]-V[F[:,(k+1)%3]],axis=1) for k in range(3)]))
def curve_op(P, h):
    n=len(P); e=np.linalg.norm(np.roll(P,-1,0)-P,axis=1); e=np.maximum(e,1e-2*h)  # kShortEdge?
    w=1/e; m=0.5*(e+np.roll(e,1))
    K=np.zeros((n,n))
    for i in range(n):
        j=(i+1)%n; K[i,i]+=w[i]; K[j,j]+=w[i]; K[i,j]-=w[i]; K[j,i]-=w[i]
    return K,m
name,nz,variant=sys.argv[1],sys.argv[2],sys.argv[3]; order=2; steps=4
Vc,F=read_ply(M+'dn_%s_clean.ply'%name); Vy,_=read_ply(M+'dn_%s_n%s_s13.ply'%(name,nz))
h=mean_edge(Vy,F); unit=h**(2*order); sigma=float(nz)*mean_edge(Vc,F)
Nc,_=area_normals(Vc,F); Nr=robust_normals(Vy,F)
grid=np.logspace(-4,3,57)
tot=collections.defaultdict(lambda: np.zeros(len(grid)))
for L in loops(F):
    L=np.array(L); n=len(L); Y=Vy[L]; X=Vc[L]
    if variant=='noisy': P=Y
    elif variant=='clean': P=X
    else:
        P=Y.copy()
        for _ in range(int(variant[5:])): P=0.5*P+0.25*(np.roll(P,1,0)+np.roll(P,-1,0))
    K,m=curve_op(P,h)
    C=K if order==1 else K@np.diag(1/m)@K
    G=np.diag(m**-0.5)@C@np.diag(m**-0.5); g,U=np.linalg.eigh(G); g=np.maximum(g,0)
    D=np.sqrt(m)
    # tangent of clean loop
    T=np.roll(X,-1,0)-np.roll(X,1,0); T/=np.linalg.norm(T,axis=1)[:,None]
    def proj(Nn):  # unit normal ⊥ t
        Q=Nn-(Nn*T).sum(1)[:,None]*T; return Q/np.linalg.norm(Q,axis=1)[:,None]
    nc=proj(Nc[L]); bc=np.cross(T,nc); nr=Nr[L]
    Yt=(U.T@(D[:,None]*Y))  # coordinates in eigenbasis
    for k,t in enumerate(grid):
        f=(1+t*unit*g)**(-steps)
        Xp=(U@(f[:,None]*Yt))/D[:,None]
        R=Xp-Y; E=Xp-X
        trH=f.sum()
        tot['rss_r'][k]+=((R*nr).sum(1)**2).sum(); tot['rss_c'][k]+=((R*nc).sum(1)**2).sum()
        tot['rss_cb'][k]+=((R*bc).sum(1)**2).sum()
        tot['tr'][k]+=trH; tot['N'][k]+=n
        tot['en'][k]+=((E*nc).sum(1)**2).sum(); tot['eb'][k]+=((E*bc).sum(1)**2).sum()
N=tot['N'][0]; s2=sigma**2
sure_r=tot['rss_r']+2*s2*tot['tr']-N*s2; sure_c=tot['rss_c']+2*s2*tot['tr']-N*s2
sure_nb=sure_c+tot['rss_cb']
for k,t in enumerate(grid):
    if k%4 or len(sys.argv)<5: continue
    print("%9.3g  sure_r %.4f sure_c %.4f  true_n %.4f | sure_nb %.4f true_nb %.4f  (per N sigma^2)"%(t,sure_r[k]/N/s2,sure_c[k]/N/s2,tot['en'][k]/N/s2,sure_nb[k]/N/s2,(tot['en'][k]+tot['eb'][k])/N/s2))
a=lambda v: grid[np.argmin(v)]
print(name,nz,"argmin: sure_r %.3g sure_c %.3g true_n %.3g | sure_nb %.3g true_nb %.3g"%(a(sure_r),a(sure_c),a(tot['en']),a(sure_nb),a(tot['en']+tot['eb'])))
i=np.argmin(sure_c); j=np.argmin(sure_nb)
print("   true_n at sure_c min %.4f (best %.4f)   true_nb at sure_nb min %.4f (best %.4f)  at sure_r min: n %.4f nb %.4f"%(tot['en'][i]/N/s2, tot['en'].min()/N/s2, (tot['en']+tot['eb'])[j]/N/s2,(tot['en']+tot['eb']).min()/N/s2, tot['en'][np.argmin(sure_r)]/N/s2,(tot['en']+tot['eb'])[np.argmin(sure_r)]/N/s2))
