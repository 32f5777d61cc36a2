#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 50: the index gaps of a 256 x 144 torus grid (radii 3 and 1, the size of
# VertexOrder.NoEdgeSpansMoreThanTwoFronts's grid, without its noise and with each quad split
# along one diagonal) numbered along the former Z-order curve (order_gaps.py's replica): the
# share of edges more than 768 rows apart (the test's bound) and the largest gap.
# Usage: /usr/bin/python3 torus_gaps.py
import os, sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from order_gaps import edge_gaps, morton  # noqa: E402

U, V = 256, 144
i, j = np.meshgrid(np.arange(U), np.arange(V), indexing="ij")
u, w = 2 * np.pi * i / U, 2 * np.pi * j / V
v = np.stack([(3 + np.cos(w)) * np.cos(u), (3 + np.cos(w)) * np.sin(u), np.sin(w)], -1).reshape(-1, 3)
at = lambda a, b: (a % U) * V + (b % V)
f = np.array([t for a in range(U) for b in range(V)
              for t in ([at(a, b), at(a + 1, b), at(a + 1, b + 1)],
                        [at(a, b), at(a + 1, b + 1), at(a, b + 1)])])
g = edge_gaps(morton(v), f)[1]
print("vertices %d: Z-order largest gap %d, edges past 768 %.4f" % (len(v), g.max(), (g > 768).mean()))
