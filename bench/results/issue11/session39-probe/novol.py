#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 39: measurement aid, not part of any build (see README.md here).
import json,sys,os,subprocess,math,tempfile
from concurrent.futures import ThreadPoolExecutor
sys.path.insert(0,os.path.dirname(os.path.abspath(__file__))); from plyio import CACHE as C, MESHES as M, SETS
I=C+'/bench-build/main/bin/implicit-fairing'; TOOL=C+'/bench-build/bench/bin/fairing-denoise-tool'
jobs=[]
for sname,(f,suf) in SETS.items():
    if sname=='denoise-noise': continue  # the 108 scan cases: the study's draws and held out
    rows=[json.loads(l) for l in open(f)]
    mk={m['name']:m for m in rows[0]['meta']['meshes']}
    cases={}
    for r in rows:
        if 'mesh' in r and 'noise' in r and 'rms' in r: cases.setdefault((r['mesh'],r['noise']),[]).append(r)
    for (m,n),rs in sorted(cases.items()):
        if mk[m]['kind']!='scan' or n=='clean': continue
        peers=[r for r in rs if r.get('method') not in ('ours','ours CLI auto')]
        cli=[r for r in rs if r.get('method')=='ours CLI auto']
        if not peers or not cli: continue
        bp=min(peers,key=lambda r:r['rms']); bc=min(cli,key=lambda r:r['rms'])
        jobs.append((sname,m,n,M+'/dn_%s_%s%s.ply'%(m,n,suf),M+'/dn_%s_clean.ply'%m,mk[m]['closed'],bp,bc))
def run(j):
    sname,m,n,noisy,clean,closed,bp,bc=j
    out=os.path.join(tempfile.gettempdir(),'nv_%s_%s_%s.ply'%(sname,m,n)); res={}
    for op in ('umbrella','scale-dependent','curvature'):
        p=subprocess.run([I,'--operator',op,'--no-volume',noisy,out],capture_output=True,env=dict(os.environ,OMP_NUM_THREADS='1'))
        if p.returncode: res[op]=(float('inf'),None); continue
        e=json.loads(subprocess.run([TOOL,'eval',clean,'mesh',noisy,out],capture_output=True,text=True).stdout)
        res[op]=(e['rms'],e['volume_change'])
    os.remove(out)
    best=min(res,key=lambda k:res[k][0])
    return dict(set=sname,mesh=m,noise=n,closed=closed,peer=bp['rms'],peer_method=bp['method'],click=bc['rms'],click_op=bc.get('op'),
                novol=res[best][0],novol_op=best,novol_vol=res[best][1],novol_all=res)
with ThreadPoolExecutor(2) as ex:
    for r in ex.map(run,jobs): print(json.dumps(r),flush=True)
