# SPDX-License-Identifier: GPL-3.0-or-later
# The engine's automatic choice of every row of a committed study (or the rows matching FILTER, a
# Python expression in mesh, noise, op, order, steps) against that study's oracle, under the
# throwaway switches ENV ("A=1,B=2" or "-"). Usage: BIN STUDY.jsonl SUFFIX ENV OUT [FILTER]
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
binary, study, suffix, envs, out = sys.argv[1:6]
flt = sys.argv[6] if len(sys.argv) > 6 else 'True'
M = os.path.expanduser('~/.cache/filter_implicit_fairing/bench-meshes')
rows = [json.loads(l) for l in open(study)]
meshes = {m['name']: m for m in rows[0]['meta']['meshes']}
best = {}
for r in rows[1:]:
    if r.get('method') != 'ours' or r.get('kind') != 'fixed': continue
    k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
    best[k] = min(best.get(k, 9), r['rms'])
def keep(k):
    mesh, noise, op, order, steps = k
    return eval(flt)
cases = sorted(k for k in best if keep(k) and os.path.exists('%s/dn_%s_%s%s.ply' % (M, k[0], k[1], suffix)))
extra = dict(kv.split('=') for kv in envs.split(',')) if envs != '-' else {}
def run(k):
    mesh, noise, op, order, steps = k
    noisy = '%s/dn_%s_%s%s.ply' % (M, mesh, noise, suffix)
    env = dict(os.environ, OMP_NUM_THREADS='1', **extra)
    o = subprocess.run([binary, 'sweep', noisy, '%s/dn_%s_clean.ply' % (M, mesh), meshes[mesh]['truth'],
                        op, str(order), str(steps), '1', '--auto', '--ts', '1'], env=env,
                       capture_output=True, text=True).stdout
    a = [json.loads(l) for l in o.splitlines() if '"auto"' in l]
    if not a: return dict(case=k, error='no auto row')
    return dict(case=k, ts=a[0]['time_step'], rms=a[0]['rms'], oracle=best[k], ratio=a[0]['rms'] / best[k])
with ThreadPoolExecutor(2) as ex, open(out, 'w') as f:
    for r in ex.map(run, cases):
        f.write(json.dumps(r) + '\n'); f.flush()
