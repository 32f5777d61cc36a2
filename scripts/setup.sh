#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Idempotent set-up on a fresh Debian 12 machine: apt packages, MeshLab SDKs (into a cache
# outside the repository), then configure and build everything into build/.
# Environment: FAIRING_CACHE (default ~/.cache/filter_implicit_fairing), BUILD_DIR (default build).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
export FAIRING_CACHE=${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}

# Debian packages the engine, the tests and the tools need.
packages=(g++ cmake ninja-build pkg-config libeigen3-dev libgtest-dev libgmock-dev
          libcli11-dev nlohmann-json3-dev)
# The sanitizer build and the fuzzer (scripts/sanitize.sh, fuzz/run.sh): clang with libFuzzer.
packages+=(clang libclang-rt-14-dev)
# MeshLab 2020.09 plugin (Debian 12's meshlab), its headless runs and integration tests
# (python3 test helpers; xdotool, imagemagick and tesseract drive and read the GUI under Xvfb).
packages+=(meshlab qtbase5-dev libqt5opengl5-dev libglew-dev dpkg-dev xz-utils python3
           xvfb xauth xdotool imagemagick tesseract-ocr tesseract-ocr-eng)
# The Debian package (scripts/package.sh, tests/package): man page from --help, lintian, man -w.
packages+=(help2man lintian man-db)
# scripts/batch.py (Dask distributed, progress bar) and its tests (label batch).
packages+=(python3-distributed python3-tqdm)
# scripts/recipes.sh and its test (label recipes): numpy for the figures, f3d for the pictures.
packages+=(python3-numpy f3d fonts-dejavu-core)
"$root/scripts/ensure-packages.sh" "${packages[@]}"

# MeshLab 2020.09 headers (Debian source package, pinned) into the cache; prints its directory.
meshlab_2020_source=$("$root/scripts/meshlab-2020-sdk.sh")
# MeshLab 2025.07 plugin SDK: meshlab-common and io_base built in float and double precision, and
# the MeshLab 2025.07 GUI (float, io_base only), into the cache; prints its directory.
meshlab_2025_sdk=$("$root/scripts/meshlab-2025-sdk.sh")
# MeshLab 2022.02 (Debian 13 / Ubuntu 24.04): meshlab-common, io_base and the GUI, float, from
# trixie's source package (pinned) into the same cache; prints its directory.
# Cold cost of both SDKs and a warm run: scripts/meshlab-2025-sdk.md.
meshlab_2022_sdk=$("$root/scripts/meshlab-2022-sdk.sh")
# Debian 13's own meshlab package (7.7 MB, sha256 pinned; unpacked by a test, never installed).
debian13_meshlab=$("$root/scripts/debian13-meshlab.sh")

cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DMESHLAB_2020_SOURCE="$meshlab_2020_source" -DMESHLAB_2025_SDK="$meshlab_2025_sdk" \
  -DMESHLAB_2022_SDK="$meshlab_2022_sdk" -DMESHLAB_2022_DEBIAN_DEB="$debian13_meshlab" \
  "$@" >/dev/null
cmake --build "$build_dir" -j2
