# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# What session 26's measurement aids share: the committed study's rows of ours and the mesh cache.
import collections
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(os.environ.get('FAIRING_CACHE', os.path.expanduser('~/.cache/filter_implicit_fairing')),
                      'bench-meshes')


def best_rows(kind='fixed'):
    """(mesh, noise, op, order, steps) -> (rms, time_step) of the study's lowest-error row of ours
    of that kind (fixed: the oracle; auto: the automatic choice)."""
    best = collections.defaultdict(lambda: (float('inf'), 0))
    with open(os.path.join(HERE, '../../denoise.jsonl')) as f:
        for line in f:
            r = json.loads(line)
            if r.get('method') == 'ours' and r.get('kind') == kind and 'op' in r:
                k = (r['mesh'], r['noise'], r['op'], r['order'], r['steps'])
                best[k] = min(best[k], (r['rms'], r['time_step']))
    return best
