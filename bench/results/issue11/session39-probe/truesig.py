#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: measurement aid, not part of any build (see README.md here).
import json,sys,os,subprocess
from concurrent.futures import ThreadPoolExecutor
sys.path.insert(0,os.path.dirname(os.path.abspath(__file__))); from plyio import MESHES as M, SETS
TOOL=os.environ['TOOL']  # a fairing-denoise-tool built with throwaway.patch
OP,ORD,ST=sys.argv[1],int(sys.argv[2]),int(sys.argv[3]); kinds=sys.argv[4].split(',')
h_cache={}
def mean_edge(p):
    if p not in h_cache: h_cache[p]=json.loads(subprocess.run([TOOL,'info',p],capture_output=True,text=True).stdout)['mean_edge']
    return h_cache[p]
jobs=[]
for sname,(f,suf) in SETS.items():
    rows=[json.loads(l) for l in open(f)]
    meta=rows[0]['meta']; mk={m['name']:m for m in meta['meshes']}
    cases={}
    for r in rows:
        if r.get('method')=='ours' and r.get('op')==OP and r.get('order')==ORD and r.get('steps')==ST and 'noise' in r:
            cases.setdefault((r['mesh'],r['noise']),[]).append(r)
    for (m,n),rs in sorted(cases.items()):
        if mk[m]['kind'] not in kinds or n=='clean': continue
        fx=[r for r in rs if r['kind']=='fixed']; au=[r for r in rs if r['kind']=='auto']
        if not fx or not au: continue
        best=min(fx,key=lambda r:r['rms'])
        if sname=='denoise-noise':
            lv=n[1:] if n[0]=='n' else n[3:]; kind='normal' if n[0]=='n' else 'iso'
            noisy=M+'/dn_%s_%s_%s%s%s.ply'%(m,n,lv,kind,suf)
        else: noisy=M+'/dn_%s_%s%s.ply'%(m,n,suf)
        if not os.path.exists(noisy): print('missing',noisy,file=sys.stderr); continue
        level=float(n.lstrip('niso'))
        jobs.append((sname,m,n,noisy,M+'/dn_%s_clean.ply'%m,mk[m]['truth'],level,best,au[0]))
def run(j):
    sname,m,n,noisy,clean,truth,level,best,au=j
    sig=level*mean_edge(clean)
    env=dict(os.environ,OMP_NUM_THREADS='1',FAIRING_SIGMA=repr(sig))
    out=subprocess.run([TOOL,'sweep',noisy,clean,truth,OP,str(ORD),str(ST),'1','--auto','--ts',repr(best['time_step'])],capture_output=True,text=True,env=env).stdout
    pts=[json.loads(l) for l in out.splitlines() if l.startswith('{')]
    a=[p for p in pts if p['kind']=='auto'][0]
    return dict(set=sname,mesh=m,noise=n,oracle=best['rms'],oracle_ts=best['time_step'],est=au['rms'],est_ts=au['time_step'],est_sig=au['noise_level_edges'],true=a['rms'],true_ts=a['time_step'])
with ThreadPoolExecutor(2) as ex:
    for r in ex.map(run,jobs):
        print(json.dumps(r),flush=True)
