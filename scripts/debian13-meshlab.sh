#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Fetch Debian 13 (trixie)'s binary package meshlab_2022.02+dfsg1-1_amd64.deb (sha256 pinned;
# 7.7 MB) into the cache, for tests/meshlab2022's check that the 2022.02 plugin fits the MeshLab
# Debian 13 users install (its libmeshlab-common.so exports every symbol the plugin imports).
# The package is only unpacked, never installed or run (it needs trixie's glibc and Qt).
#
# stdout: one line, the path of the .deb. Progress goes to stderr. Idempotent: when the file
# with the right sha256 is in the cache, nothing is fetched. The system's apt state is not
# touched: a private deb list (URIs and Signed-By copied from
# /etc/apt/sources.list.d/debian.sources) lives in the cache.
#
# Environment: FAIRING_CACHE (default: $HOME/.cache/filter_implicit_fairing)
set -euo pipefail
CACHE="${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}"
VERSION="2022.02+dfsg1-1"
DEB="meshlab_${VERSION}_amd64.deb"
SHA256="a6a1c06962fb46475e2f3a3c9eebb6ad0795b68b0e595b14805ce85ebfccfe53"
FINAL="$CACHE/debs/$DEB"

log() { printf 'debian13-meshlab: %s\n' "$*" >&2; }
die() { log "ERROR: $*"; exit 1; }
ok() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$SHA256" ]; }

if ok "$FINAL"; then printf '%s\n' "$FINAL"; exit 0; fi

mkdir -p "$CACHE/debs"
exec 9>"$CACHE/.lock-debian13"
flock 9
if ok "$FINAL"; then printf '%s\n' "$FINAL"; exit 0; fi

A="$CACHE/apt-debian13"
src_list=/etc/apt/sources.list.d/debian.sources
uris="$(sed -n 's/^URIs:[[:space:]]*//p' "$src_list" 2>/dev/null | grep -v security | head -n1 || true)"
signed="$(sed -n 's/^Signed-By:[[:space:]]*//p' "$src_list" 2>/dev/null | head -n1 || true)"
uris="${uris:-http://deb.debian.org/debian}"
signed="${signed:-/usr/share/keyrings/debian-archive-keyring.gpg}"
rm -rf "$A"
mkdir -p "$A/etc" "$A/prefs" "$A/lists/partial" "$A/cache/archives/partial" "$A/dl"
printf 'Types: deb\nURIs: %s\nSuites: trixie\nComponents: main\nSigned-By: %s\n' \
    "$uris" "$signed" > "$A/etc/trixie.sources"
O=(-o Dir::Etc::sourcelist=/dev/null -o "Dir::Etc::sourceparts=$A/etc"
   -o "Dir::State::Lists=$A/lists" -o "Dir::Cache=$A/cache"
   -o Dir::Etc::preferences=/dev/null -o "Dir::Etc::preferencesparts=$A/prefs"
   -o Dir::State::status=/dev/null -o APT::Architecture=amd64 -o APT::Sandbox::User=root -q)
log "apt-get update (private deb list: trixie)"
apt-get "${O[@]}" update >&2 || die "private apt-get update failed"
log "apt-get download meshlab=$VERSION"
( cd "$A/dl" && apt-get "${O[@]}" download "meshlab=$VERSION" >&2 ) || die "download failed"
ok "$A/dl/$DEB" || die "sha256 mismatch for $DEB (want $SHA256)"
mv "$A/dl/$DEB" "$FINAL"
rm -rf "$A"
printf '%s\n' "$FINAL"
