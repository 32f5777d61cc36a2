# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# auto-gap.md section 42: where a result's error lies on the unit two-density sphere: RMS and
# mean of |x| - 1 per tenth of the clean mesh's z (the finer half is z > 0).
# Usage: python3 drift.py CLEAN.ply RESULT.ply...
import os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "session39-probe"))
from plyio import read_ply  # noqa: E402
C = read_ply(sys.argv[1])[0]
bins = np.linspace(-1, 1, 11)
idx = np.digitize(C[:, 2], bins)
print("%-28s %s" % ("file (RMS / mean per tenth of z)", " ".join("%15s" % ("z<%.1f" % b) for b in bins[1:])))
for f in sys.argv[2:]:
    e = np.linalg.norm(read_ply(f)[0], axis=1) - 1
    print("%-28s %s  all %.2e" % (os.path.basename(f)[:28], " ".join(
        "%7.1e/%+.0e" % (np.sqrt((e[idx == k] ** 2).mean()), e[idx == k].mean()) for k in range(1, 11)),
        np.sqrt((e ** 2).mean())))
