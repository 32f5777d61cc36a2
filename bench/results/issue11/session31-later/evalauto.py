# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Throwaway: auto / oracle (oracle from bench/results/denoise.jsonl) for the one-click configs.
import json, subprocess, sys, os, math, collections
from concurrent.futures import ThreadPoolExecutor
M = '/root/.cache/filter_implicit_fairing/bench-meshes/'
DT = os.environ.get('DT', '/tmp/bX/bin/fairing-denoise-tool')
TRUTH = {'sphere2_3k': 'sphere', 'sphere2_13k': 'sphere', 'sphere2_51k': 'sphere', 'torus_10k': 'torus:1:0.4'}
R = [json.loads(l) for l in open(os.environ.get('ORACLE', '/work/main/bench/results/denoise.jsonl'))][1:]
SUF = os.environ.get('SUF', '')
orc = {}
for r in R:
    if r.get('method') == 'ours' and r.get('kind') == 'fixed' and r.get('rms') is not None and not r.get('error'):
        k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
        orc[k] = min(orc.get(k, 9e9), r['rms'])
meshes = os.environ.get('MESHES', 'sphere2_3k sphere2_13k torus_10k elephant_6k fandisk_13k camel_20k dragon_20k elephant_loop1_22k').split()
noises = os.environ.get('NOISES', 'n0.1 n0.25 n0.5 iso0.25').split()
configs = [tuple(c.split(':')) for c in os.environ.get('CONFIGS', 'umbrella:2:4 scale-dependent:2:2 curvature:2:4').split()]
jobs = [(m, n, op, int(o), int(s)) for m in meshes for n in noises for (op, o, s) in configs]
def one(k):
    m, n, op, o, s = k
    out = subprocess.run([DT, 'sweep', M + 'dn_%s_%s%s.ply' % (m, n, SUF), M + 'dn_%s_clean.ply' % m, TRUTH.get(m, 'mesh'), op, str(o), str(s), '1', '--auto', '--ts', '1'],
                         capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS='1')).stdout
    a = [json.loads(l) for l in out.splitlines() if '"auto"' in l][0]
    return k, a['rms'], a['time_step']
res = list(ThreadPoolExecutor(2).map(one, jobs))
tag = sys.argv[1] if len(sys.argv) > 1 else 'run'
with open('/tmp/eval_%s.jsonl' % tag, 'w') as f:
    for k, rms, ts in res: f.write(json.dumps(dict(key=k, rms=rms, ts=ts, q=rms / orc[k])) + '\n')
by = collections.defaultdict(list)
for k, rms, ts in res: by[k[2]].append((rms / orc[k], k))
for op, v in by.items():
    q = [x for x, _ in v]
    print('%-16s n %d gmean %.4f worst %.3f %s  >1.10: %d' % (op, len(q), math.exp(sum(map(math.log, q)) / len(q)), max(q), max(v)[1][:2], sum(x > 1.10 for x in q)))
