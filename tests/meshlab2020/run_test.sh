#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# One MeshLab 2020.09 integration test (registered in CTest by CMakeLists.txt, label meshlab2020).
#   run_test.sh run FILTER MESH [--quality MODE] [--select-x-gt V] [name=value ...]
#       generated noisy MESH -> real meshlabserver with an .mlx listing every parameter ->
#       compared with engine_reference run on the same file (float rounding at most)
#   run_test.sh old-labels FILTER MESH [name=value ...]   the same with a script that carries
#       the enum labels of version 0.1.0
#   run_test.sh quality-fixed FILTER          quality 0 vertices stay bit-identical
#   run_test.sh selection FILTER              stock selection filter + "Affect only selection"
#   run_test.sh failure                       non-manifold input: non-zero exit, input unchanged
#   run_test.sh unsaved                       output cannot be written: non-zero exit
#   run_test.sh dump                          meshlabserver -d lists filters and parameters
#   run_test.sh gui-script FILTER [name=value ...]   script saved the GUI's way replays headless
# Environment (set by CMake): BUILD_DIR, WORK_DIR, ENGINE_REFERENCE, GUI_SCRIPT_SAVER,
# FAIRING_PLUGIN, REPO.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=${REPO:-$(cd "$here/../.." && pwd)}
mltest() { python3 "$here/mltest.py" "$@"; }
server() { "$repo/scripts/meshlabserver.sh" "$@"; }
work=${WORK_DIR:?}
rm -rf "$work"; mkdir -p "$work"; cd "$work"

declare -A MENU=(
    [umbrella]="Implicit Fairing: Umbrella Diffusion"
    [scale_dependent]="Implicit Fairing: Scale-Dependent Diffusion"
    [curvature_flow]="Implicit Fairing: Curvature Flow")

# run FILTER MESH [--quality MODE] [--select-x-gt V] [params...]: meshlabserver vs reference
run_case() {
    local filter=$1 mesh=$2; shift 2
    local quality=none sel=()
    while [ $# -gt 0 ]; do
        case $1 in
            --quality) quality=$2; shift 2 ;;
            --select-x-gt) sel=(--select-x-gt "$2"); shift 2 ;;
            *) break ;;
        esac
    done
    mltest gen "$mesh" in.ply --quality "$quality"
    mltest mlx run.mlx "$filter" "${sel[@]}" "${mlx_opts[@]}" "$@"
    echo "--- script"; cat run.mlx
    local mask=()
    [ "$quality" != none ] && mask=(-m vq)
    echo "--- meshlabserver"
    server -i in.ply -o out.ply "${mask[@]}" -s run.mlx
    echo "--- engine_reference"
    # every parameter exactly as the script gives it to MeshLab
    local params
    mapfile -t params < <(mltest mlxparams run.mlx)
    "$ENGINE_REFERENCE" in.ply ref.ply "$filter" "${sel[@]}" "${params[@]}"
    mltest compare out.ply ref.ply
}

mlx_opts=()
case ${1:?case} in
old-labels)
    # a script saved with the labels of version 0.1.0 ("L² (second order, recommended)") still
    # runs, and means what it meant: MeshLab reads the index, not the label
    shift
    mlx_opts=(--old-labels)
    run_case "$@"
    grep -q 'enum_val1="L² (second order, recommended)"' run.mlx \
        || { echo "FAIL: the script does not carry the old label"; exit 1; }
    mltest moved in.ply out.ply
    ;;
run)
    shift
    run_case "$@"
    # quality weights or a selection fix some vertices on purpose
    case " $* " in *" --quality "*|*" --select-x-gt "*) mltest moved in.ply out.ply 0.25 ;;
                   *) mltest moved in.ply out.ply ;; esac
    ;;
quality-fixed)
    run_case "$2" grid --quality halfx qualityWeights=true
    mltest fixed in.ply out.ply --quality-zero
    ;;
selection)
    run_case "$2" sphere --select-x-gt 0.25 Selected=true
    mltest fixed in.ply out.ply --x-le 0.25
    ;;
failure)
    mltest gen nonmanifold in.ply
    mltest mlx run.mlx umbrella
    before=$(sha256sum in.ply | cut -d' ' -f1)
    set +e
    server -i in.ply -o out.ply -s run.mlx > server.log 2>&1
    rc=$?
    set -e
    cat server.log
    after=$(sha256sum in.ply | cut -d' ' -f1)
    [ "$rc" -ne 0 ] || { echo "FAIL: exit status 0 on a non-manifold mesh"; exit 1; }
    [ "$before" = "$after" ] || { echo "FAIL: the input file changed"; exit 1; }
    [ ! -e out.ply ] || { echo "FAIL: an output was written"; exit 1; }
    grep -qi "non-manifold\|nonmanifold" server.log \
        || { echo "FAIL: the error message does not name the problem"; exit 1; }
    # the repair filter by its menu entry in this MeshLab (2020.09's name)
    grep -qF "run MeshLab's 'Repair non Manifold Edges by removing faces' filter (Filters > Cleaning and Repairing) first" server.log \
        || { echo "FAIL: the error message does not name 2020.09's repair filter"; exit 1; }
    echo "failure: exit status $rc, input unchanged, no output, message:"
    grep -i "failed:" server.log || true
    ;;
unsaved)
    # meshlabserver exits 0 when it cannot save: the wrapper must not
    mltest gen sphere in.ply
    mltest mlx run.mlx umbrella
    set +e
    server -i in.ply -o "$work/no/such/dir/out.ply" -s run.mlx > server.log 2>&1
    rc=$?
    set -e
    tail -n 3 server.log
    [ "$rc" -ne 0 ] || { echo "FAIL: exit status 0 although nothing was saved"; exit 1; }
    echo "unsaved: exit status $rc"
    ;;
dump)
    server -d dump.txt
    for f in "${MENU[@]}"; do
        grep -q "^\\\\section f[0-9]* $f *\$" dump.txt || { echo "FAIL: '$f' not listed"; exit 1; }
    done
    python3 - "$here" <<'EOF'
import re, sys
text = open("dump.txt", encoding="utf-8").read()
descs = ["Time step (0 = automatic)", "Smoothing steps", "Operator order", "Integration",
         "Preserve volume", "Open components", "Boundary", "Use vertex quality as smoothing weight",
         "Invert quality weight", "Affect only selection", "Solver tolerance",
         "Max solver iterations", "Freeze operator", "Accept unconverged solves"]
for name in ["Umbrella Diffusion", "Scale-Dependent Diffusion", "Curvature Flow"]:
    m = re.search(r"\\section f\d+ Implicit Fairing: " + name + r" *\n(.*?)</TABLE>", text, re.S)
    if not m:
        print("FAIL: no section for " + name); sys.exit(1)
    body = m.group(1)
    for d in descs:
        if "<TD> %s </TD>" % d not in body:
            print("FAIL: %s lacks parameter '%s'" % (name, d)); sys.exit(1)
    if "Desbrun" not in body:
        print("FAIL: %s does not cite the paper" % name); sys.exit(1)
    print("dump: %s lists all %d parameters" % (name, len(descs)))
EOF
    ;;
gui-script)
    filter=$2; shift 2
    QT_QPA_PLATFORM=offscreen "$GUI_SCRIPT_SAVER" "$FAIRING_PLUGIN" gui.mlx "${MENU[$filter]}" "$@"
    echo "--- script as the GUI saves it"; cat gui.mlx
    mltest gen sphere in.ply
    server -i in.ply -o out.ply -s gui.mlx
    # the reference gets exactly the values the saved script holds (defaults included)
    mapfile -t saved < <(mltest mlxparams gui.mlx)
    echo "parameters in the saved script: ${saved[*]}"
    [ "${#saved[@]}" -eq 14 ] || { echo "FAIL: expected 14 parameters in the saved script"; exit 1; }
    "$ENGINE_REFERENCE" in.ply ref.ply "$filter" "${saved[@]}"
    mltest compare out.ply ref.ply
    mltest moved in.ply out.ply
    ;;
*)
    echo "unknown case $1"; exit 2 ;;
esac
echo PASS
