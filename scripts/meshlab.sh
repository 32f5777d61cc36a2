#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Open Debian 12's real MeshLab 2020.09 GUI with the freshly built implicit fairing plugin, without
# installing anything (same private prefix as scripts/meshlabserver.sh):
#   scripts/meshlab.sh [mesh.ply ...]
# The filters are in Filters > Smoothing, Fairing and Deformation > Implicit Fairing: ...
# Needs a display; without one, run it under Xvfb: xvfb-run -a scripts/meshlab.sh mesh.ply
# Environment: BUILD_DIR, FAIRING_PLUGIN (as for meshlabserver.sh); FAIRING_FRESH_CONFIG=1 runs
# with an empty temporary MeshLab configuration (reproducible; used by the GUI test).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
prefix=$("$here/meshlabserver.sh" --prefix-only)
if [ -z "${DISPLAY:-}" ]; then
    echo "meshlab.sh: no DISPLAY; run it as: xvfb-run -a $0 $*" >&2
    exit 2
fi
if [ "${FAIRING_FRESH_CONFIG:-0}" = 1 ]; then
    # an empty configuration next to the prefix, wiped at each start (exec keeps the PID)
    cfg=$(dirname "$prefix")/gui-config
    rm -rf "$cfg"; mkdir -p "$cfg"
    export XDG_CONFIG_HOME=$cfg
fi
exec "$prefix/bin/meshlab" "$@"
