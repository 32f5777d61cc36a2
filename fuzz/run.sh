#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Build the libFuzzer targets with clang, -fsanitize=fuzzer,address,undefined (the engine too,
# for coverage and checks), in their own build directory, and fuzz for a bounded time.
#   fuzz/run.sh [SECONDS]          default 60 (CI)
#   FUZZ_RUNS=1000000 fuzz/run.sh  a fixed number of executions instead (the long local run)
# Environment: FUZZ_BUILD_DIR (default <repo>/build-fuzz), FAIRING_CACHE (MeshLab SDK cache,
# for vcglib). Exit status non-zero on a crash, a sanitizer report, a timeout (> 10 s for one
# input) or an out-of-memory; the input that did it is in $FUZZ_BUILD_DIR/artifacts/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${1:-60}
command -v clang++ >/dev/null || { echo "fuzz/run.sh: clang++ not found" >&2; exit 2; }
sdk=$("$root/scripts/meshlab-2020-sdk.sh")

flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DFAIRING_BUILD_TESTS=OFF -DFAIRING_BUILD_FUZZERS=ON -DVCGLIB_DIR="$sdk/vcglib" >/dev/null
cmake --build "$build" --target fuzz_mesh_bytes -j2

corpus=$build/corpus/fuzz_mesh_bytes
mkdir -p "$corpus" "$build/artifacts"
python3 "$root/fuzz/make_seeds.py" "$corpus"
limit=(-max_total_time="$seconds")
[ -n "${FUZZ_RUNS:-}" ] && limit=(-runs="$FUZZ_RUNS")
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
start=$(date +%s)
"$build/bin/fuzz_mesh_bytes" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/" "$corpus"
echo "fuzz/run.sh: fuzz_mesh_bytes clean after $(( $(date +%s) - start )) s"
