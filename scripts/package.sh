#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Builds the Debian 12 package implicit-fairing_<version>-<rev>_amd64.deb (CPack, see
# cmake/packaging.cmake) from the normal build dir and prints its path on stdout.
#   scripts/package.sh [--lintian]     --lintian: also run Debian's lintian on it (report only)
# Environment: BUILD_DIR (default <repo>/build, configured by scripts/setup.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
die() { echo "package.sh: $*" >&2; exit 2; }

[ -f "$build_dir/CPackConfig.cmake" ] \
    || die "$build_dir/CPackConfig.cmake missing: configure with MESHLAB_2020_SOURCE first (scripts/setup.sh)"
command -v dpkg-shlibdeps >/dev/null || die "dpkg-shlibdeps missing (apt-get install dpkg-dev)"
command -v help2man >/dev/null || die "help2man missing (apt-get install help2man), needed for the man page"

# Only what the package holds (cpack itself builds nothing with the Ninja generator).
cmake --build "$build_dir" -j2 --target filter_implicit_fairing implicit-fairing \
    implicit-fairing-man implicit-fairing-changelog >&2
[ -f "$build_dir/man/implicit-fairing.1.gz" ] || die "man page not generated (help2man)"

out=$build_dir/package
rm -f "$out"/*.deb
(cd "$build_dir" && cpack -G DEB --config CPackConfig.cmake -B "$out") >&2
debs=("$out"/*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || die "cpack did not produce exactly one .deb in $out"
if [ "${1:-}" = --lintian ]; then
    command -v lintian >/dev/null || die "lintian missing (apt-get install lintian)"
    lintian --info --display-info "${debs[0]}" >&2 || true
fi
printf '%s\n' "${debs[0]}"
