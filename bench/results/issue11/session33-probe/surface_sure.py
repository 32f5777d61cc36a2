#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""SURE of the umbrella L^2 x STEPS along the robust normals (the engine's) against SURE on the
distance of the noisy vertices to the filtered surface, and the true error, for given time steps
(tr H from the eigenvalues of M^-1/2 K M^-1/2: small meshes only).
  CLI=.../implicit-fairing BIN=.../bench/bin surface_sure.py NOISY CLEAN SIGMA_MESH_UNITS T1,T2,... [STEPS]"""
import json, os, subprocess, sys, tempfile
import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from meshio33 import read_any, mean_edge, adjacency, robust_normals

CLI, DT = os.environ["CLI"], os.path.join(os.environ["BIN"], "fairing-denoise-tool")
noisy, clean, sig = sys.argv[1], sys.argv[2], float(sys.argv[3])
steps = int(sys.argv[5]) if len(sys.argv) > 5 else 4
y, f = read_any(noisy)
n = len(y)
A = adjacency(y, f)
m = np.asarray(A.sum(1)).ravel()
g = sl.eigvalsh((sp.diags(m ** -0.5) @ (sp.diags(m) - A) @ sp.diags(m ** -0.5)).toarray())
normals = robust_normals(y, f, A)
out = os.path.join(tempfile.mkdtemp(), "out.ply")


def rms(args):
    r = subprocess.run([DT, "eval"] + args, capture_output=True, text=True, check=True).stdout
    return json.loads(r.splitlines()[-1])["rms"]


for ts in map(float, sys.argv[4].split(",")):
    subprocess.run([CLI, "--operator", "umbrella", "--steps", str(steps), "--time-step", repr(ts), "-q",
                    noisy, out], check=True)
    x, _ = read_any(out)
    tr = np.sum((1 + ts * g ** 2) ** -steps)
    rss_n = np.sum(np.einsum("ij,ij->i", normals, y - x) ** 2)
    rss_s = (rms([out, "mesh", noisy, noisy]) * mean_edge(x, f)) ** 2 * n
    print("ts %7.3g tr H / N %.4f  SURE_n %.5g  SURE_surface %.5g  true error %.5f"
          % (ts, tr / n, (rss_n + 2 * sig ** 2 * tr - n * sig ** 2) / n,
             (rss_s + 2 * sig ** 2 * tr - n * sig ** 2) / n, rms([clean, "mesh", noisy, out])))
