# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 41 (not kept): the spread of the vertex areas' change over the curvature
# flow's first recomputed step, a candidate signal for freezing; needs the CLI built with
# throwaway.patch (EXP_STAT). Usage: I=... python3 masses.py > masses.jsonl
import json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
exec(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'freeze.py')).read().split('variants =')[0].replace('EXTRA = sys.argv[1:]', 'EXTRA=[]'))
def one(c):
    d, seed, mesh, noise, truth = c
    p = subprocess.run([CLI, noisy_of(seed, mesh, noise), TMP + "/st_%s_%s_%d.ply" % (mesh, noise, seed),
                        "--operator", "curvature", "--threads", "1", "-q"], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1", EXP_STAT="1"))
    os.remove(TMP + "/st_%s_%s_%d.ply" % (mesh, noise, seed))
    st = [l for l in p.stderr.splitlines() if l.startswith("STAT")]
    print(json.dumps(dict(set=d, mesh=mesh, noise=noise, stat=st[0] if st else None)), flush=True)
with ThreadPoolExecutor(2) as ex: list(ex.map(one, cases))
