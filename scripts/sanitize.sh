#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The unit suite (tests/engine, label engine, and tests/robustness, label robustness) under
# AddressSanitizer and UndefinedBehaviorSanitizer, any finding fatal. Engine and unit tests only
# (no MeshLab), in a build directory of its own:
#   scripts/sanitize.sh [ctest arguments]
# Environment: SANITIZE_BUILD_DIR (default <repo>/build-sanitize), CXX (default clang++ when
# installed, else g++).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${SANITIZE_BUILD_DIR:-$root/build-sanitize}
if [ -z "${CXX:-}" ]; then
    if command -v clang++ >/dev/null; then CXX=clang++; else CXX=g++; fi
fi
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DFAIRING_BUILD_TESTS=ON -DFAIRING_BUILD_FUZZERS=OFF -DMESHLAB_2020_SOURCE= >/dev/null
cmake --build "$build" --target engine_tests robustness_tests -j2
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build" -L 'engine|robustness' --output-on-failure -j2 "$@"
