#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# GUI test of the plugin in the real MeshLab 2025.07 (or 2022.02) application under Xvfb, started
# by scripts/meshlab2025.sh with a fresh, pre-seeded configuration. Three sessions:
#   1. noisy sphere: Filters > Smoothing, Fairing and Deformation lists the three filters; the
#      Curvature Flow dialog shows the documented defaults; Preview changes the mesh and
#      un-checking it restores it bit-identically; Apply writes the run's figures to the log.
#   2. non-manifold edge: Apply shows MeshLab's "Filter Failure" dialog with our message and
#      the mesh is unchanged.
#   3. a 1 M-face torus: the status bar's progress bar moves while the filter runs.
# "The mesh" is always what MeshLab itself saves (File > Export Mesh As, io_base): exports are
# compared byte for byte. The GUI is driven with xdotool; text is found with tesseract
# (tests/meshlab2020/ocr.py). Every wait polls a condition (window title, log line, OCR, file)
# with a deadline; screenshots are kept in WORK_DIR and their paths printed.
# Environment (set by CTest): WORK_DIR, REPO, MESHLAB_GUI, FAIRING_PLUGIN, FAIRING_MESHLAB
# (2025 or 2022), BUILD_DIR, FAIRING_GUI_HOME (scripts/meshlab2025.sh).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=${REPO:-$(cd "$here/../.." && pwd)}
work=${WORK_DIR:?}
tag=${FAIRING_MESHLAB:-2025}
export FAIRING_GUI_HOME=${FAIRING_GUI_HOME:-$work/home}   # MeshLab's private folders
version=2025.07
[ "$tag" = 2022 ] && version=2022.02

if [ -z "${GUI_TEST_INNER:-}" ]; then
    for t in xvfb-run xdotool import convert tesseract python3; do
        command -v "$t" >/dev/null || { echo "FAIL: $t missing (run scripts/setup.sh)"; exit 1; }
    done
    rm -rf "$work"; mkdir -p "$work"
    GUI_TEST_INNER=1 exec xvfb-run -a -s "-screen 0 1600x1200x24" bash "$0" "$@"
fi

cd "$work"
mkdir -p exports
ocr() { python3 "$repo/tests/meshlab2020/ocr.py" "$@"; }
mltest() { python3 "$repo/tests/meshlab2020/mltest.py" "$@"; }
probe() { python3 "$here/gui_probe.py" "$@"; }
shot() { import -window root "$work/$1.png"; echo "screenshot: $work/$1.png"; }
meshlab_pid=
session=
stop_gui() {
    if [ -n "$meshlab_pid" ]; then
        kill "$meshlab_pid" 2>/dev/null || true
        wait "$meshlab_pid" 2>/dev/null || true
        meshlab_pid=
    fi
}
trap stop_gui EXIT
fail() {
    echo "FAIL: $*"
    shot "failure-$session" || true
    echo "--- MeshLab output ($session)"; tail -n 40 "$session.log" 2>/dev/null || true
    exit 1
}

# wait_for DESCRIPTION SECONDS COMMAND...: poll COMMAND every 0.2 s until it succeeds
wait_for() {
    local what=$1 secs=$2; shift 2
    local deadline=$((SECONDS + secs))
    until "$@" >/dev/null 2>&1; do
        [ -z "$meshlab_pid" ] || kill -0 "$meshlab_pid" 2>/dev/null || fail "MeshLab exited while waiting for: $what"
        [ "$SECONDS" -lt "$deadline" ] || fail "timed out after ${secs} s waiting for: $what"
        sleep 0.2
    done
}
window() { xdotool search --onlyvisible --name "$1" | head -n 1; }
has_window() { [ -n "$(window "$1")" ]; }
geometry() {   # WxH+X+Y of the first visible window whose title matches $1
    local WINDOW X Y WIDTH HEIGHT SCREEN
    eval "$(xdotool getwindowgeometry --shell "$(window "$1")")"
    echo "${WIDTH}x${HEIGHT}+${X}+${Y}"
}
log_count() { grep -c -- "$1" "$session.log" || true; }
log_count_above() { [ "$(log_count "$1")" -gt "$2" ]; }

# click_text SHOT TEXT CROP: click the centre of TEXT, found by OCR in region CROP of a fresh
# screenshot (retried until it appears: menus and dialogs take a moment to draw)
found_at=
find_text() {
    shot "$1" >/dev/null
    found_at=$(ocr "$work/$1.png" "$2" --crop "$3")
}
click_text() {
    wait_for "'$2' on the screen" 30 find_text "$1" "$2" "$3"
    echo "click '$2' at $found_at (screenshot: $work/$1.png)"
    # shellcheck disable=SC2086
    xdotool mousemove $found_at
    sleep 0.2    # let the widget see the pointer enter before the press (hover state)
    xdotool click 1
}

main_title="^MeshLab $version"
# start_gui SESSION MESH: MeshLab with MESH, fresh configuration; waits until the mesh is open
start_gui() {
    session=$1
    FAIRING_FRESH_CONFIG=1 FAIRING_WINDOW_SIZE=1400x1000 MESHLAB_GUI="$MESHLAB_GUI" \
        FAIRING_MESHLAB="$tag" "$repo/scripts/meshlab2025.sh" "$2" > "$session.log" 2>&1 &
    meshlab_pid=$!
    wait_for "the MeshLab $version main window" 60 has_window "$main_title"
    # MeshLab's log lines are echoed on stderr as "LOG: <level> <text>"
    wait_for "MeshLab to open $(basename "$2")" 120 grep -q "^LOG: .*All files opened" "$session.log"
    if grep -q "Unable to load the following plugins\|libfilter_implicit_fairing" "$session.log"; then
        grep "plugin" "$session.log"; fail "a plugin did not load"
    fi
    # the settings were pre-seeded: no usage-statistics question
    if has_window "Send Anonymous Statistics"; then fail "the usage-statistics question was shown"; fi
    echo "session $session: MeshLab $version opened $(basename "$2") ($session.log)"
}

# open_filter SHOT FILTER: Filters > Smoothing, Fairing and Deformation > FILTER; waits for its
# dialog (a floating dock titled with the filter's name) and sets $dialog to its geometry
dialog=
open_filter() {
    local menus=1100x1000+0+0
    xdotool mousemove 700 500    # away from the menu bar (a hovered menu title stays open)
    click_text "$1-menu" "Filters" 800x60+0+0
    click_text "$1-menu-filters" "Smoothing, Fairing and Deformation" $menus
    click_text "$1-menu-smoothing" "$2" $menus
    wait_for "the '$2' dialog" 30 has_window "^$2\$"
    wait_for "the '$2' dialog to draw its buttons" 30 find_text "$1-dialog" "Apply" "$(geometry "^$2\$")"
    dialog=$(geometry "^$2\$")
    echo "dialog '$2': $dialog"
}

# export_mesh OUT: File > Export Mesh As (Ctrl+Shift+E), file name typed into Qt's file dialog,
# MeshLab's saving options accepted as they are (OK); waits until OUT is written
export_mesh() {
    local out=$1
    xdotool windowfocus --sync "$(window "$main_title")"
    xdotool key ctrl+shift+e
    wait_for "the export file dialog" 30 has_window '^Save ".*" Layer$'
    xdotool windowfocus --sync "$(window '^Save ".*" Layer$')"
    xdotool key ctrl+a
    xdotool type --delay 20 "$out"
    xdotool key Return
    wait_for "MeshLab's saving options" 30 has_window "^Choose Saving Options"
    xdotool windowfocus --sync "$(window "^Choose Saving Options")"
    xdotool key Return
    wait_for "$out to be written" 60 test -s "$out"
    wait_for "the saving options to close" 30 bash -c "! xdotool search --onlyvisible --name '^Choose Saving Options' | grep -q ."
    echo "exported $out ($(sha256sum "$out" | cut -c1-16))"
}

filters=("Implicit Fairing: Umbrella Diffusion" "Implicit Fairing: Scale-Dependent Diffusion"
         "Implicit Fairing: Curvature Flow")

# ---- 1. menu, dialog defaults, Preview, Apply ------------------------------------------------
mltest gen sphere "$work/sphere.ply"
start_gui sphere "$work/sphere.ply"
shot sphere-start
export_mesh "$work/exports/sphere-loaded.ply"
mltest compare "$work/sphere.ply" "$work/exports/sphere-loaded.ply"

open_filter sphere "Implicit Fairing: Curvature Flow"
# the submenu as it was when the entry was clicked
ocr "$work/sphere-menu-smoothing.png" --crop 1100x1000+0+0 > menu-smoothing.txt
for f in "${filters[@]}"; do
    grep -qF "$f" menu-smoothing.txt || { cat menu-smoothing.txt; fail "menu entry '$f' not found"; }
    echo "menu entry found: $f"
done
shot sphere-dialog
ocr "$work/sphere-dialog.png" --crop "$dialog" > dialog.txt
# labels and documented defaults (README "Parameters": curvature flow time step 0 = automatic,
# 4 steps, L2, implicit, open components None, boundary Automatic, tolerance 1e-8, 2000
# iterations): each value read on its label's row (a strip of the dialog at the label's height,
# OCR'd alone, so the page layout tesseract guesses cannot pair a label with another row's value)
read -r dw dh dx dy <<<"$(echo "$dialog" | tr 'x+' '  ')"
while IFS='|' read -r label value; do
    pos=$(ocr "$work/sphere-dialog.png" "$label" --crop "$dialog") \
        || { cat dialog.txt; fail "the dialog lacks the label '$label'"; }
    row=$(ocr "$work/sphere-dialog.png" --crop "${dw}x30+${dx}+$((${pos#* } - 15))")
    grep -qE -- " $value( |$)" <<<"$row" \
        || fail "the dialog's row '$row' does not show the default '$value' of '$label'"
    echo "default: $row"
done <<'EOF_DEFAULTS'
Time step|0
Smoothing steps|4
Operator order|L2 \(second order\)
Integration|Implicit
Open components|None
Boundary|Automatic
Solver tolerance|[1l]e-08
Max solver iterations|2000
EOF_DEFAULTS
for t in "Preserve volume" "Use vertex quality as smoothing weight" "Invert quality weight" \
         "Affect only selection" "Freeze operator" "Accept unconverged solves" "Preview" "Apply"; do
    grep -qF -- "$t" dialog.txt || { cat dialog.txt; fail "the dialog lacks '$t'"; }
done
if [ "$tag" = 2025 ]; then   # 2025.07's dialog also shows the pymeshlab name
    grep -qF "apply_coord_implicit_fairing_curvature_flow" dialog.txt \
        || { cat dialog.txt; fail "the dialog lacks the pymeshlab name"; }
fi
echo "dialog shows the documented defaults: $work/sphere-dialog.png"

applied() { log_count "Applied filter"; }
n=$(applied)
click_text sphere-dialog "Preview" "$dialog"
wait_for "the preview run" 120 log_count_above "Applied filter" "$n"
shot sphere-preview
export_mesh "$work/exports/sphere-preview.ply"
if cmp -s "$work/exports/sphere-loaded.ply" "$work/exports/sphere-preview.ply"; then
    fail "Preview did not change the mesh"
fi
mltest moved "$work/exports/sphere-loaded.ply" "$work/exports/sphere-preview.ply" 0.5
echo "Preview changed the mesh"

click_text sphere-preview-off "Preview" "$dialog"
export_mesh "$work/exports/sphere-preview-off.ply"
cmp "$work/exports/sphere-loaded.ply" "$work/exports/sphere-preview-off.ply" \
    || fail "un-checking Preview did not restore the mesh bit-identically"
echo "un-checking Preview restored the mesh bit-identically"

n=$(applied)
click_text sphere-apply "Apply" "$dialog"
wait_for "Apply to run the filter" 120 log_count_above "Applied filter" "$n"
for line in "Vertices moved: " "CG iterations in total: " "Volume of closed components: before " \
            "Time: "; do
    grep -q "^LOG: .*$line" sphere.log || fail "the log lacks '$line'"
done
echo "--- the filter's log"
grep "^LOG: " sphere.log | sed -n '/Curvature Flow: /,$p' | tail -n 20
shot sphere-applied
# the log pane shows the figures too (the layer dialog's log, at the main window's right edge,
# under the filter's dialog until that is closed)
click_text sphere-applied "Close" "$dialog"
wait_for "the dialog to close" 30 bash -c "! xdotool search --onlyvisible --name '^Implicit Fairing: Curvature Flow\$' | grep -q ."
wait_for "the figures in the log pane" 30 find_text sphere-log "CG iterations in total:" \
    "$(geometry "$main_title" | awk -F'[x+]' '{ printf "%dx%d+%d+%d", 480, $2, $3 + $1 - 480, $4 }')"
echo "the log pane shows the figures: $work/sphere-log.png"
export_mesh "$work/exports/sphere-applied.ply"
mltest moved "$work/exports/sphere-loaded.ply" "$work/exports/sphere-applied.ply" 0.5
stop_gui
# MeshLab read the pre-seeded settings (a value it could not read would have been rewritten
# with its default, true) and so never made up a statistics id
conf=$FAIRING_GUI_HOME/config/VCG/MeshLab_64bit_fp.conf
if [ "$tag" = 2025 ]; then   # 2022.02 has no such settings
    for p in checkForUpdate sendAnonymousData; do
        grep -q "System::$p.*value=.\"false" "$conf" || { cat "$conf"; fail "$conf: $p is not false"; }
    done
fi
# the id is created by the update check, which also sends the statistics
if grep -q "^UID=" "$conf"; then fail "MeshLab checked for updates (it created a statistics id)"; fi
echo "settings kept as seeded: no update check, no statistics ($conf)"

# ---- 2. refused input: MeshLab's error dialog with our message, mesh unchanged ---------------
mltest gen nonmanifold "$work/nonmanifold.ply"
start_gui nonmanifold "$work/nonmanifold.ply"
export_mesh "$work/exports/nonmanifold-loaded.ply"
open_filter nonmanifold "Implicit Fairing: Umbrella Diffusion"
click_text nonmanifold-dialog "Apply" "$dialog"
wait_for "MeshLab's 'Filter Failure' dialog" 60 has_window "^Filter Failure$"
wait_for "the error message on the screen" 30 find_text nonmanifold-error "non-manifold edge" \
    "$(geometry "^Filter Failure$")"
ocr "$work/nonmanifold-error.png" --crop "$(geometry "^Filter Failure$")" > error.txt
cat error.txt
for t in "Failure of filter" "Implicit Fairing: Umbrella Diffusion" "1 non-manifold edge (shared by three or more faces)" "Manifold Edges' filter (Filters > Cleaning and Repairing)"; do
    grep -qF "$t" error.txt || fail "the error dialog lacks '$t'"
done
echo "error dialog: $work/nonmanifold-error.png"
xdotool windowfocus --sync "$(window "^Filter Failure$")"
xdotool key Return
wait_for "the error dialog to close" 30 bash -c "! xdotool search --onlyvisible --name '^Filter Failure$' | grep -q ."
# MeshLab logs the failure once its message box is closed
wait_for "the failure in the log" 30 grep -q "^LOG: .*Umbrella Diffusion failed: 1 non-manifold edge" nonmanifold.log
export_mesh "$work/exports/nonmanifold-after.ply"
cmp "$work/exports/nonmanifold-loaded.ply" "$work/exports/nonmanifold-after.ply" \
    || fail "the refused filter changed the mesh"
echo "the refused filter left the mesh bit-identical"
stop_gui

# ---- 3. the progress bar moves on a 1 M-face mesh ------------------------------------------
probe torus "$work/torus1m.ply" 1000000
start_gui torus "$work/torus1m.ply"
open_filter torus "Implicit Fairing: Curvature Flow"
# the status bar's right end holds the progress bar; look only right of the filter's dialog
eval "$(xdotool getwindowgeometry --shell "$(window "$main_title")")"
dialog_right=$(echo "$dialog" | awk -F'[x+]' '{ print $1 + $3 }')
left=$((X + WIDTH - 700 > dialog_right ? X + WIDTH - 700 : dialog_right))
bar="$((X + WIDTH - left))x40+$left+$((Y + HEIGHT - 40))"
echo "progress bar region: $bar"
shot torus-before
before=$(probe bar "$work/torus-before.png" "$bar")
n=$(log_count "Applied filter")
click_text torus-dialog "Apply" "$dialog"
seen=()
k=0
deadline=$((SECONDS + 300))
while ! log_count_above "Applied filter" "$n"; do
    kill -0 "$meshlab_pid" 2>/dev/null || fail "MeshLab exited during the filter"
    [ "$SECONDS" -lt "$deadline" ] || fail "the filter did not finish within 300 s"
    import -window root "$work/torus-run.png"
    c=$(probe bar "$work/torus-run.png" "$bar")
    if [ "$c" -gt "$before" ] && [[ " ${seen[*]} " != *" $c "* ]]; then
        seen+=("$c"); k=$((k + 1))
        cp "$work/torus-run.png" "$work/torus-progress-$k.png"
        echo "progress bar: $c highlighted pixels (screenshot: $work/torus-progress-$k.png)"
    fi
done
[ "${#seen[@]}" -ge 2 ] || fail "the progress bar showed ${#seen[@]} distinct states (want >= 2): ${seen[*]}"
[ "${seen[-1]}" -gt "${seen[0]}" ] || fail "the progress bar did not grow: ${seen[*]}"
echo "the progress bar moved through ${#seen[@]} states on the 1 M-face torus"
grep "^LOG: .*Time: " torus.log | tail -n 1
stop_gui

rm -f "$work"/*.ocr.png "$work/torus-run.png"    # OCR intermediates and the polling shot
echo "screenshots kept in $work:"
ls "$work"/*.png | sed 's/^/  /'
echo PASS
