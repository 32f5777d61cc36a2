#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The modelled risk of a FAIRING_DUMP_RISK dump (session37-probe/throwaway.patch): its minimum, the
one-standard-error choice (auto_strength.cpp, choose), and the curve in units of N sigma^2.
    risk.py DUMP...; the real error at some of its time steps: real_51k_n0.1.jsonl"""
import math, sys
for path in sys.argv[1:]:
    R = [l.split() for l in open(path) if l.startswith('RISK')]
    lam = [float(r[1]) for r in R]; rss = [float(r[2]) for r in R]; div = [float(r[3]) for r in R]
    s = float(R[0][4]); N = float(R[0][5]); s2 = s * s
    risk = [a + 2 * s2 * d - N * s2 for a, d in zip(rss, div)]
    b = min(range(len(risk)), key=lambda i: risk[i])
    strongest = b
    for g in range(b + 1, len(risk)):
        if risk[g] <= risk[b] + s2 * math.sqrt(2 * abs(div[b] - div[g])): strongest = g
    print(path, 'N', N, 'min at', lam[b], 'risk/Ns2 %.4f' % (risk[b] / (N * s2)), 'div', div[b], 'SE-rule', lam[strongest], 'div', div[strongest])
    for i in range(0, len(lam), 4):
        if 1e3 <= lam[i] <= 2e6:
            print('  %.3g risk/Ns2 %.4f  (rss/Ns2 %.4f div/N %.4f) thr %.4f' % (lam[i], risk[i] / (N * s2), rss[i] / (N * s2), div[i] / N, (risk[b] + s2 * math.sqrt(2 * abs(div[b] - div[i]))) / (N * s2)))
