#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: measurement aid, not part of any build (see README.md here).
import sys,os,json,subprocess,tempfile,numpy as np
sys.path.insert(0,os.path.dirname(os.path.abspath(__file__))); from plyio import *
C=CACHE; I=C+'/bench-build/main/bin/implicit-fairing'; T=C+'/bench-build/bench/bin/fairing-denoise-tool'; M=MESHES
def cli(i,o,ts,extra=()):
    subprocess.run([I,'--operator','umbrella','--order','2','--steps',str(STEPS),'--time-step',repr(ts),*extra,i,o],check=True,capture_output=True)
STEPS=int(os.environ.get('STEPS','8'))
name,noisy,truth=sys.argv[1:4]; grid=[float(x) for x in sys.argv[4].split(',')]
clean=M+'/dn_%s_clean.ply'%name; y=M+'/'+noisy
Y,F=read_ply(y); V0=volume(Y,F); nv=len(Y)
wd=os.path.join(tempfile.gettempdir(),'w_'+noisy.replace('.ply','')); os.makedirs(wd,exist_ok=True)
variants=['engine','uniform','pos_s8','pos_s16','half_s8','half_s16','half_s32','third_s16']
res={v:[] for v in variants}
for ts in grid:
    a,b,r=wd+'/a.ply',wd+'/b.ply',wd+'/r_%g.ply'%ts
    cli(y,a,ts,['--no-volume']); cli(a,b,ts,['--no-volume']); cli(y,r,ts)
    A,_=read_ply(a); B,_=read_ply(b); n=normals(A,F)
    s=np.einsum('ij,ij->i',n,A-B)
    fields={'uniform':np.ones(nv)}
    for k in (8,16): fields['pos_s%d'%k]=np.maximum(umbrella_smooth(s,F,k,nv),0)
    for k in (8,16,32):
        w=np.maximum(umbrella_smooth(s,F,k,nv),0); fields['half_s%d'%k]=0.5+0.5*w/w.mean()
    w=np.maximum(umbrella_smooth(s,F,16,nv),0); fields['third_s16']=2/3+1/3*w/w.mean()
    files=[r]
    for k,w in fields.items():
        X=restore(A,F,w,V0); fn=wd+'/%s_%g.ply'%(k,ts); write_ply(fn,X,F); files.append(fn)

    out=subprocess.run([T,'eval',clean,truth,y,*files],check=True,capture_output=True,text=True).stdout
    rms=[json.loads(l)['rms'] for l in out.splitlines()]
    for v,e in zip(variants,rms): res[v].append(e)
    print('ts %.4g '%ts+' '.join('%s %.5f'%(v,e) for v,e in zip(variants,rms)),flush=True)
    for fn in files: os.remove(fn)
print('BEST',name,noisy,' '.join('%s %.5f@%g'%(v,min(res[v]),grid[int(np.argmin(res[v]))]) for v in variants))
