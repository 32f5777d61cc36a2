#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Fetch and build the MeshLab 2025.07 plugin SDK (meshlab-common and io_base in float AND double
# precision) and the MeshLab 2025.07 GUI application (`meshlab`, float, with io_base only) into a
# versioned cache outside the repository. scripts/meshlab-2022-sdk.sh runs this script for
# MeshLab 2022.02 (float only).
#
# stdout: exactly one line, the SDK directory.  Progress and the SDK used go to stderr.
# Idempotent: when the SDK directory with its STAMP exists, nothing is fetched or built.
#
# Environment:
#   FAIRING_CACHE        cache root (default: $HOME/.cache/filter_implicit_fairing)
#   FAIRING_JOBS         parallel build jobs (default: 2)
#   FAIRING_MESHLAB_SDK  auto (default: 2025.07, else trixie's 2022.02), 2025.07 or 2022.02
#   FAIRING_MESHLAB_GUI  1 (default): also build the GUI (gui/); 0: libraries only
#   FAIRING_SDK_PRECISIONS  "float double" (default) or "float" (the directory name then ends
#                        in -float, so a float-only SDK is never mistaken for a complete one)
#
# Layout of the SDK directory (see scripts/meshlab-2025-sdk.md):
#   src/                      unpacked orig tarball (MeshLab sources incl. src/vcglib)
#   float/distrib/            libmeshlab-common.so, plugins/libio_base.so ($ORIGIN RUNPATHs)
#   float/PLUGIN_DEFINES      compile definitions a plugin needs, one NAME=VALUE per line
#   double/...                the same for the double-precision build
#   gui/distrib/meshlab       the GUI (float), next to its own libmeshlab-common.so, plugins/
#                             (io_base) and shaders/; gui/STAMP written last. Built in the same
#                             tree as float/ (identical libraries); added to an existing SDK
#                             directory that lacks it without touching the rest.
#   INCLUDE_DIRS              include directories a plugin needs, one per line
#   VERSION, SOURCE, TARBALL_SHA256, STAMP (written last)
set -euo pipefail
shopt -s inherit_errexit

CACHE="${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}"
JOBS="${FAIRING_JOBS:-2}"
WANT="${FAIRING_MESHLAB_SDK:-auto}"
GUI="${FAIRING_MESHLAB_GUI:-1}"
PRECISIONS="${FAIRING_SDK_PRECISIONS:-float double}"
case "$GUI" in 0|1) ;; *) echo "meshlab-2025-sdk: FAIRING_MESHLAB_GUI must be 0 or 1" >&2; exit 1 ;; esac
case "$PRECISIONS" in "float double"|float) ;;
    *) echo "meshlab-2025-sdk: FAIRING_SDK_PRECISIONS must be 'float double' or 'float'" >&2; exit 1 ;; esac

# version | orig tarball | sha256 | apt version pattern | build layout
SDK_2025="2025.07|meshlab_2025.07~dfsg.orig.tar.xz|d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4|2025.07~dfsg-*|new"
SDK_2022="2022.02|meshlab_2022.02+dfsg1.orig.tar.xz|11da26ec46c3fbbbc806d410a3221542ec21ec13fdcc55d624304600029435fd|2022.02+dfsg1-1|old"
# Suites searched for the source package, in order of preference.
SUITES_2025="sid testing"   # testing = forky today
SUITES_2022="trixie"

DEPS=(qtbase5-dev libqt5opengl5-dev libeigen3-dev libglew-dev libglu1-mesa-dev
      cmake ninja-build g++ xz-utils)

log() { printf 'meshlab-2025-sdk: %s\n' "$*" >&2; }
die() { log "ERROR: $*"; exit 1; }

# --- 1. build dependencies ----------------------------------------------------------------
"$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/ensure-packages.sh" "${DEPS[@]}"

# --- toolchain part of the cache key ------------------------------------------------------
QT_VER="$(dpkg-query -W -f='${Version}' qtbase5-dev)"
QT_VER="${QT_VER#*:}"; QT_VER="${QT_VER%%[+~-]*}"          # 5.15.8+dfsg-11+deb12u3 -> 5.15.8
GCC_MAJOR="$(g++ -dumpversion)"; GCC_MAJOR="${GCC_MAJOR%%.*}"
[ -n "$QT_VER" ] && [ -n "$GCC_MAJOR" ] || die "cannot determine Qt/GCC versions"

sdk_field() { printf '%s' "$1" | cut -d'|' -f"$2"; }
sdk_dir()   { printf '%s/meshlab-%s-%s-qt%s-gcc%s%s' "$CACHE" "$(sdk_field "$1" 1)" \
                  "$(sdk_field "$1" 3 | cut -c1-12)" "$QT_VER" "$GCC_MAJOR" \
                  "$([ "$PRECISIONS" = float ] && echo -float)"; }
# complete: the libraries (STAMP) and, when wanted, the GUI (gui/STAMP)
sdk_complete() { [ -f "$1/STAMP" ] && { [ "$GUI" = 0 ] || [ -f "$1/gui/STAMP" ]; }; }

case "$WANT" in
    auto)    CANDIDATES=("$SDK_2025" "$SDK_2022") ;;
    2025.07) CANDIDATES=("$SDK_2025") ;;
    2022.02) CANDIDATES=("$SDK_2022") ;;
    *) die "FAIRING_MESHLAB_SDK must be auto, 2025.07 or 2022.02 (got '$WANT')" ;;
esac

announce() {   # $1 = SDK dir
    log "using MeshLab SDK $(cat "$1/VERSION") ($(cat "$1/SOURCE")): $1"
    if [ "$(cat "$1/VERSION")" != 2025.07 ] && [ "$WANT" = auto ]; then
        log "WARNING: fallback SDK, not 2025.07: plugins must use its API (e.g. RichAbsPerc) and MESHLAB_VERSION"
    fi
    printf '%s\n' "$1"
}

# Fast path: the preferred SDK is already built.
if sdk_complete "$(sdk_dir "${CANDIDATES[0]}")"; then
    announce "$(sdk_dir "${CANDIDATES[0]}")"; exit 0
fi

mkdir -p "$CACHE/tarballs"
# The cache root is shared with other scripts: use only names of our own. One lock per MeshLab
# version (.lock-2025, .lock-2022), taken before a version is looked at (fallbacks only when
# reached), so the 2025.07 and 2022.02 SDKs can be built at the same time, never one twice.
next_fd=9
lock_version() {   # $1 = SDK record
    local v lock
    v="$(sdk_field "$1" 1)"
    lock="$CACHE/.lock-$(printf '%s' "$v" | cut -c1-4)"
    eval "exec $next_fd>\"\$lock\""
    if ! flock -n "$next_fd"; then
        log "waiting for another run to release $lock"
        flock "$next_fd"
    fi
    next_fd=$((next_fd - 1))
    # Under the lock, this version's temp dirs can only be left-overs of killed runs.
    rm -rf "$CACHE/.tmp-meshlab-$v-"* "$CACHE/apt-${v%%.*}/dl" "$CACHE/meshlab-$v-"*/.tmp-gui.*
}

# --- 2. fetching ---------------------------------------------------------------------------
APT_DIR=""    # $CACHE/apt-2025 or apt-2022: set per version by fetch_tarball
APT_OPTS=()
apt_ready=""
apt_private_update() {     # private deb-src list for the given suites; the system is untouched
    local suites="$1" uris signed
    [ "$apt_ready" = "$suites" ] && return 0
    uris="$(sed -n 's/^URIs:[[:space:]]*//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null \
            | grep -v security | head -n1 || true)"
    signed="$(sed -n 's/^Signed-By:[[:space:]]*//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null \
            | head -n1 || true)"
    uris="${uris:-http://deb.debian.org/debian}"
    signed="${signed:-/usr/share/keyrings/debian-archive-keyring.gpg}"
    rm -rf "$APT_DIR"
    mkdir -p "$APT_DIR/etc" "$APT_DIR/prefs" "$APT_DIR/lists/partial" "$APT_DIR/cache/archives/partial" "$APT_DIR/dl"
    printf 'Types: deb-src\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: %s\n' \
        "$uris" "$suites" "$signed" > "$APT_DIR/etc/meshlab-src.sources"
    APT_OPTS=(-o Dir::Etc::sourcelist=/dev/null -o "Dir::Etc::sourceparts=$APT_DIR/etc"
              -o "Dir::State::Lists=$APT_DIR/lists" -o "Dir::Cache=$APT_DIR/cache"
              -o Dir::Etc::preferences=/dev/null -o "Dir::Etc::preferencesparts=$APT_DIR/prefs"
              -o APT::Sandbox::User=root -q)
    log "apt-get update (private deb-src list: $suites)"
    apt-get "${APT_OPTS[@]}" update >&2 || { log "private apt-get update failed"; return 1; }
    apt_ready="$suites"
}

tarball_ok() { [ -f "$1" ] && [ "$(sha256sum "$1" | cut -d' ' -f1)" = "$2" ]; }

GOT_TARBALL=""; GOT_ORIGIN=""
fetch_tarball() {   # $1 = SDK record, $2 = suites. Sets GOT_TARBALL and GOT_ORIGIN on success.
    # Runs in an "if" (errexit is off): every step checks its own result.
    local rec="$1" suites="$2" ver tar sha pat path srcver
    ver="$(sdk_field "$rec" 1)"; tar="$(sdk_field "$rec" 2)"
    sha="$(sdk_field "$rec" 3)"; pat="$(sdk_field "$rec" 4)"
    path="$CACHE/tarballs/$tar"
    APT_DIR="$CACHE/apt-${ver%%.*}"
    if tarball_ok "$path" "$sha"; then
        GOT_TARBALL="$path"; GOT_ORIGIN="$(cat "$path.origin" 2>/dev/null || echo "cached $tar")"
        return 0
    fi
    rm -f "$path"
    apt_private_update "$suites" || return 1
    # newest Debian revision of this upstream version that any listed suite carries
    srcver="$(apt-cache "${APT_OPTS[@]}" showsrc meshlab 2>/dev/null \
              | sed -n 's/^Version:[[:space:]]*//p' | while read -r v; do
                    # shellcheck disable=SC2053
                    [[ "$v" == $pat ]] && echo "$v"; done | sort -V | tail -n1 || true)"
    if [ -z "$srcver" ]; then
        log "no meshlab $ver source package in: $suites"; return 1
    fi
    log "downloading meshlab $srcver orig tarball"
    ( cd "$APT_DIR/dl" && apt-get "${APT_OPTS[@]}" source --download-only --tar-only \
          "meshlab=$srcver" >&2 ) || { log "apt-get source meshlab=$srcver failed"; return 1; }
    [ -f "$APT_DIR/dl/$tar" ] || { log "apt did not deliver $tar"; return 1; }
    if ! tarball_ok "$APT_DIR/dl/$tar" "$sha"; then
        log "sha256 mismatch for $tar (want $sha)"; rm -f "$APT_DIR/dl/$tar"; return 1
    fi
    mv "$APT_DIR/dl/$tar" "$path" || return 1
    echo "Debian source package meshlab $srcver, orig tarball sha256 $sha" > "$path.origin" || return 1
    GOT_TARBALL="$path"; GOT_ORIGIN="$(cat "$path.origin")"
}
# --- 3. build ------------------------------------------------------------------------------
TMP=""
cleanup() { if [ -n "$TMP" ]; then rm -rf "$TMP"; fi; }
trap cleanup EXIT

# build_tree SRCROOT LAYOUT PREC WITH_GUI BUILD_DIR: configure and build meshlab-common and
# io_base (+ the meshlab application and its shaders when WITH_GUI=1) in BUILD_DIR; the logs go
# to BUILD_DIR.{configure,build}.log. Sets TREE_DISTRIB (the distrib folder) and TREE_EIGEN.
TREE_DISTRIB=""; TREE_EIGEN=""
build_tree() {
    local srcroot="$1" layout="$2" prec="$3" with_gui="$4" b="$5"
    local dbl=OFF libs_only=ON cmsrc opts targets t0 x
    [ "$prec" = double ] && dbl=ON
    [ "$with_gui" = 1 ] && libs_only=OFF
    if [ "$layout" = new ]; then   # 2025.07: top-level CMakeLists.txt, MESHLAB_* options
        cmsrc="$srcroot"
        opts=(-DMESHLAB_BUILD_ONLY_LIBRARIES="$libs_only" -DMESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES=OFF
              -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR="$dbl")
    else                           # 2022.02: CMakeLists.txt in src/, other option names
        cmsrc="$srcroot/src"
        opts=(-DBUILD_ONLY_MESHLAB_LIBRARIES="$libs_only" -DBUILD_WITH_DOUBLE_SCALAR="$dbl")
        # no MESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES yet; the dfsg tarball lacks parts
        # of some bundled libraries (u3d's zlib), so switch the optional ones off.
        for x in BOOST CGAL LEVMAR LIB3DS LIBE57_FORMAT LIBIGL MUPARSER NEWUOA NEXUS \
                 OPENCTM QHULL SSYNTH TINY_GLTF U3D XERCES; do
            opts+=("-DALLOW_BUNDLED_$x=OFF" "-DALLOW_SYSTEM_$x=OFF")
        done
    fi
    log "configuring the $prec build$([ "$with_gui" = 1 ] && echo ' with the GUI')"
    t0=$SECONDS
    cmake -S "$cmsrc" -B "$b" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++ \
        -DCMAKE_BUILD_RPATH_USE_ORIGIN=ON \
        "${opts[@]}" -DMESHLAB_PLUGINS=meshlabplugins/io_base > "$b.configure.log" 2>&1 \
        || { tail -n 40 "$b.configure.log" >&2; die "cmake configure ($prec) failed"; }
    targets=(meshlab-common io_base)
    if [ "$with_gui" = 1 ]; then
        targets+=(meshlab)
        # the shaders MeshLab's render modes read next to the binary
        if cmake --build "$b" --target help 2>/dev/null | grep -q '^copy-distrib-files:'; then
            targets+=(copy-distrib-files)
        fi
    fi
    log "building ${targets[*]} ($prec, -j$JOBS)"
    cmake --build "$b" --target "${targets[@]}" -j "$JOBS" > "$b.build.log" 2>&1 \
        || { tail -n 40 "$b.build.log" >&2; die "build ($prec) failed"; }
    log "$prec build done in $((SECONDS - t0)) s"
    TREE_DISTRIB="$(dirname "$(find "$b" -name libmeshlab-common.so -print -quit)")"
    [ -f "$TREE_DISTRIB/libmeshlab-common.so" ] && [ -f "$TREE_DISTRIB/plugins/libio_base.so" ] \
        || die "build outputs not found in $b"
    if [ "$with_gui" = 1 ]; then
        [ -x "$TREE_DISTRIB/meshlab" ] || die "the meshlab application was not built in $b"
    fi
    # Eigen include dir the build used (vcglib takes the system Eigen: no eigenlib in dfsg)
    TREE_EIGEN="$(grep -o -E -- '-I[^ ]*eigen[^ ]*' "$b/build.ninja" \
                  | grep -v vcglib | head -n1 | cut -c3- || true)"
}

# install_gui DISTRIB DEST: the GUI component (whole distrib folder: meshlab, its
# libmeshlab-common.so, plugins/libio_base.so, shaders/; $ORIGIN RUNPATHs), STAMP last.
install_gui() {
    cp -a "$1" "$2/distrib"
    rm -f "$2/distrib/plugins/"*.a
    "$2/distrib/meshlab" --version > "$2/VERSION" 2>/dev/null \
        || die "the built meshlab does not run: $2/distrib/meshlab --version"
    date -u +%Y-%m-%dT%H:%M:%SZ > "$2/STAMP"
}

BUILT_DIR=""
build_sdk() {   # $1 = SDK record, $2 = tarball, $3 = origin text; sets BUILT_DIR
    local rec="$1" tarball="$2" origin="$3" ver sha layout final top srcroot prec eigen_dir=""
    ver="$(sdk_field "$rec" 1)"; sha="$(sdk_field "$rec" 3)"; layout="$(sdk_field "$rec" 5)"
    final="$(sdk_dir "$rec")"
    TMP="$(mktemp -d "$CACHE/.tmp-$(basename "$final").XXXXXX")"

    log "unpacking $(basename "$tarball")"
    mkdir "$TMP/unpack"
    tar --no-same-owner -xJf "$tarball" -C "$TMP/unpack"
    top="$(find "$TMP/unpack" -mindepth 1 -maxdepth 1 -type d)"
    [ "$(printf '%s\n' "$top" | wc -l)" -eq 1 ] || die "unexpected tarball layout"
    mv "$top" "$TMP/src"; rmdir "$TMP/unpack"
    srcroot="$TMP/src"
    [ "$(tr -d '[:space:]' < "$srcroot/ML_VERSION")" = "$ver" ] \
        || die "ML_VERSION is '$(cat "$srcroot/ML_VERSION")', expected $ver"
    [ -f "$srcroot/src/vcglib/vcg/complex/complex.h" ] \
        || die "vcglib is missing from the tarball (expected src/vcglib)"

    for prec in $PRECISIONS; do
        local suffix="" with_gui=0
        [ "$prec" = double ] && suffix=d
        # the GUI is float (MeshLab's release builds are): built in the float tree
        [ "$prec" = float ] && with_gui="$GUI"
        build_tree "$srcroot" "$layout" "$prec" "$with_gui" "$TMP/build-$prec"
        mkdir -p "$TMP/$prec/distrib"
        cp -a "$TREE_DISTRIB/libmeshlab-common.so" "$TREE_DISTRIB/plugins" "$TMP/$prec/distrib/"
        rm -f "$TMP/$prec/distrib/plugins/"*.a
        eigen_dir="${eigen_dir:-$TREE_EIGEN}"
        grep -q -x -- "-- MeshLab version: $ver$suffix" "$TMP/build-$prec.configure.log" \
            || die "configure log does not report MeshLab version $ver$suffix"
        printf 'MESHLAB_SCALAR=%s\nMESHLAB_VERSION=%s\n' "$prec" "$ver$suffix" \
            > "$TMP/$prec/PLUGIN_DEFINES"
        mv "$TMP/build-$prec.configure.log" "$TMP/$prec/configure-$prec.log"
        mv "$TMP/build-$prec.build.log" "$TMP/$prec/build-$prec.log"
        if [ "$with_gui" = 1 ]; then
            mkdir "$TMP/gui"
            install_gui "$TREE_DISTRIB" "$TMP/gui"
        fi
        rm -rf "$TMP/build-$prec"    # absolute paths inside would be wrong after the rename
    done

    # include dirs: <src>/src (meshlab-common's own PUBLIC dir: "common/..." includes),
    # vcglib and the system Eigen (vcglib prefers it; the dfsg tarball has no eigenlib).
    printf '%s\n' "$final/src/src" "$final/src/src/vcglib" "${eigen_dir:-/usr/include/eigen3}" \
        > "$TMP/INCLUDE_DIRS"
    printf '%s\n' "$ver" > "$TMP/VERSION"
    printf '%s\n' "$origin" > "$TMP/SOURCE"
    printf '%s\n' "$sha" > "$TMP/TARBALL_SHA256"
    date -u +%Y-%m-%dT%H:%M:%SZ > "$TMP/STAMP"

    chmod 755 "$TMP"             # mktemp -d made it 0700
    rm -rf "$final"              # a left-over without STAMP
    mv -T "$TMP" "$final"
    TMP=""
    BUILT_DIR="$final"
}

# add_gui DIR RECORD: the GUI for an SDK directory built without it (libraries untouched).
add_gui() {
    local final="$1" layout
    layout="$(sdk_field "$2" 5)"
    TMP="$(mktemp -d "$final/.tmp-gui.XXXXXX")"
    build_tree "$final/src" "$layout" float 1 "$TMP/build"
    mkdir "$TMP/gui"
    install_gui "$TREE_DISTRIB" "$TMP/gui"
    mv "$TMP/build.configure.log" "$TMP/build.build.log" "$TMP/gui/"
    chmod 755 "$TMP/gui"
    rm -rf "$final/gui"          # a left-over without STAMP
    mv -T "$TMP/gui" "$final/gui"
    rm -rf "$TMP"; TMP=""
}

for rec in "${CANDIDATES[@]}"; do
    ver="$(sdk_field "$rec" 1)"
    dir="$(sdk_dir "$rec")"
    lock_version "$rec"
    if [ -f "$dir/STAMP" ]; then
        if ! sdk_complete "$dir"; then
            t_start=$SECONDS
            log "adding the MeshLab $ver GUI to $dir"
            add_gui "$dir" "$rec"
            log "GUI built in $((SECONDS - t_start)) s"
        fi
        announce "$dir"; exit 0
    fi
    if [ "$ver" = 2025.07 ]; then suites="$SUITES_2025"; else suites="$SUITES_2022"; fi
    if fetch_tarball "$rec" "$suites"; then
        t_start=$SECONDS
        build_sdk "$rec" "$GOT_TARBALL" "$GOT_ORIGIN"
        log "built in $((SECONDS - t_start)) s"
        announce "$BUILT_DIR"; exit 0
    fi
    log "MeshLab $ver SDK not available, trying the next fallback"
done
die "no MeshLab SDK source could be obtained (tried: ${CANDIDATES[*]%%|*})"
