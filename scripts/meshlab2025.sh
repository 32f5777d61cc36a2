#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Open the real MeshLab 2025.07 GUI (built from Debian's source tarball into the cache by
# scripts/meshlab-2025-sdk.sh) with the freshly built float plugin, installing nothing:
#   scripts/meshlab2025.sh [mesh.ply ...]
# The filters are in Filters > Smoothing, Fairing and Deformation > Implicit Fairing: ...
# Needs a display; without one: xvfb-run -a scripts/meshlab2025.sh mesh.ply
#
# How MeshLab 2025.07 (and 2022.02) finds plugins (src/common/globals.cpp, mlapplication.cpp,
# meshlab/mainwindow_Init.cpp): first <folder of the binary>/plugins (the SDK's io_base), then the
# per-user folder QStandardPaths::AppDataLocation/MeshLabExtraPlugins/<version>/, which on Linux
# is $XDG_DATA_HOME/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07/. This script points
# XDG_DATA_HOME at a private folder of the build directory and links the plugin there.
# XDG_CONFIG_HOME points at a private folder too, whose settings
# (VCG/MeshLab_64bit_fp.conf) are pre-seeded: the first-start question about usage statistics
# is answered (informativeShown), and the online update check and the statistics are off
# (2025.07: two settings; 2022.02 has none, so its last check is dated in the far future).
#
# Environment:
#   BUILD_DIR        build directory (default <repo>/build)
#   FAIRING_MESHLAB  2025 (default) or 2022: the MeshLab 2022.02 GUI with the 2022.02 plugin
#   FAIRING_PLUGIN   the plugin (default $BUILD_DIR/meshlab<2025|2022>-float/plugins/
#                    libfilter_implicit_fairing.so)
#   MESHLAB_GUI      the meshlab binary (default: gui/distrib/meshlab of the SDK that
#                    scripts/meshlab-<2025|2022>-sdk.sh prints; built there if missing)
#   FAIRING_GUI_HOME the private folders' parent (default $BUILD_DIR/meshlab<2025|2022>-gui)
#   FAIRING_FRESH_CONFIG=1  wipe the private folders at each start (reproducible; the GUI test)
#   FAIRING_WINDOW_SIZE=WxH the main window's size at start (default: maximized)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
tag=${FAIRING_MESHLAB:-2025}
case "$tag" in
    2025) version=2025.07 ;;
    2022) version=2022.02 ;;
    *) echo "meshlab2025.sh: FAIRING_MESHLAB must be 2025 or 2022" >&2; exit 2 ;;
esac
plugin=${FAIRING_PLUGIN:-$build_dir/meshlab$tag-float/plugins/libfilter_implicit_fairing.so}
die() { echo "meshlab2025.sh: $*" >&2; exit 2; }

[ -f "$plugin" ] || die "plugin not built: $plugin (run scripts/setup.sh)"
if [ -z "${MESHLAB_GUI:-}" ]; then
    sdk=$("$root/scripts/meshlab-$tag-sdk.sh")    # 0.1 s when the cache is warm
    MESHLAB_GUI=$sdk/gui/distrib/meshlab
fi
[ -x "$MESHLAB_GUI" ] || die "no MeshLab $version GUI at $MESHLAB_GUI"
if [ -z "${DISPLAY:-}" ]; then
    die "no DISPLAY; run it as: xvfb-run -a $0 $*"
fi

home=${FAIRING_GUI_HOME:-$build_dir/meshlab$tag-gui}
if [ "${FAIRING_FRESH_CONFIG:-0}" = 1 ]; then
    rm -rf "$home"
fi
export XDG_DATA_HOME=$home/data XDG_CONFIG_HOME=$home/config
extra=$XDG_DATA_HOME/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/$version
mkdir -p "$extra" "$XDG_CONFIG_HOME/VCG"
ln -sfn "$(realpath "$plugin")" "$extra/libfilter_implicit_fairing.so"

# MeshLab's settings: QSettings, INI format. Global parameters are stored as the XML of their
# RichParameter (MainWindow::loadMeshLabSettings reads them back). Seeded once; MeshLab adds the
# rest at its first start.
conf=$XDG_CONFIG_HOME/VCG/MeshLab_64bit_fp.conf
if [ ! -f "$conf" ]; then
    param() {   # QSettings INI: key with ':' percent-encoded, value quoted with \" escapes
        printf 'MeshLab%%3A%%3ASystem%%3A%%3A%s="<Param name=\\"MeshLab::System::%s\\" type=\\"%s\\" value=\\"%s\\"/>"\n' \
            "$1" "$1" "$2" "$3"
    }
    {
        echo "[General]"
        echo "informativeShown=true"
        echo "dontRemindMeToSendEmail=true"
        # 2022.02 checks for updates and sends statistics, unconditionally, at the first start
        # of each day (MainWindow::showEvent): the last check is dated in the far future
        # (QDate's text format, which QDate::fromString reads back)
        echo "lastTimeMeshLabVersionCheckedOnStart=$(LC_ALL=C date -d 2999-12-31 '+%a %b %-d %Y')"
        param checkForUpdate RichBool false
        param sendAnonymousData RichBool false
        if [ -n "${FAIRING_WINDOW_SIZE:-}" ]; then
            param startupWindowWidth RichInt "${FAIRING_WINDOW_SIZE%x*}"
            param startupWindowHeight RichInt "${FAIRING_WINDOW_SIZE#*x}"
        fi
    } > "$conf"
fi
exec "$MESHLAB_GUI" "$@"
