#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Run Debian 12's real meshlabserver (MeshLab 2020.09) headless with the freshly built implicit
# fairing plugin, without installing anything:
#   scripts/meshlabserver.sh -i in.ply -o out.ply -s script.mlx     (any meshlabserver arguments)
#
# MeshLab 2020.09 finds plugins only relative to the real path of its binary, so a private
# prefix in the build directory holds a COPY of the binary in bin/ and, in
# lib/x86_64-linux-gnu/meshlab/, a link to libmeshlab-common.so and plugins/ with links to all
# stock plugins (PLY import lives there) plus our .so.
#
# Exit status: meshlabserver's own when non-zero (255: a filter failed or is missing; the
# filter's error message is printed on stderr by the plugin); otherwise non-zero as well when
# a filter reported a problem or an output (-o) or dump (-d) file was not written, since
# meshlabserver exits 0 even then.
#
# Environment: BUILD_DIR (default <repo>/build), FAIRING_PLUGIN (the .so, default
# $BUILD_DIR/meshlab2020/plugins/libfilter_implicit_fairing.so).
# Internal: `--prefix-only` prepares the prefix and prints its path (used by scripts/meshlab.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
plugin=${FAIRING_PLUGIN:-$build_dir/meshlab2020/plugins/libfilter_implicit_fairing.so}
sys_lib=/usr/lib/x86_64-linux-gnu/meshlab
prefix=$build_dir/meshlab2020/prefix

die() { echo "meshlabserver.sh: $*" >&2; exit 2; }
[ -f "$plugin" ] || die "plugin not built: $plugin (run scripts/setup.sh)"
[ -x /usr/bin/meshlabserver ] && [ -f "$sys_lib/libmeshlab-common.so" ] \
    || die "Debian's meshlab is not installed (run scripts/setup.sh)"

# --- the private prefix (idempotent; safe when several runs start at once) -----------------
mkdir -p "$prefix"
exec 8>"$prefix/.lock"
flock 8
mkdir -p "$prefix/bin" "$prefix/lib/x86_64-linux-gnu/meshlab/plugins"
for b in meshlabserver meshlab; do
    if [ -x "/usr/bin/$b" ] && ! cmp -s "/usr/bin/$b" "$prefix/bin/$b"; then
        cp "/usr/bin/$b" "$prefix/bin/$b.tmp" && mv -f "$prefix/bin/$b.tmp" "$prefix/bin/$b"
    fi
done
ln -sfn "$sys_lib/libmeshlab-common.so" "$prefix/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so"
pdir=$prefix/lib/x86_64-linux-gnu/meshlab/plugins
find "$pdir" -maxdepth 1 -type l ! -exec test -e {} \; -delete    # stale links
for p in "$sys_lib"/plugins/*.so; do
    ln -sfn "$p" "$pdir/$(basename "$p")"
done
ln -sfn "$(readlink -f "$plugin")" "$pdir/$(basename "$plugin")"
flock -u 8
exec 8>&-

if [ "${1:-}" = --prefix-only ]; then printf '%s\n' "$prefix"; exit 0; fi

# --- packages for a headless run ---------------------------------------------------------
for p in xvfb xauth; do
    [ "$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)" = installed ] \
        || die "package $p missing (run scripts/setup.sh)"
done

# --- outputs to check afterwards ---------------------------------------------------------
outputs=()
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
    case "${args[i]}" in
        -o|-d|-w) if ((i + 1 < ${#args[@]})); then outputs+=("${args[i+1]}"); fi ;;
    esac
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/config"
touch "$tmp/start"
sleep 0.01   # so that a file written by this run is strictly newer than the marker

set +e
XDG_CONFIG_HOME="$tmp/config" xvfb-run -a -s "-screen 0 1280x1024x24" \
    "$prefix/bin/meshlabserver" "$@" > >(tee "$tmp/out") 2>&1
rc=$?
wait    # for tee
set -e

if [ "$rc" -ne 0 ]; then
    echo "meshlabserver.sh: meshlabserver exited with status $rc" >&2
    exit "$rc"
fi
status=0
if grep -q "^Problem with filter" "$tmp/out"; then
    echo "meshlabserver.sh: a filter failed" >&2
    status=1
fi
for f in "${outputs[@]}"; do
    if [ ! -s "$f" ] || [ ! "$f" -nt "$tmp/start" ]; then
        echo "meshlabserver.sh: $f was not written" >&2
        status=1
    fi
done
exit "$status"
