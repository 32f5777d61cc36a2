#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
import sys, os, json, subprocess, tempfile, numpy as np, scipy.sparse as sp, scipy.sparse.linalg as sla
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session25-restoration"))
from restoration_floor import read_ply, write_ply, area_normals
DT = os.environ["BIN"] + "/fairing-denoise-tool"; CLI = os.environ["CLI"]
noisy, clean = sys.argv[1:3]; steps = 4
tmp = tempfile.mkdtemp(); oc = os.path.join(tmp, "oc.ply")
info = json.loads(subprocess.run([CLI, "--operator", "umbrella", "--json", noisy, oc], capture_output=True, text=True).stdout.strip().split("\n")[-1])
ts = info["time_step"]
x, f = read_ply(noisy); n = len(x); c_out, _ = read_ply(oc)
e = np.sort(np.r_[f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1)
u, c = np.unique(e, axis=0, return_counts=True)
bd = np.zeros(n, bool); bd[u[c == 1].ravel()] = True
A = sp.coo_matrix((np.ones(2 * len(u)), (np.r_[u[:, 0], u[:, 1]], np.r_[u[:, 1], u[:, 0]])), (n, n)).tocsr()
W = sp.diags(1 / np.asarray(A.sum(1)).ravel()) @ A
Lfree = W - sp.identity(n); Lfix = sp.diags((~bd).astype(float)) @ Lfree
I = sp.identity(n, format="csr")
def run(L, ts, x0):
    S = sla.splu((I + ts * (L @ L)).tocsc()); y = x0.copy()
    for _ in range(steps): y = S.solve(y)
    return y
files = [oc]; names = ["one-click"]
def add(name, y):
    p = os.path.join(tmp, "%d.ply" % len(files)); write_ply(p, y, f); files.append(p); names.append(name)
yfree = run(Lfree, ts, x); nrm, _ = area_normals(yfree, f)
for base_name, base in (("noisy", x), ("curve", c_out)):
    xb = x.copy(); d = np.einsum("ij,ij->i", nrm, yfree - base); xb[bd] = base[bd] + d[bd, None] * nrm[bd]
    add("normal-free on " + base_name, run(Lfix, ts, xb))
xb = x.copy(); xb[bd] = c_out[bd]; add("proto curve", run(Lfix, ts, xb))
if os.environ.get("SAVE"):
    import shutil
    for i, p in enumerate(files): shutil.copy(p, "/tmp/s32/save_%d.ply" % i)
out = subprocess.run([DT, "eval", clean, "mesh", noisy] + files, capture_output=True, text=True).stdout.split("\n")
print(os.path.basename(noisy), "ts %.3g" % ts, " | ".join("%s %.4f" % (nm, json.loads(l)["rms"]) for nm, l in zip(names, out)))
