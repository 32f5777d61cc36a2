#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# GUI smoke test of the plugin in Debian 12's real MeshLab 2020.09 under Xvfb:
# the plugin loads, Filters > Smoothing, Fairing and Deformation lists the three filters, the
# Curvature Flow dialog opens with its parameters, and Apply runs the filter (its log lines
# appear). The GUI is driven with xdotool; text is located on screenshots with tesseract.
# Screenshots are kept in WORK_DIR and their paths printed.
# Environment: WORK_DIR, BUILD_DIR, FAIRING_PLUGIN, REPO (set by CTest).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=${REPO:-$(cd "$here/../.." && pwd)}
work=${WORK_DIR:?}

if [ -z "${GUI_SMOKE_INNER:-}" ]; then
    for t in xvfb-run xdotool import convert tesseract python3; do
        command -v "$t" >/dev/null || { echo "FAIL: $t missing (run scripts/setup.sh)"; exit 1; }
    done
    rm -rf "$work"; mkdir -p "$work"
    GUI_SMOKE_INNER=1 exec xvfb-run -a -s "-screen 0 1600x1200x24" bash "$0" "$@"
fi

cd "$work"
ocr() { python3 "$here/ocr.py" "$@"; }
shot() { import -window root "$work/$1.png"; echo "screenshot: $work/$1.png"; }
meshlab_pid=
cleanup() { if [ -n "$meshlab_pid" ]; then kill "$meshlab_pid" 2>/dev/null || true; fi; }
trap cleanup EXIT
fail() { echo "FAIL: $*"; shot failure || true; echo "--- GUI output"; cat gui.log || true; exit 1; }

# click on TEXT found in region CROP (WxH+X+Y) of a fresh screenshot NAME (retries: menus take
# a moment to appear)
click_text() {
    local name=$1 text=$2 crop=$3 pos
    for _ in 1 2 3 4; do
        shot "$name" >/dev/null
        if pos=$(ocr "$work/$name.png" "$text" --crop "$crop"); then
            echo "click '$text' at $pos (screenshot: $work/$name.png)"
            # shellcheck disable=SC2086
            xdotool mousemove $pos; sleep 0.3; xdotool click 1
            return 0
        fi
        sleep 1
    done
    fail "'$text' not found on the screen"
}

python3 "$here/mltest.py" gen sphere "$work/sphere.ply"
FAIRING_FRESH_CONFIG=1 "$repo/scripts/meshlab.sh" "$work/sphere.ply" > gui.log 2>&1 &
meshlab_pid=$!

for _ in $(seq 60); do
    grep -q "All files opened" gui.log 2>/dev/null && break
    kill -0 "$meshlab_pid" 2>/dev/null || fail "MeshLab exited"
    sleep 0.5
done
grep -q "All files opened" gui.log || fail "MeshLab did not open the mesh"
grep -i "implicit_fairing" gui.log && fail "plugin loading problem" || true
sleep 2
shot start

menus=1100x1000+0+0
click_text menu-filters "Filters" 800x40+0+0
sleep 1
click_text menu-filters-open "Smoothing, Fairing and Deformation" $menus
sleep 1
shot menu-smoothing
ocr "$work/menu-smoothing.png" --crop $menus > menu-smoothing.txt
for f in "Implicit Fairing: Umbrella Diffusion" "Implicit Fairing: Scale-Dependent Diffusion" \
         "Implicit Fairing: Curvature Flow"; do
    grep -qF "$f" menu-smoothing.txt || { cat menu-smoothing.txt; fail "menu entry '$f' not found"; }
    echo "menu entry found: $f"
done
click_text menu-smoothing "Implicit Fairing: Curvature Flow" $menus

for _ in $(seq 20); do
    xdotool search --name "^Implicit Fairing: Curvature Flow\$" >/dev/null 2>&1 && break
    sleep 0.5
done
xdotool search --name "^Implicit Fairing: Curvature Flow\$" >/dev/null \
    || fail "the filter dialog did not open"
sleep 1
eval "$(xdotool search --name "^Implicit Fairing: Curvature Flow\$" getwindowgeometry --shell | head -n 5)"
dialog="${WIDTH}x${HEIGHT}+${X}+${Y}"
echo "dialog window: $dialog"
shot dialog
ocr "$work/dialog.png" --crop "$dialog" > dialog.txt
for t in "Time step" "automatic" "Operator order" "Affect only selection" "Preview"; do
    grep -qF "$t" dialog.txt || { cat dialog.txt; fail "dialog lacks '$t'"; }
    echo "dialog shows: $t"
done

click_text dialog "Apply" "$dialog"
for _ in $(seq 40); do
    grep -q "Vertices moved" gui.log && break
    sleep 0.5
done
grep -q "Vertices moved" gui.log || fail "Apply did not run the filter"
sleep 1
shot applied
echo "--- filter log in the GUI"
grep "LOG: 2" gui.log
echo "screenshots kept in $work: start.png menu-smoothing.png dialog.png applied.png"
echo PASS
