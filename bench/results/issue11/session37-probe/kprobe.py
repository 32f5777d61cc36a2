#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# kprobe.py MESH NOISE SUFFIX TRUTH OP ORDER STEPS K OFFSETS(comma) [BEST]
import json, os, subprocess, sys
BIN=os.environ.get('BIN', '/tmp/s37/bb/bin') + '/fairing-denoise-tool'; M=os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
mesh,noise,suf,truth,op,order,steps,K,offs=sys.argv[1:10]
best=float(sys.argv[10]) if len(sys.argv)>10 else None
noisy='%s/dn_%s_%s%s.ply'%(M,mesh,noise,suf); clean='%s/dn_%s_clean.ply'%(M,mesh)
out=[]
for o in offs.split(','):
    env=dict(os.environ, FAIRING_PROBES=K, FAIRING_PROBE_SEED=str(int(o)*1000))
    p=subprocess.run([BIN,'sweep',noisy,clean,truth,op,order,steps,'1','--auto','--ts','1'],capture_output=True,text=True,env=env)
    a=[json.loads(l) for l in p.stdout.splitlines() if '"auto"' in l][0]
    out.append((a['rms'],a['time_step'],a['strength_seconds'],a['seconds']))
print('%s %s%s K=%s: '%(mesh,noise,suf,K)+' '.join('%.3f@%.3g'%(r/best if best else r,t) for r,t,_,_ in out), ' est %.2fs total %.2fs'%(sum(x[2] for x in out)/len(out),sum(x[3] for x in out)/len(out)),flush=True)
