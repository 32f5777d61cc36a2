#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# steps_eval.py EXTRACT SUFFIX STEPS(comma) [ENV] : umbrella L2 auto error per steps on the scans,
# one click (with the extract's other two defaults) over the best peer
import collections, json, os, subprocess, sys
BIN=os.environ.get('BIN', '/tmp/s37/bb/bin') + '/fairing-denoise-tool'; M=os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
extract, suf, stepss = sys.argv[1], sys.argv[2], sys.argv[3].split(',')
env = dict(os.environ); env.update(dict(kv.split('=') for kv in (sys.argv[4].split(';') if len(sys.argv) > 4 else []) if kv))
rows=[json.loads(l) for l in open(extract)]
meta={m['name']:m for m in rows[0]['meta']['meshes']}
PEERS=('MeshLab','CGAL','OpenMesh')
ours=collections.defaultdict(dict); peer={}
for r in rows[1:]:
    if 'noise' not in r or 'rms' not in r or r.get('kind')=='cost': continue
    c=(r['mesh'],r['noise'])
    if r.get('method')=='ours' and r.get('kind')=='auto' and (r.get('op'),r.get('order'),r.get('steps')) in {('umbrella',2,4),('scale-dependent',2,2),('curvature',2,4)}:
        ours[c][r['op']]=r['rms']
    elif r.get('method','').startswith(PEERS) and not r.get('error'):
        peer[c]=min(peer.get(c,9.0),r['rms'])
for (m,nz) in sorted(peer):
    if meta[m]['kind']!='scan': continue
    noisy='%s/dn_%s_%s%s.ply'%(M,m,nz,suf); clean='%s/dn_%s_clean.ply'%(M,m)
    if not os.path.exists(noisy): continue
    out=[]
    for s in stepss:
        o=[json.loads(l) for l in subprocess.run([BIN,'sweep',noisy,clean,meta[m]['truth'],'umbrella','2',s,'1','--auto','--ts','1'],capture_output=True,text=True,env=env).stdout.splitlines()]
        a=[j for j in o if j['kind']=='auto'][0]
        others=[v for k,v in ours[(m,nz)].items() if k!='umbrella']
        out.append('x%s %.5f %.4f'%(s,a['rms'],min([a['rms']]+others)/peer[(m,nz)]))
    print('%-20s %-8s ext_umb %.5f peer %.5f | %s'%(m,nz,ours[(m,nz)].get('umbrella',0),peer[(m,nz)],' | '.join(out)),flush=True)
