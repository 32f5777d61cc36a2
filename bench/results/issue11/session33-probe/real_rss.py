#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The measured RSS_n / N (mesh units^2) of fair()'s restored result along the robust normals, at
given time steps: what the strength estimate's modelled curve should follow. The operator is env
OP (default umbrella, session 33), further CLI options env EXTRA (e.g. "--steps 1", session 34).
  CLI=.../implicit-fairing [OP=...] [EXTRA=...] real_rss.py NOISY T1,T2,..."""
import os, subprocess, sys, tempfile
import numpy as np
from meshio33 import read_any, adjacency, robust_normals

y, f = read_any(sys.argv[1])
normals = robust_normals(y, f, adjacency(y, f))
out = os.path.join(tempfile.mkdtemp(), "out.ply")
for ts in map(float, sys.argv[2].split(",")):
    subprocess.run([os.environ["CLI"], "--operator", os.environ.get("OP", "umbrella"),
                    "--time-step", repr(ts)] + os.environ.get("EXTRA", "").split()
                   + ["-q", sys.argv[1], out], check=True)
    x, _ = read_any(out)
    print("ts %g RSS_n / N %.5f" % (ts, np.mean(np.einsum("ij,ij->i", normals, y - x) ** 2)))
