# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""Each filter's one-click step count with L^2 (parameters/filter_parameters.h defaultSteps), for
the benchmarks that time or sweep the defaults (run_bench.py, denoise.py)."""
ONE_CLICK_STEPS = {"umbrella": 8, "scale-dependent": 2, "curvature": 4}
