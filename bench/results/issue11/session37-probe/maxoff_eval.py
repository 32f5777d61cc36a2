#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# maxoff_eval.py SUFFIX MESHES(name:truth,...) NOISES OP ORDER STEPS ENVSPEC...
# per case and env setting: auto error and the best fixed step on a log grid refined around its best
import json, os, subprocess, sys, math
BIN=os.environ.get('BIN', '/tmp/s37/bb/bin') + '/fairing-denoise-tool'; M=os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
suf, meshes, noises, op, order, steps = sys.argv[1:7]
envs = sys.argv[7:]
def run(noisy, clean, truth, env, ts, auto):
    e = dict(os.environ); e.update(env)
    args=[BIN,'sweep',noisy,clean,truth,op,order,steps,'1','--ts',','.join('%.6g'%t for t in ts)]
    if auto: args.append('--auto')
    out=[json.loads(l) for l in subprocess.run(args,capture_output=True,text=True,env=e).stdout.splitlines()]
    return out
for mt in meshes.split(','):
    mesh, truth = mt.split(':',1)
    for nz in noises.split(','):
        noisy='%s/dn_%s_%s%s.ply'%(M,mesh,nz,suf); clean='%s/dn_%s_clean.ply'%(M,mesh)
        if not os.path.exists(noisy): continue
        res=[]
        for es in envs:
            env=dict(kv.split('=') for kv in es.split(';') if kv)
            o=run(noisy,clean,truth,env,[1],True)
            a=[j for j in o if j['kind']=='auto'][0]
            t0=a['time_step'] if a['time_step']>0 else 1
            grid=[t0*10**(k/5) for k in range(-5,8)]
            d={j['time_step']:j['rms'] for j in run(noisy,clean,truth,env,grid,False) if j['kind']=='fixed'}
            b=min(d,key=d.get)
            fine=[b*10**(k/20) for k in (-3,-2,-1,1,2,3)]
            d.update({j['time_step']:j['rms'] for j in run(noisy,clean,truth,env,fine,False) if j['kind']=='fixed'})
            b=min(d,key=d.get)
            res.append('%s auto %.5f@%.3g best %.5f@%.3g ratio %.3f'%(es or 'base',a['rms'],a['time_step'],d[b],b,a['rms']/d[b]))
        print('%-20s %-8s %s'%(mesh,nz+suf,' | '.join(res)),flush=True)
