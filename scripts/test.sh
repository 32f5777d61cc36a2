#!/usr/bin/env bash
# The whole test suite, as CI runs it: set-up (idempotent), build, then every test through CTest.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
"$root/scripts/setup.sh"
ctest --test-dir "$build_dir" --output-on-failure -j2 "$@"
