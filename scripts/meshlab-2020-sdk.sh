#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Fetch the MeshLab 2020.09 sources that match Debian 12's `meshlab` binary package
# (meshlab=2020.09+dfsg1-2, pinned) into a cache outside the repository. Only headers are used:
# the plugin is compiled against <dir>/src and <dir>/vcglib and links Debian's own
# /usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so.
#
# stdout: exactly one line, the unpacked source directory. Progress goes to stderr.
# Idempotent: when the directory with its STAMP exists, nothing is fetched.
# The system's apt configuration is not touched: a private deb-src list (URIs and Signed-By
# copied from /etc/apt/sources.list.d/debian.sources) lives in the cache.
#
# Environment:
#   FAIRING_CACHE  cache root (default: $HOME/.cache/filter_implicit_fairing)
set -euo pipefail

CACHE="${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}"
PKG_VERSION="2020.09+dfsg1-2"
SUITE="bookworm"
FINAL="$CACHE/meshlab-$PKG_VERSION"
DEPS=(dpkg-dev xz-utils debian-archive-keyring)

log() { printf 'meshlab-2020-sdk: %s\n' "$*" >&2; }
die() { log "ERROR: $*"; exit 1; }
valid() {   # $1 = dir: a complete, unpacked source tree
    [ -f "$1/STAMP" ] && [ -f "$1/src/common/interfaces.h" ] \
        && [ -f "$1/vcglib/vcg/complex/complex.h" ]
}

if valid "$FINAL"; then
    log "using $FINAL"
    printf '%s\n' "$FINAL"; exit 0
fi

# --- tools apt-get source needs (dpkg-source unpacks the package) ------------------------
"$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/ensure-packages.sh" "${DEPS[@]}"

mkdir -p "$CACHE"
exec 9>"$CACHE/.lock-2020"
if ! flock -n 9; then log "waiting for another run to release $CACHE/.lock-2020"; flock 9; fi
if valid "$FINAL"; then log "using $FINAL"; printf '%s\n' "$FINAL"; exit 0; fi

# --- private apt configuration: deb-src for bookworm only ---------------------------------
APT_DIR="$CACHE/apt-2020"
src_list=/etc/apt/sources.list.d/debian.sources
uris="$(sed -n 's/^URIs:[[:space:]]*//p' "$src_list" 2>/dev/null | grep -v security | head -n1 || true)"
signed="$(sed -n 's/^Signed-By:[[:space:]]*//p' "$src_list" 2>/dev/null | head -n1 || true)"
uris="${uris:-http://deb.debian.org/debian}"
signed="${signed:-/usr/share/keyrings/debian-archive-keyring.gpg}"
rm -rf "$APT_DIR"
mkdir -p "$APT_DIR/etc" "$APT_DIR/lists/partial" "$APT_DIR/cache/archives/partial"
printf 'Types: deb-src\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: %s\n' \
    "$uris" "$SUITE" "$signed" > "$APT_DIR/etc/fairing-deb-src.sources"
APT_OPTS=(-o Dir::Etc::sourcelist=/dev/null -o "Dir::Etc::sourceparts=$APT_DIR/etc"
          -o "Dir::State::Lists=$APT_DIR/lists" -o "Dir::Cache=$APT_DIR/cache"
          -o Dir::Etc::preferences=/dev/null -o "Dir::Etc::preferencesparts=$APT_DIR/etc"
          -o APT::Sandbox::User=root -q)
log "apt-get update (private deb-src list: $uris $SUITE)"
apt-get "${APT_OPTS[@]}" update >&2 || die "private apt-get update failed"

# --- fetch into a temp dir, verify, rename -------------------------------------------------
TMP="$(mktemp -d "$CACHE/.tmp-meshlab-2020.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
log "apt-get source meshlab=$PKG_VERSION"
( cd "$TMP" && apt-get "${APT_OPTS[@]}" source "meshlab=$PKG_VERSION" >"$TMP/apt-source.log" 2>&1 ) \
    || { tail -n 30 "$TMP/apt-source.log" >&2; die "apt-get source meshlab=$PKG_VERSION failed"; }
srcdir="$(find "$TMP" -mindepth 1 -maxdepth 1 -type d -name 'meshlab-*' -print -quit)"
[ -n "$srcdir" ] || die "apt-get source did not unpack a meshlab-* directory"
[ "$(tr -d '[:space:]' < "$srcdir/ML_VERSION" 2>/dev/null || true)" = 2020.09 ] \
    || die "unexpected ML_VERSION in $srcdir"
mv "$srcdir" "$TMP/tree"
mv "$TMP/apt-source.log" "$TMP/tree/APT_SOURCE.log"
printf 'Debian source meshlab %s (%s %s)\n' "$PKG_VERSION" "$uris" "$SUITE" > "$TMP/tree/SOURCE"
date -u +%Y-%m-%dT%H:%M:%SZ > "$TMP/tree/STAMP"
valid "$TMP/tree" || die "unpacked tree lacks src/common/interfaces.h or vcglib"
rm -rf "$FINAL"                      # a left-over without STAMP
mv -T "$TMP/tree" "$FINAL"
log "using $FINAL"
printf '%s\n' "$FINAL"
