#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The whole test suite, as CI runs it: set-up (idempotent), build, then every test through CTest.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
"$root/scripts/setup.sh"
ctest --test-dir "$build_dir" --output-on-failure -j2 "$@"
# The engine's unit and robustness tests again under AddressSanitizer and UBSan (own build dir).
"$root/scripts/sanitize.sh"
# libFuzzer over mesh bytes -> adapter -> engine, for a bounded time (own build dir).
"$root/fuzz/run.sh" "${FUZZ_SECONDS:-60}"
