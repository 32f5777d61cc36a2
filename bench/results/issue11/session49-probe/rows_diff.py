#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 49: each set's automatic rows at git revision REV against the working
# tree's, each over its oracle (the best fixed step of the same filter, order and steps, as
# session43-probe/sets_sum.py takes it): the rows whose choice moved, the geometric mean of the
# new error over the old on them, the rows that crossed 10 % either way, and the largest moves.
# Usage (repository root): python3 rows_diff.py REV [SET ...]
import json, math, os, subprocess, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session43-probe"))
from sets_sum import SETS, oracles, path  # noqa: E402


def autos(lines):
    rows = [json.loads(l) for l in lines if l.strip()][1:]
    best = oracles(rows)
    auto = {(r["mesh"], r["noise"], r["op"], r["order"], r["steps"]): r for r in rows
            if r.get("method") == "ours" and r.get("kind") == "auto" and r.get("rms") is not None}
    return {k: (r["rms"] / best[k], r["rms"], r.get("time_step"), r.get("strength_iterations"))
            for k, r in auto.items() if k in best}


rev = sys.argv[1]
total = [0, 0]
for d in sys.argv[2:] or SETS:
    old = autos(subprocess.run(["git", "show", "%s:%s" % (rev, path(d))], capture_output=True,
                               text=True, check=True).stdout.splitlines())
    new = autos(open(path(d)).read().splitlines())
    common = [k for k in new if k in old]
    moved = [k for k in common if old[k][2] != new[k][2]]
    logs = [math.log(new[k][1] / old[k][1]) for k in moved]
    its = [(old[k][3], new[k][3]) for k in common if old[k][3] and new[k][3]]
    crossed = [k for k in common if (old[k][0] <= 1.1) != (new[k][0] <= 1.1)]
    print("== %s: %d rows, %d moved, new / old error on them gmean %.4f; Lanczos steps %d -> %d"
          % (d, len(common), len(moved), math.exp(sum(logs) / max(1, len(logs))),
             sum(a for a, _ in its), sum(b for _, b in its)))
    total[0] += sum(a for a, _ in its)
    total[1] += sum(b for _, b in its)
    for k in crossed:
        print("   crossed 10 %%: %s: %.3f -> %.3f (time step %.4g -> %.4g)"
              % (" ".join(map(str, k)), old[k][0], new[k][0], old[k][2], new[k][2]))
    by_change = sorted(moved, key=lambda k: new[k][1] / old[k][1])
    for k in by_change[:1] + by_change[-1:]:
        print("   %s: %.3f -> %.3f of the oracle" % (" ".join(map(str, k)), old[k][0], new[k][0]))
print("all sets: Lanczos steps %d -> %d (%+.1f %%)" % (total[0], total[1],
                                                      100 * (total[1] / max(1, total[0]) - 1)))
