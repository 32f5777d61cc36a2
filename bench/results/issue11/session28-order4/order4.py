#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 28: the paper's higher powers of the Laplacian (section 2.5, Figure 3a) as
filter shapes, against the umbrella L^2 x4 default: the oracle (best of a fine log sweep) of
(I + a L^(2p))^-m, restored to the input's volume by the engine's uniform normal offset, and
unrestored (measurement aid, not part of any build; a is not the engine's time step).

    order4.py BIN NOISY CLEAN [NOISY CLEAN ...]

Prints one JSON line per case and filter. Needs numpy and scipy (Debian: python3-scipy)."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply, restore, volume, write_ply  # noqa: E402

FILTERS = {"L2x4": (1, 4), "L3x1": (1.5, 1), "L3x2": (1.5, 2), "L3x4": (1.5, 4), "L4x1": (2, 1)}


def umbrella(x, f):
    n = len(x)
    e = np.unique(np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1), axis=0)
    adjacency = sp.csr_matrix((np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])),
                              shape=(n, n))
    return (sp.diags(1 / np.asarray(adjacency.sum(1)).ravel()) @ adjacency - sp.identity(n)).tocsc()


def main():
    bin_dir, pairs = sys.argv[1], sys.argv[2:]
    tool = os.path.join(bin_dir, "fairing-denoise-tool")
    tmp = tempfile.mkdtemp()
    for noisy, clean in zip(pairs[::2], pairs[1::2]):
        x, f = read_ply(noisy)
        n, target = len(x), volume(x, f)
        L = umbrella(x, f)
        I = sp.identity(n, format="csc")
        K2 = (L @ L).tocsc()
        powers = {1: K2, 2: (K2 @ K2).tocsc()}
        # order 3 (L^3 is indefinite as -L^3 >= 0): (I - a L^3)
        powers[1.5] = (-(K2 @ L)).tocsc()

        def evaluate(p, m, values):
            files = []
            for k, a in enumerate(values):
                solve = sla.splu((I + a * powers[p]).tocsc()).solve
                y = x.copy()
                for _ in range(m):
                    y = solve(y)
                write_ply(os.path.join(tmp, "u%d.ply" % k), y, f)
                write_ply(os.path.join(tmp, "r%d.ply" % k), restore(y, f, np.ones(n), target), f)
                files += [os.path.join(tmp, "u%d.ply" % k), os.path.join(tmp, "r%d.ply" % k)]
            out = subprocess.run([tool, "eval", clean, "mesh", noisy] + files, check=True,
                                 capture_output=True, text=True).stdout
            rms = [json.loads(l)["rms"] for l in out.splitlines() if l]
            return rms[0::2], rms[1::2]

        for name, (p, m) in FILTERS.items():
            coarse = [10.0 ** (k / 2) for k in range(-6, 9)]  # 1e-3 .. 1e4
            _, r = evaluate(p, m, coarse)
            best = coarse[int(np.argmin(r))]
            fine = [best * 2.0 ** (k / 6) for k in range(-10, 11)]
            u, r = evaluate(p, m, fine)
            i, j = int(np.argmin(r)), int(np.argmin(u))
            print(json.dumps(dict(case=os.path.basename(noisy), filter=name, restored=r[i], a=fine[i],
                                  unrestored=u[j], a_unrestored=fine[j],
                                  edge_of_grid=i in (0, len(fine) - 1))), flush=True)


if __name__ == "__main__":
    main()
