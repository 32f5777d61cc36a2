#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# per case: K probe seeds -> risk curves; choices per seed (minimizer, 1-SE rule), and of the mean curve
import json, os, subprocess, sys, math
import numpy as np
BIN=os.environ.get('BIN', '/tmp/s37/bb/bin') + '/fairing-denoise-tool'; M=os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
def curves(noisy, clean, truth, op, order, steps, seed):
    env=dict(os.environ, FAIRING_DUMP_RISK='1', FAIRING_PROBE_SEED=str(seed))
    p=subprocess.run([BIN,'sweep',noisy,clean,truth,op,str(order),str(steps),'1','--auto','--ts','1'],capture_output=True,text=True,env=env)
    rows=[l.split()[1:] for l in p.stderr.splitlines() if l.startswith('RISK')]
    a=[json.loads(l) for l in p.stdout.splitlines() if '"auto"' in l][0]
    g=np.array([float(r[0]) for r in rows]); rss=np.array([float(r[1]) for r in rows]); tr=np.array([float(r[2]) for r in rows])
    s=float(rows[0][3]); return g,rss,tr,s,a
def choose(g,rss,tr,s,rule):
    risk=rss+2*s*s*tr; b=int(np.argmin(risk)); k=b
    if rule:
        for j in range(b+1,len(g)):
            if g[j] > 2.5*g[b]*1.0001: break
            if risk[j]<=risk[b]+s*s*math.sqrt(2*abs(tr[b]-tr[j])): k=j
    return g[k]
def errors(noisy,clean,truth,op,order,steps,ts):
    p=subprocess.run([BIN,'sweep',noisy,clean,truth,op,str(order),str(steps),'1','--ts',','.join('%.6g'%t for t in ts)],capture_output=True,text=True)
    d={}
    for l in p.stdout.splitlines():
        j=json.loads(l)
        if j['kind']=='fixed': d[j['time_step']]=j['rms']
    return d
mesh,noise,suffix,truth,op,order,steps,K=sys.argv[1:9]; K=int(K)
noisy='%s/dn_%s_%s%s.ply'%(M,mesh,noise,suffix); clean='%s/dn_%s_clean.ply'%(M,mesh)
C=[curves(noisy,clean,truth,op,int(order),int(steps),k) for k in range(K)]
n=min(len(c[0]) for c in C); g=C[0][0][:n]
mean_rss=np.mean([c[1][:n] for c in C],0); mean_tr=np.mean([c[2][:n] for c in C],0); s=C[0][3]
picks={'eng0':[c[4]['time_step'] for c in C]}
picks['min']=[choose(c[0][:n],c[1][:n],c[2][:n],s,False) for c in C]
picks['se']=[choose(c[0][:n],c[1][:n],c[2][:n],s,True) for c in C]
avg={'min':choose(g,mean_rss,mean_tr,s,False),'se':choose(g,mean_rss,mean_tr,s,True)}
allts=sorted(set(picks['min']+picks['se']+list(avg.values())))
lo,hi=min(allts)/5,max(allts)*5
grid=[10**(k/10) for k in range(int(math.floor(10*math.log10(lo))),int(math.ceil(10*math.log10(hi)))+1)]
E=errors(noisy,clean,truth,op,order,steps,grid+picks['eng0'])
ts=np.array(sorted(E)); er=np.array([E[t] for t in ts]); best=er.min()
def err(t): return math.exp(np.interp(math.log(t),np.log(ts),np.log(er)))
res={'eng0':C[0][4]['rms']/best}
for r in ('min','se'):
    res[r+'1']=err(picks[r][0])/best
    for k in (4,8):
        mr=np.mean([c[1][:n] for c in C[:k]],0); mt=np.mean([c[2][:n] for c in C[:k]],0)
        res[r+str(k)]=err(choose(g,mr,mt,s,r=='se'))/best
res['engall']=[round(c[4]['rms']/best,3) for c in C]
print(json.dumps(dict(mesh=mesh,noise=noise+suffix,op=op,order=order,steps=steps,best=best,**res)),flush=True)
