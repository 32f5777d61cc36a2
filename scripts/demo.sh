#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# The main job: smooths a noisy mesh with each of the three filters through Debian's real
# meshlabserver (MeshLab 2020.09) with the freshly built plugin, prints a table and writes
# before/after pictures. Set-up (packages, MeshLab sources, build) runs first, idempotently.
#
#   scripts/demo.sh [MESH.ply]     default: a generated noisy torus with its clean twin as truth
#
# Each filter runs with the defaults its dialog shows: the .mlx is written by MeshLab's own
# script writer from the plugin's parameter list, as the GUI's "Save Script" does.
# Outputs go to OUT_DIR (default <repo>/out/demo).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
out=${OUT_DIR:-$root/out/demo}

"$root/scripts/setup.sh"
"$root/scripts/ensure-packages.sh" f3d imagemagick fonts-dejavu-core

mkdir -p "$out"
if [ $# -ge 1 ]; then
  cp "$1" "$out/noisy.ply"
  truth=no
else
  python3 "$root/scripts/demo_mesh.py" gen "$out"
  truth=yes
fi

measure() {  # prints "rms_error_in_edges volume" (rms only against the generated torus)
  python3 "$root/scripts/demo_mesh.py" measure "$1"
}
read -r err0 vol0 < <(measure "$out/noisy.ply")

picture() {  # MESH.ply PNG TITLE
  xvfb-run -a f3d --output="$2.raw.png" --resolution=480,360 --up=+Z \
    --camera-elevation-angle=45 "$1" >/dev/null 2>&1
  convert "$2.raw.png" -font /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf -gravity north \
    -fill white -pointsize 18 -annotate +0+8 "$3" "$2"
  rm -f "$2.raw.png"
}
picture "$out/noisy.ply" "$out/0_noisy.png" "noisy input"

plugin=$build_dir/meshlab2020/plugins/libfilter_implicit_fairing.so
printf '\n%-46s %9s %9s %12s %14s\n' filter "time (s)" "CG iter." "volume (%)" "error (edges)"
printf '%-46s %9s %9s %12s %14s\n' "noisy input" - - - "$([ $truth = yes ] && echo "$err0" || echo -)"
i=1
for filter in "Implicit Fairing: Umbrella Diffusion" "Implicit Fairing: Scale-Dependent Diffusion" \
              "Implicit Fairing: Curvature Flow"; do
  name=$(echo "${filter#Implicit Fairing: }" | tr 'A-Z -' 'a-z__')
  QT_QPA_PLATFORM=offscreen "$build_dir/bin/gui_script_saver" "$plugin" "$out/$name.mlx" "$filter" \
    >/dev/null 2>&1
  start=$EPOCHREALTIME
  "$root/scripts/meshlabserver.sh" -i "$out/noisy.ply" -o "$out/$name.ply" -s "$out/$name.mlx" \
    > "$out/$name.log" 2>&1 || { echo "demo: $filter failed, see $out/$name.log" >&2; exit 1; }
  seconds=$(python3 -c "print($EPOCHREALTIME - $start)")
  iterations=$(sed -n 's/.*CG iterations in total: \([0-9]*\).*/\1/p' "$out/$name.log" | tail -1)
  read -r err vol < <(measure "$out/$name.ply")
  dvol=$(python3 -c "print('%+.2e' % (100 * ($vol - $vol0) / $vol0))")
  printf '%-46s %9.2f %9s %12s %14s\n' "$filter" "$seconds" "$iterations" "$dvol" \
    "$([ $truth = yes ] && echo "$err" || echo -)"
  picture "$out/$name.ply" "$out/${i}_$name.png" "${filter#Implicit Fairing: }"
  i=$((i + 1))
done
montage "$out"/[0-9]_*.png -tile 2x2 -geometry +2+2 -background '#333' "$out/before_after.png"
echo
echo "time: whole meshlabserver run (start-up, PLY load, filter, save); error: RMS distance of"
echo "the vertices to the clean torus in mean edge lengths; volume: change from the input."
echo "Meshes, logs and scripts: $out"
echo "Pictures: $out/before_after.png"
