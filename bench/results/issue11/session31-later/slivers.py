# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Throwaway: how far the dragon's loop vertices move in its 12 one-click CLI runs, in mean edges.
import os
import numpy as np, sys, collections, subprocess
exec(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'session30-loops', 'loopsure.py')).read().split("def mean_edge")[0].split("name,nz,variant=")[0])
M='/root/.cache/filter_implicit_fairing/bench-meshes/'
X,F=read_ply(M+'dn_dragon_20k_clean.ply')
h=np.mean(np.concatenate([np.linalg.norm(X[F[:,k]]-X[F[:,(k+1)%3]],axis=1) for k in range(3)]))
L=sum(loops(F),[]); worst=0
for op in ['umbrella','scale-dependent','curvature']:
    for n in ['n0.1','n0.25','n0.5','iso0.25']:
        Y,_=read_ply(M+'dn_dragon_20k_%s.ply'%n)
        subprocess.run([os.environ.get('CLI', '/tmp/bC/bin/implicit-fairing'),M+'dn_dragon_20k_%s.ply'%n,'/tmp/slivers_out.ply','--operator',op],check=True,capture_output=True)
        b=open('/tmp/slivers_out.ply','rb').read(); i=b.index(b'end_header\n')+11
        nv=int(b[:i].decode().split('element vertex ')[1].split()[0]); R=np.frombuffer(b[i:i+12*nv],dtype='<f4').reshape(nv,3).astype(float)
        m=np.linalg.norm(R[L]-Y[L],axis=1).max()/h; worst=max(worst,m); print(op,n,'%.3f'%m)
print('worst %.3f'%worst)
