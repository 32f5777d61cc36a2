#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Fetch and build the MeshLab 2022.02 plugin SDK: the MeshLab that Debian 13 (trixie) and
# Ubuntu 24.04 ship as `meshlab` (FilterPlugin API, float). Debian's source package
# meshlab=2022.02+dfsg1-1 from trixie (orig tarball sha256 pinned in meshlab-2025-sdk.sh),
# meshlab-common and io_base in float, and the `meshlab` GUI (float, io_base only), into the
# same cache as the 2025.07 SDK. Same script, same guarantees (cache keyed by version, tarball
# sha256, Qt and GCC; built in a temp dir and renamed; a warm run does nothing):
#
#   SDK=$(scripts/meshlab-2022-sdk.sh)   # prints <cache>/meshlab-2022.02-11da26ec46c3-qt<Qt>-gcc<N>-float
#
# Layout: as scripts/meshlab-2025-sdk.md describes, without double/.
# Environment: FAIRING_CACHE, FAIRING_JOBS, FAIRING_MESHLAB_GUI (as for meshlab-2025-sdk.sh).
set -euo pipefail
export FAIRING_MESHLAB_SDK=2022.02 FAIRING_SDK_PRECISIONS=float
exec "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/meshlab-2025-sdk.sh" "$@"
