# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# A 300x300-cell sheet with 10,000 one-cell holes (every third cell each way), as PLY.
import numpy as np, sys
n = int(sys.argv[2]) if len(sys.argv) > 2 else 300
xs, ys = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(n + 1, dtype=float))
V = np.c_[xs.ravel(), ys.ravel(), np.zeros((n + 1) ** 2)]
F = []
for j in range(n):
    for i in range(n):
        if i % 3 == 1 and j % 3 == 1: continue
        a = j * (n + 1) + i; b = a + 1; c = a + n + 1; d = c + 1
        F += [(a, b, d), (a, d, c)]
F = np.array(F, dtype='<i4')
with open(sys.argv[1], 'wb') as f:
    f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\n"
             "property double y\nproperty double z\nelement face %d\n"
             "property list uchar int vertex_indices\nend_header\n" % (len(V), len(F))).encode())
    f.write(V.astype('<f8').tobytes())
    rec = np.zeros(len(F), dtype=np.dtype([('n', 'u1'), ('v', '<i4', 3)])); rec['n'] = 3; rec['v'] = F
    f.write(rec.tobytes())
