#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# probe_eval.py OP ORDER STEPS NPROBES CASE... -- ENV...   CASE = mesh:noise:suffix:truth
import json, os, subprocess, sys, math
BIN=os.environ.get('BIN', '/tmp/s37/bb/bin') + '/fairing-denoise-tool'; M=os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
a=sys.argv[1:]; k=a.index('--'); op,order,steps,npr=a[:4]; cases=a[4:k]; envs=a[k+1:] or ['']
os.makedirs('/tmp/s37/oracles',exist_ok=True)
def sweep(noisy,clean,truth,ts,env,auto):
    e=dict(os.environ); e.update(env)
    args=[BIN,'sweep',noisy,clean,truth,op,order,steps,'1','--ts',','.join('%.6g'%t for t in ts)]+(['--auto'] if auto else [])
    return [json.loads(l) for l in subprocess.run(args,capture_output=True,text=True,env=e).stdout.splitlines()]
for c in cases:
    mesh,nz,suf,truth=c.split(':',3)
    noisy='%s/dn_%s_%s%s.ply'%(M,mesh,nz,suf); clean='%s/dn_%s_clean.ply'%(M,mesh)
    of='/tmp/s37/oracles/%s_%s%s_%s%s%s.json'%(mesh,nz,suf,op,order,steps)
    grid=json.load(open(of)) if os.path.exists(of) else {}
    line='%-14s %-12s'%(mesh,nz+suf)
    for es in envs:
        env=dict(kv.split('=') for kv in es.split(';') if kv)
        ts=[]
        for p in range(int(npr)):
            e2=dict(env); e2['FAIRING_PROBE_SEED']=str(p*1000)
            r=[j for j in sweep(noisy,clean,truth,[1],e2,True) if j['kind']=='auto'][0]
            ts.append((r['time_step'],r['rms']))
        # oracle on a grid of 20 per decade covering the choices and beyond
        lo=min(t for t,_ in ts)/6; hi=max(t for t,_ in ts)*6
        need=[10**(q/20) for q in range(int(math.floor(20*math.log10(lo))),int(math.ceil(20*math.log10(hi)))+1)]
        need=[t for t in need if '%.6g'%t not in grid]
        if need:
            for j in sweep(noisy,clean,truth,need,{},False):
                if j['kind']=='fixed': grid['%.6g'%j['time_step']]=j['rms']
            json.dump(grid,open(of,'w'))
        best=min(grid.values())
        rs=[r/best for _,r in ts]
        line+=' | %s: miss %d/%d gmean %.3f max %.3f [%s]'%(es or 'base',sum(x>1.1 for x in rs),len(rs),math.exp(sum(map(math.log,rs))/len(rs)),max(rs),' '.join('%.2f'%x for x in rs))
    print(line,flush=True)
