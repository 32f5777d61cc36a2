# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Throwaway: the Monte-Carlo divergence of the real pipeline (CLI) with the engine's probe signs.
import numpy as np, subprocess, sys
import os
# read_ply, area_normals, robust_normals (session 30's script, up to its loop code).
exec(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'session30-loops',
                       'loopsure.py')).read().split("def loops")[0])
M = '/root/.cache/filter_implicit_fairing/bench-meshes/'
CLI = __import__('os').environ.get('CLI', '/tmp/bC/bin/implicit-fairing')
import os
EXTRA = os.environ.get('EXTRA', '').split()
def splitmix64(v):
    m = (1 << 64) - 1
    v = (v + 0x9e3779b97f4a7c15) & m
    v = ((v ^ (v >> 30)) * 0xbf58476d1ce4e5b9) & m
    v = ((v ^ (v >> 27)) * 0x94d049bb133111eb) & m
    return v ^ (v >> 31)
def write_ply(p, V, F):
    with open(p, 'wb') as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(V), len(F))).encode())
        f.write(V.astype('<f8').tobytes())
        rec = np.zeros(len(F), dtype=np.dtype([('n', 'u1'), ('v', '<i4', 3)])); rec['n'] = 3; rec['v'] = F
        f.write(rec.tobytes())
def read_out(p):
    b = open(p, 'rb').read(); i = b.index(b'end_header\n') + 11
    nv = int(b[:i].decode().split('element vertex ')[1].split()[0])
    return np.frombuffer(b[i:i + 12 * nv], dtype='<f4').reshape(nv, 3).astype(float)
mesh, op, order, steps, salt = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
Y, F = read_ply(M + 'dn_%s.ply' % mesh)
X, _ = read_ply(M + 'dn_%s_clean.ply' % mesh.rsplit('_', 1)[0])
N, _ = area_normals(X, F)
noise = np.sum(N * (Y - X), 1); sigma2 = np.mean(noise ** 2)
if os.environ.get('STRENGTH_NORMALS'):
    nb = [set() for _ in range(len(Y))]
    for f in F:
        for k in range(3): nb[f[k]].update((f[(k + 1) % 3], f[(k + 2) % 3]))
    nb = [np.array(sorted(s)) for s in nb]
    S = Y.copy()
    for _ in range(int(os.environ['STRENGTH_NORMALS'])): S = np.array([0.5 * S[i] + 0.5 * S[nb[i]].mean(0) for i in range(len(S))])
    N = robust_normals(S, F)
    if os.environ.get('RANDOM_TILT'):
        N0 = area_normals(X, F)[0]; rng = np.random.default_rng(5)
        T = rng.normal(size=N0.shape); T -= np.sum(T * N0, 1)[:, None] * N0; T /= np.linalg.norm(T, axis=1)[:, None]
        a = np.radians(float(os.environ['RANDOM_TILT'])); N = np.cos(a) * N0 + np.sin(a) * T
    print('mean tilt of the probe normals from the clean ones (deg):', np.degrees(np.mean(np.arccos(np.clip(np.sum(N * area_normals(X, F)[0], 1), -1, 1)))))
b = np.array([1.0 if splitmix64(i ^ 0x27d4eb2f165667c5 ^ ((salt * 0x9e3779b97f4a7c15) & ((1 << 64) - 1))) & 1 else -1.0 for i in range(len(Y))])
eps = float(os.environ.get("EPS", "0.1")) * np.sqrt(sigma2)
write_ply('/tmp/truediv_yp.ply', Y + eps * b[:, None] * N, F)
def run(src, ts):
    subprocess.run([CLI, src, '/tmp/truediv_o.ply', '--operator', op, '--order', order, '--steps', steps,
                    '--time-step', ts] + EXTRA, check=True, capture_output=True)
    return read_out('/tmp/truediv_o.ply')
for ts in sys.argv[6:]:
    f0 = run(M + 'dn_%s.ply' % mesh, ts); f1 = run('/tmp/truediv_yp.ply', ts)
    div = np.sum(b * np.sum(N * (f1 - f0), 1)) / eps
    rss = np.sum(np.sum(N * (Y - f0), 1) ** 2); err = np.sum(np.sum(N * (f0 - X), 1) ** 2)
    emp = (np.sum(noise ** 2) + err - rss) / (2 * sigma2)
    print('ts %8s  mc-div(probe) %7.2f  <noise,f>/s2 %7.2f  err %.5f' % (ts, div, emp, err))
