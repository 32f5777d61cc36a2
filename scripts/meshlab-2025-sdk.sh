#!/usr/bin/env bash
# Fetch and build the MeshLab 2025.07 plugin SDK (libraries only: meshlab-common and
# io_base) in float AND double precision into a versioned cache outside the repository.
#
# stdout: exactly one line, the SDK directory.  Progress and the SDK used go to stderr.
# Idempotent: when the SDK directory with its STAMP exists, nothing is fetched or built.
#
# Environment:
#   FAIRING_CACHE        cache root (default: $HOME/.cache/filter_implicit_fairing)
#   FAIRING_JOBS         parallel build jobs (default: 2)
#   FAIRING_MESHLAB_SDK  auto (default: 2025.07, else trixie's 2022.02), 2025.07 or 2022.02
#
# Layout of the SDK directory (see scripts/meshlab-2025-sdk.md):
#   src/                      unpacked orig tarball (MeshLab sources incl. src/vcglib)
#   float/distrib/            libmeshlab-common.so, plugins/libio_base.so ($ORIGIN RUNPATHs)
#   float/PLUGIN_DEFINES      compile definitions a plugin needs, one NAME=VALUE per line
#   double/...                the same for the double-precision build
#   INCLUDE_DIRS              include directories a plugin needs, one per line
#   VERSION, SOURCE, TARBALL_SHA256, STAMP (written last)
set -euo pipefail
shopt -s inherit_errexit

CACHE="${FAIRING_CACHE:-$HOME/.cache/filter_implicit_fairing}"
JOBS="${FAIRING_JOBS:-2}"
WANT="${FAIRING_MESHLAB_SDK:-auto}"

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
sdk_dir()   { printf '%s/meshlab-%s-%s-qt%s-gcc%s' "$CACHE" "$(sdk_field "$1" 1)" \
                  "$(sdk_field "$1" 3 | cut -c1-12)" "$QT_VER" "$GCC_MAJOR"; }

case "$WANT" in
    auto)    CANDIDATES=("$SDK_2025" "$SDK_2022") ;;
    2025.07) CANDIDATES=("$SDK_2025") ;;
    2022.02) CANDIDATES=("$SDK_2022") ;;
    *) die "FAIRING_MESHLAB_SDK must be auto, 2025.07 or 2022.02 (got '$WANT')" ;;
esac

announce() {   # $1 = SDK dir
    log "using MeshLab SDK $(cat "$1/VERSION") ($(cat "$1/SOURCE")): $1"
    if [ "$(cat "$1/VERSION")" != 2025.07 ]; then
        log "WARNING: fallback SDK, not 2025.07: plugins must use its API (e.g. RichAbsPerc) and MESHLAB_VERSION"
    fi
    printf '%s\n' "$1"
}

# Fast path: the preferred SDK is already built.
if [ -f "$(sdk_dir "${CANDIDATES[0]}")/STAMP" ]; then
    announce "$(sdk_dir "${CANDIDATES[0]}")"; exit 0
fi

mkdir -p "$CACHE/tarballs"
# The cache root is shared with other scripts: use only names of our own.
exec 9>"$CACHE/.lock-2025"
if ! flock -n 9; then
    log "waiting for another run to release $CACHE/.lock-2025"
    flock 9
fi
# Under the lock, our temp dirs can only be left-overs of killed runs.
rm -rf "$CACHE"/.tmp-meshlab-2025.07-* "$CACHE"/.tmp-meshlab-2022.02-* "$CACHE"/apt-2025/dl

# --- 2. fetching ---------------------------------------------------------------------------
APT_DIR="$CACHE/apt-2025"
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

BUILT_DIR=""
build_sdk() {   # $1 = SDK record, $2 = tarball, $3 = origin text; sets BUILT_DIR
    local rec="$1" tarball="$2" origin="$3" ver sha layout final top srcroot prec cmsrc eigen_dir=""
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

    for prec in float double; do
        local dbl=OFF suffix="" t0 opts
        [ "$prec" = double ] && { dbl=ON; suffix=d; }
        if [ "$layout" = new ]; then   # 2025.07: top-level CMakeLists.txt, MESHLAB_* options
            cmsrc="$srcroot"
            opts=(-DMESHLAB_BUILD_ONLY_LIBRARIES=ON -DMESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES=OFF
                  -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR="$dbl")
        else                           # 2022.02: CMakeLists.txt in src/, other option names
            cmsrc="$srcroot/src"
            opts=(-DBUILD_ONLY_MESHLAB_LIBRARIES=ON -DBUILD_WITH_DOUBLE_SCALAR="$dbl")
            # no MESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES yet; the dfsg tarball lacks parts
            # of some bundled libraries (u3d's zlib), so switch the optional ones off.
            local x
            for x in BOOST CGAL LEVMAR LIB3DS LIBE57_FORMAT LIBIGL MUPARSER NEWUOA NEXUS \
                     OPENCTM QHULL SSYNTH TINY_GLTF U3D XERCES; do
                opts+=("-DALLOW_BUNDLED_$x=OFF" "-DALLOW_SYSTEM_$x=OFF")
            done
        fi
        log "configuring the $prec build"
        t0=$SECONDS
        cmake -S "$cmsrc" -B "$TMP/build-$prec" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++ \
            -DCMAKE_BUILD_RPATH_USE_ORIGIN=ON \
            "${opts[@]}" -DMESHLAB_PLUGINS=meshlabplugins/io_base > "$TMP/configure-$prec.log" 2>&1 \
            || { tail -n 40 "$TMP/configure-$prec.log" >&2; die "cmake configure ($prec) failed"; }
        log "building meshlab-common and io_base ($prec, -j$JOBS)"
        cmake --build "$TMP/build-$prec" --target meshlab-common io_base -j "$JOBS" \
            > "$TMP/build-$prec.log" 2>&1 \
            || { tail -n 40 "$TMP/build-$prec.log" >&2; die "build ($prec) failed"; }
        log "$prec build done in $((SECONDS - t0)) s"

        local distrib
        distrib="$(dirname "$(find "$TMP/build-$prec" -name libmeshlab-common.so -print -quit)")"
        [ -f "$distrib/libmeshlab-common.so" ] && [ -f "$distrib/plugins/libio_base.so" ] \
            || die "build outputs not found in $TMP/build-$prec"
        mkdir -p "$TMP/$prec"
        cp -a "$distrib" "$TMP/$prec/distrib"
        # Eigen include dir the build used (vcglib takes the system Eigen: no eigenlib in dfsg)
        eigen_dir="$(grep -o -E -- '-I[^ ]*eigen[^ ]*' "$TMP/build-$prec/build.ninja" \
                     | grep -v vcglib | head -n1 | cut -c3- || true)"
        grep -q -x -- "-- MeshLab version: $ver$suffix" "$TMP/configure-$prec.log" \
            || die "configure log does not report MeshLab version $ver$suffix"
        printf 'MESHLAB_SCALAR=%s\nMESHLAB_VERSION=%s\n' "$prec" "$ver$suffix" \
            > "$TMP/$prec/PLUGIN_DEFINES"
        mv "$TMP/configure-$prec.log" "$TMP/build-$prec.log" "$TMP/$prec/"
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

for rec in "${CANDIDATES[@]}"; do
    ver="$(sdk_field "$rec" 1)"
    dir="$(sdk_dir "$rec")"
    if [ -f "$dir/STAMP" ]; then
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
