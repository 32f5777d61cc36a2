#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The Debian package, installed for real (label package; RUN_SERIAL: it changes the system).
# Builds the .deb (scripts/package.sh), checks it with lintian when installed (errors fail),
# `apt-get install ./implicit-fairing_*.deb`, then uses only the INSTALLED files:
#   /usr/bin/meshlabserver -d lists our three filters; an .mlx smoothing through it;
#   /usr/bin/implicit-fairing --help, --version and a smoothing that gives meshlabserver's result;
#   man -w finds the page;
# then `apt-get purge` and checks that no path of ours is left. The system is restored on any
# exit (trap): the package purged, packages apt pulled in purged, files it overwrote put back.
# Exit 77 (skipped) when not root or when implicit-fairing was installed before the test.
# Environment (set by CMake): REPO, BUILD_DIR, WORK_DIR.
set -euo pipefail
repo=${REPO:?}
work=${WORK_DIR:?}
pkg=implicit-fairing
mltest() { python3 "$repo/tests/meshlab2020/mltest.py" "$@"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
apt_get() {
    # other apt users on the machine: wait for the lock instead of failing
    DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=300 -y -q "$@"
}
installed() { dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null | grep -qx installed; }

if [ "$(id -u)" -ne 0 ]; then
    echo "SKIP: installs and removes a Debian package system-wide; run as root (CI does)"
    exit 77
fi
if installed "$pkg" || [ "$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null)" = config-files ]; then
    echo "SKIP: $pkg is already on this system ($(dpkg-query -W -f='${Version}' "$pkg")); the test" \
         "would remove it. Remove it first: apt-get purge $pkg"
    exit 77
fi
for p in meshlab xvfb xauth man-db python3; do
    installed "$p" || fail "package $p missing (scripts/setup.sh installs it)"
done

rm -rf "$work"; mkdir -p "$work/backup" "$work/config"; cd "$work"

# --- the .deb ------------------------------------------------------------------------------
deb=$(BUILD_DIR=${BUILD_DIR:?} "$repo/scripts/package.sh")
echo "package: $deb"
dpkg-deb --info "$deb" | sed -n '/Package:/,$p'
if command -v lintian >/dev/null; then
    echo "--- lintian (errors fail the test; warnings and notes are reported)"
    set +e
    lintian --info --display-info --fail-on error "$deb" > lintian.txt 2>&1
    lintian_rc=$?
    set -e
    grep -v "running with root privileges" lintian.txt || echo "(no tags)"
    [ "$lintian_rc" -eq 0 ] || fail "lintian reported errors (exit status $lintian_rc)"
fi
depends=$(dpkg-deb -f "$deb" Depends)
case "$depends" in *"meshlab (>= 2020.09+dfsg1-2), meshlab (<< 2020.09+dfsg1-3~)"*) ;;
    *) fail "Depends lacks the MeshLab 2020.09+dfsg1-2 bounds: $depends" ;; esac

# --- install, with everything needed to undo it ----------------------------------------------
# Paths the package holds, which of them existed before (an earlier `cmake --install` leaves
# unowned files that dpkg would overwrite and then delete), and the packages installed now.
mapfile -t deb_paths < <(dpkg-deb --fsys-tarfile "$deb" | tar -t | sed -e 's|^\./|/|' -e 's|/$||' \
                         | grep -v '^/\?$')
: > existed_before
for p in "${deb_paths[@]}"; do
    if [ -e "$p" ]; then
        echo "$p" >> existed_before
        if [ -f "$p" ]; then mkdir -p "backup$(dirname "$p")"; cp -a "$p" "backup$p"; fi
    fi
done
cp "$deb" "$work/"   # apt's _apt user must be able to read it
deb_file=./$(basename "$deb")
chmod 0644 "$deb_file"; chmod 0755 "$work"
# What apt would install along with ours (nothing when meshlab is there): only those are purged
# afterwards. Never a before/after difference of the package list: other users of the machine
# may install packages meanwhile.
apt_get install --simulate "$deb_file" | awk '$1 == "Inst" {print $2}' | grep -vx "$pkg" \
    > pulled || true
[ ! -s pulled ] || echo "apt will also install: $(tr '\n' ' ' < pulled)"

# The script's own output, for the clean-up: a signal may arrive inside a redirected function.
exec 3>&1 4>&2
cleanup() {
    local rc=$?
    set +e
    exec 1>&3 2>&4
    if installed "$pkg" || dpkg-query -W "$pkg" >/dev/null 2>&1; then
        echo "cleanup: purging $pkg"
        apt_get purge "$pkg" >/dev/null
    fi
    # the dependencies apt pulled in for us, if still marked automatic (nobody asked for them)
    local p
    while read -r p; do
        if apt-mark showauto "$p" | grep -qx "$p"; then
            echo "cleanup: purging $p, installed by apt for $pkg"
            apt_get purge "$p" >/dev/null
        fi
    done < pulled
    if [ -d backup ] && [ -n "$(find backup -type f -print -quit)" ]; then
        echo "cleanup: restoring files that were there before the test:"
        (cd backup && find . -type f | sed 's|^\.||') | while read -r f; do
            mkdir -p "$(dirname "$f")"; cp -a "backup$f" "$f"; echo "  $f"
        done
    fi
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

echo "--- apt-get install $deb_file"
apt_get install "$deb_file" | tail -n 3
installed "$pkg" || fail "$pkg is not installed after apt-get install"
dpkg -L "$pkg" | grep -vx '/\.' | sort > files_installed
for f in /usr/bin/implicit-fairing /usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_implicit_fairing.so \
         /usr/share/man/man1/implicit-fairing.1.gz /usr/share/doc/implicit-fairing/copyright \
         /usr/share/doc/implicit-fairing/changelog.Debian.gz; do
    grep -qx "$f" files_installed || fail "dpkg -L $pkg does not list $f"
    [ -f "$f" ] || fail "$f not on disk after the install"
done
echo "installed: $(grep -c . files_installed) paths, $(wc -l < existed_before) of them there before"

# --- the installed meshlabserver: the filters are listed and one runs ------------------------
# Debian's meshlabserver loads plugins from /usr/lib/x86_64-linux-gnu/meshlab/plugins only.
server() {
    # timeout: fail (and clean up) before CTest's own time limit kills the script
    XDG_CONFIG_HOME="$work/config" timeout 300 \
        xvfb-run -a -s "-screen 0 1280x1024x24" /usr/bin/meshlabserver "$@"
}
server -d dump.txt > dump.log 2>&1 || { cat dump.log; fail "meshlabserver -d exited non-zero"; }
for f in "Implicit Fairing: Umbrella Diffusion" "Implicit Fairing: Scale-Dependent Diffusion" \
         "Implicit Fairing: Curvature Flow"; do
    grep -q "^\\\\section f[0-9]* $f *\$" dump.txt || fail "installed meshlabserver does not list '$f'"
    echo "meshlabserver -d: lists '$f'"
done

mltest gen sphere in.ply
mltest mlx run.mlx curvature_flow timeStep=5 stepSmoothNum=2
server -i in.ply -o server.ply -s run.mlx > server.log 2>&1 \
    || { cat server.log; fail "meshlabserver exited non-zero"; }
! grep -q "^Problem with filter" server.log || { cat server.log; fail "the filter failed"; }
[ -s server.ply ] || { cat server.log; fail "meshlabserver wrote no output"; }
mltest moved in.ply server.ply

# --- the installed command-line tool --------------------------------------------------------
[ "$(command -v implicit-fairing)" = /usr/bin/implicit-fairing ] \
    || fail "implicit-fairing on PATH is $(command -v implicit-fairing), not /usr/bin/implicit-fairing"
/usr/bin/implicit-fairing --help > help.txt || fail "implicit-fairing --help exited non-zero"
grep -q "^Usage: implicit-fairing" help.txt || fail "--help has no usage line"
version=$(/usr/bin/implicit-fairing --version)
[ "$version" = "implicit-fairing $(dpkg-query -W -f='${Version}' "$pkg" | sed 's/-[^-]*$//')" ] \
    || fail "--version says '$version', the package is $(dpkg-query -W -f='${Version}' "$pkg")"
/usr/bin/implicit-fairing in.ply cli.ply --operator curvature --time-step 5 --steps 2 --json \
    > cli.json \
    || fail "implicit-fairing exited non-zero"
python3 - <<'EOF' || fail "implicit-fairing --json"
import json
r = json.load(open("cli.json"))
assert r["vertices"] > 0 and r["operator"].startswith("curvature"), r
print("implicit-fairing: %d vertices, %d CG iterations, volume %.9g -> %.9g"
      % (r["vertices"], r["cg_iterations"], r["volume_before"], r["volume_after"]))
EOF
# Same engine, same parameters: the CLI and the installed plugin agree to float rounding.
mltest compare server.ply cli.ply

# --- the man page ---------------------------------------------------------------------------
page=$(man -w implicit-fairing) || fail "man -w implicit-fairing finds no page"
[ "$page" = /usr/share/man/man1/implicit-fairing.1.gz ] || fail "man -w gives $page"
MANWIDTH=100 man -P cat implicit-fairing 2> man.err | grep -q -- "--time-step" \
    || fail "the rendered man page lacks --time-step"
[ ! -s man.err ] || { cat man.err; fail "man reported problems rendering the page"; }
echo "man: $page"

# --- removal leaves nothing of ours --------------------------------------------------------
echo "--- apt-get purge $pkg"
apt_get purge "$pkg" | tail -n 2
! installed "$pkg" || fail "$pkg still installed after purge"
! dpkg-query -W "$pkg" >/dev/null 2>&1 || fail "dpkg still knows $pkg after purge"
left=0
while read -r p; do
    grep -qx "$p" existed_before && [ -d "$p" ] && continue   # a folder shared with others
    if [ -e "$p" ] || [ -L "$p" ]; then echo "left behind: $p"; left=$((left + 1)); fi
done < files_installed
[ "$left" -eq 0 ] || fail "$left paths of the package remain after purge"
echo "purge: none of the $(grep -c . files_installed) paths of the package remain"
echo "PASS"
