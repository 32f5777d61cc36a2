#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Session 33's probe inputs (seed 19): the curvature default's automatic choice with the switch on
# the steps' total (0: 5af7ce3) and per step (1: FAIRING_L2_PERSTEP=1), over session 33's oracles
# at 47e4aed; s33_perstep.txt labels them UNUSED and FAIRING_L2_PERSTEP. LANE=0|1: every other
# case. BIN, DATA (libcgal-demo's data/meshes) and P (the probe inputs, ../session32-probe/probe.sh
# SEED=19) as for ../session35-probe/session33_probe.sh.
ENVS="UNUSED=1 FAIRING_L2_PERSTEP=1" exec "$(dirname "$0")/../session35-probe/session33_probe.sh"
