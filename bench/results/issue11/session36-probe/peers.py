#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""One click against the best peer on the scans, with the umbrella's automatic errors taken from
se_rule.py outputs (each rule scale) and the other two filters' one-click errors and the peers'
best from the set's committed extract (the engine's automatic rows, not the CLI's).
  peers.py EXTRACT.jsonl SE_OUT.txt [EXTRACT.jsonl SE_OUT.txt ...]"""
import collections, json, math, sys

DEFAULTS = {('umbrella', 2, 4), ('scale-dependent', 2, 2), ('curvature', 2, 4)}
PEERS = ('MeshLab', 'CGAL', 'OpenMesh')  # and valid: no error (as denoise_report.py)
ratios = collections.defaultdict(list)
for extract, se_out in zip(sys.argv[1::2], sys.argv[2::2]):
    rows = [json.loads(l) for l in open(extract)]
    kind = {m['name']: m['kind'] for m in rows[0]['meta']['meshes']}
    ours, peer = collections.defaultdict(dict), {}
    for r in rows[1:]:
        if 'noise' not in r or 'rms' not in r or r.get('kind') == 'cost':
            continue
        case = (r['mesh'], r['noise'])
        if r.get('method') == 'ours' and r.get('kind') == 'auto' and \
                (r.get('op'), r.get('order'), r.get('steps')) in DEFAULTS:
            ours[case][r['op']] = r['rms']
        elif r.get('method', '').startswith(PEERS) and not r.get('error'):
            peer[case] = min(peer.get(case, 9.0), r['rms'])
    for line in open(se_out):
        t = line.split()
        if len(t) < 5 or t[2] != 'oracle':
            continue
        case, oracle = (t[0], t[1]), float(t[3].split('@')[0])
        if kind[t[0]] != 'scan' or case not in peer:
            continue
        for item in t[4:]:
            k, rest = item.split(':')
            best_of_ours = dict(ours[case], umbrella=float(rest.split('@')[0]) * oracle)
            ratios[k].append(min(best_of_ours.values()) / peer[case])
for k, v in sorted(ratios.items()):
    gmean = math.exp(sum(map(math.log, v)) / len(v))
    print('scale %s: %d scan cases, one click / best peer: geometric mean %.4f, at most 1.000 in '
          '%d, at most 1.01 in %d, worst %.3f' % (k, len(v), gmean, sum(r <= 1.0 for r in v),
                                                 sum(r <= 1.01 for r in v), max(v)))
