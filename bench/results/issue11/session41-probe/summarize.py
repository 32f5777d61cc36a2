# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 41: freeze.jsonl against each study set's one-click rows and best peers.
# Usage: python3 summarize.py (reads freeze.jsonl next to it)
import json, math, collections, os
HERE = os.path.dirname(os.path.abspath(__file__))
R = os.path.join(HERE, "..", "..")
SETS = ["denoise", "denoise-seed2", "denoise-seed8", "denoise-noise", "heldout-s11", "heldout-s13", "heldout-s17"]
fz = {}
for l in open(os.path.join(HERE, 'freeze.jsonl')):
    r = json.loads(l); fz[(r['set'], r['mesh'], r['noise'])] = r
out = []
for d in SETS:
    f = R + "/denoise.jsonl" if d == "denoise" else R + "/" + d + "/denoise.jsonl"
    rows = [json.loads(l) for l in open(f)]
    kind = {m["name"]: m.get("kind", "scan") for m in rows[0]["meta"]["meshes"]}
    one = collections.defaultdict(dict); peer = {}
    for r in rows[1:]:
        k = (r.get('mesh'), r.get('noise'))
        if r.get('method') == 'ours CLI auto': one[k][r['op']] = r['rms']
        elif r.get('method', 'ours') != 'ours' and r.get('rms') is not None:
            if k not in peer or r['rms'] < peer[k][0]: peer[k] = (r['rms'], r['method'])
    for k, o in one.items():
        z = fz[(d,) + k]
        out.append(dict(set=d, mesh=k[0], noise=k[1], kind=kind.get(k[0]), umb=o.get('umbrella'),
                        sd=o.get('scale-dependent'), cv=o.get('curvature'), cv_now=z['default'],
                        fz=z['freeze'], peer=peer.get(k, (None,))[0], peer_m=peer.get(k, (0, ''))[1]))
def g(xs): return math.exp(sum(map(math.log, xs)) / len(xs))
scans = [o for o in out if o['kind'] == 'scan' and o['peer']]
print("cases", len(out), "scans", len(scans))
print("check cv vs cv_now max rel diff", max(abs(o['cv'] / o['cv_now'] - 1) for o in out if o['cv']))
b0 = [min(o['umb'], o['sd'], o['cv']) / o['peer'] for o in scans]
b1 = [min(o['umb'], o['sd'], o['fz']) / o['peer'] for o in scans]
print("best/peer gmean now %.4f freeze %.4f; <=1: %d -> %d; <=1.01: %d -> %d" % (
    g(b0), g(b1), sum(x <= 1 for x in b0), sum(x <= 1 for x in b1), sum(x <= 1.01 for x in b0), sum(x <= 1.01 for x in b1)))
print("cases where frozen curvature becomes best of ours:")
for o, x0, x1 in zip(scans, b0, b1):
    if x1 < x0 - 1e-9:
        print("  %-14s %-18s %-8s umb %.4f sd %.4f cv %.4f fz %.4f peer %.4f (%s)  %.3f -> %.3f" % (
            o['set'], o['mesh'], o['noise'], o['umb'], o['sd'], o['cv'], o['fz'], o['peer'], o['peer_m'], x0, x1))
print("fz/cv on scans gmean %.3f range %.3f-%.3f" % (g([o['fz']/o['cv_now'] for o in scans]),
      min(o['fz']/o['cv_now'] for o in scans), max(o['fz']/o['cv_now'] for o in scans)))
kn = [o for o in out if o['kind'] != 'scan']
print("fz/cv on known gmean %.3f range %.3f-%.3f" % (g([o['fz']/o['cv_now'] for o in kn]),
      min(o['fz']/o['cv_now'] for o in kn), max(o['fz']/o['cv_now'] for o in kn)))
worse = [o for o in scans if o['fz'] > o['cv_now'] * 1.0]
for o in worse: print("  scan worse frozen: %s %s %s %.4f -> %.4f" % (o['set'], o['mesh'], o['noise'], o['cv_now'], o['fz']))
for name, sel in (("spheres", "sphere"), ("torus", "torus"), ("plane", "plane")):
    r = [o['fz'] / o['cv_now'] for o in out if sel in o['mesh']]
    print("frozen / recomputed, %s: %d cases, gmean %.3f, %.3f-%.3f" % (name, len(r), g(r), min(r), max(r)))
