#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""auto-gap.md section 25: Taubin's anti-shrinking term made implicit, (I + a L^2 - c L)^-m with
the unnormalized umbrella L and c set (secant) so that the volume is kept exactly, against the same
filter (c = 0) restored by the uniform normal offset and unrestored (measurement aid, not part of
any build; its a is not the engine's time step).

    implicit_taubin.py NOISY CLEAN STEPS A1,A2,... BIN

Needs numpy and scipy (Debian: python3-scipy)."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from restoration_floor import read_ply, restore, volume, write_ply  # noqa: E402


def main():
    noisy, clean, steps, values, bin_dir = sys.argv[1:6]
    m = int(steps)
    x, f = read_ply(noisy)
    n, target = len(x), volume(x, f)
    e = np.unique(np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1), axis=0)
    adjacency = sp.csr_matrix((np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])),
                              shape=(n, n))
    L = (sp.diags(1 / np.asarray(adjacency.sum(1)).ravel()) @ adjacency - sp.identity(n)).tocsc()
    L2, I = (L @ L).tocsc(), sp.identity(n, format="csc")

    def filtered(a, c):
        solve = sla.splu((I + (a / m) * L2 - (c / m) * L).tocsc()).solve
        y = x.copy()
        for _ in range(m):
            y = solve(y)
        return y

    tmp = tempfile.mkdtemp()
    for a in (float(v) for v in values.split(",")):
        plain = filtered(a, 0.0)
        c0, v0, c1 = 0.0, volume(plain, f) - target, 1e-3 * a ** 0.5
        for _ in range(30):  # secant on c
            kept = filtered(a, c1)
            v1 = volume(kept, f) - target
            if abs(v1) < 1e-9 * abs(target):
                break
            c0, v0, c1 = c1, v1, c1 - v1 * (c1 - c0) / (v1 - v0)
        files = [os.path.join(tmp, name + ".ply") for name in ("uniform", "unrestored", "implicit_taubin")]
        for path, y in zip(files, (restore(plain, f, np.ones(n), target), plain, kept)):
            write_ply(path, y, f)
        out = subprocess.run([os.path.join(bin_dir, "fairing-denoise-tool"), "eval", clean, "mesh", noisy] + files,
                             check=True, capture_output=True, text=True).stdout
        errors = [json.loads(l)["rms"] for l in out.splitlines() if l]
        print(json.dumps(dict(a=a, c=c1, uniform=errors[0], unrestored=errors[1], implicit_taubin=errors[2])))


if __name__ == "__main__":
    main()
