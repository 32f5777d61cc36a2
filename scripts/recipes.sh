#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
# Feature-preserving recipes (docs/feature-preserving.md): smooths a noisy CAD-like part through
# Debian's real meshlabserver (MeshLab 2020.09) with per-vertex weights or a selection made by
# MeshLab's own stock filters, then our Curvature Flow filter; measures each result against
# the clean part and renders a picture per recipe.
#
#   scripts/recipes.sh [--out DIR]     default DIR: $BUILD_DIR/recipes
#   scripts/recipes.sh --docs          also copies the pictures to docs/img/recipe_*.png and the
#                                      scripts to docs/recipes/recipe_*.mlx
#
# Needs the built plugin (scripts/setup.sh). Writes DIR/figures.json (one object per recipe,
# from scripts/recipes_mesh.py measure), DIR/figures.md (the table) and DIR/recipe_*.png.
# About 20 s on a 2-core machine.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
out=$build_dir/recipes
docs=no
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --docs) docs=yes; shift ;;
    *) echo "usage: scripts/recipes.sh [--out DIR] [--docs]" >&2; exit 2 ;;
  esac
done
"$root/scripts/ensure-packages.sh" f3d imagemagick fonts-dejavu-core python3-numpy xvfb xauth
py=/usr/bin/python3   # Debian's, with python3-numpy
mesh() { "$py" "$root/scripts/recipes_mesh.py" "$@"; }

# every file below is rewritten; nothing else in DIR is touched
mkdir -p "$out/mlx"
mesh gen "$out" --noise 0.1
"$py" "$root/scripts/recipes_mlx.py" "$out/mlx"

font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
render() {  # MESH.ply PNG TITLE [f3d options]: one 400x250 panel with a caption
  local mesh=$1 png=$2 title=$3
  shift 3
  xvfb-run -a f3d --output="$png.raw.png" --resolution=400,250 --up=+Z \
    --camera-position=4.3,-2.2,2.6 --camera-focal-point=1.7,0.5,0.8 "$@" "$mesh" >/dev/null 2>&1
  convert "$png.raw.png" -font "$font" -gravity north -fill white -pointsize 15 \
    -annotate +0+6 "$title" "$png"
  rm -f "$png.raw.png"
}
pair() {  # LEFT.png RIGHT.png OUT.png: side by side, palette PNG (small)
  montage "$1" "$2" -tile 2x1 -geometry +2+2 -background '#333' -colors 128 "PNG8:$3"
}

printf '[\n' > "$out/figures.json"
first=yes
record() {  # NAME TITLE MESH
  local m
  m=$(mesh measure "$out/clean.ply" "$out/noisy.ply" "$3")
  [ $first = yes ] || printf ',\n' >> "$out/figures.json"
  first=no
  printf '{"recipe": "%s", "title": "%s", %s' "$1" "$2" "${m#\{}" >> "$out/figures.json"
}
record noisy "noisy input (0.1 edge)" "$out/noisy.ply"

declare -A short=([uniform]="filter alone" [selection]="crease selection"
                  [geodesic]="geodesic weights" [curvature]="curvature weights")
declare -A title=(
  [uniform]="our filter alone"
  [selection]="crease selection, inverted + Affect only selection"
  [geodesic]="geodesic distance from the creases as weight"
  [curvature]="RMS curvature as weight, inverted")
declare -A weights=([selection]=unmoved [geodesic]=quality [curvature]=inverted)
for r in uniform selection geodesic curvature; do
  "$root/scripts/meshlabserver.sh" -i "$out/noisy.ply" -o "$out/$r.ply" -m vq \
    -s "$out/mlx/recipe_$r.mlx" > "$out/$r.log" 2>&1 \
    || { echo "recipes: $r failed, see $out/$r.log" >&2; exit 1; }
  record "$r" "${title[$r]}" "$out/$r.ply"
  render "$out/$r.ply" "$out/$r.result.png" "${short[$r]}: result"
  if [ "$r" = uniform ]; then
    render "$out/noisy.ply" "$out/$r.left.png" "noisy input (0.1 edge)"
  else
    mesh paint "$out/$r.ply" "$out/$r.paint.ply" "${weights[$r]}" "$out/noisy.ply"
    render "$out/$r.paint.ply" "$out/$r.left.png" "${short[$r]}: weight, red 0 (fixed) to grey 1" \
      -s --comp=-2
  fi
  pair "$out/$r.left.png" "$out/$r.result.png" "$out/recipe_$r.png"
  rm -f "$out/$r.left.png" "$out/$r.result.png"
done
printf '\n]\n' >> "$out/figures.json"

"$py" - "$out/figures.json" > "$out/figures.md" <<'EOF'
import json, sys
rows = json.load(open(sys.argv[1]))
print("| recipe | error (edges) | flat | crease | bump | crease sharpness | normal error "
      "| crease vertices kept |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for r in rows:
    print("| %s | %.4f | %.4f | %.4f | %.4f | %.1f %% | %.2f° | %.1f %% |" % (
        r["title"], r["rms_edges"], r["rms_flat"], r["rms_crease"], r["rms_bump"],
        r["crease_sharpness_pct"], r["normal_error_deg"], r["crease_unmoved_pct"]))
EOF
cat "$out/figures.md"

if [ $docs = yes ]; then
  mkdir -p "$root/docs/img" "$root/docs/recipes"
  for r in uniform selection geodesic curvature; do
    cp "$out/recipe_$r.png" "$root/docs/img/recipe_$r.png"
    cp "$out/mlx/recipe_$r.mlx" "$root/docs/recipes/recipe_$r.mlx"
  done
  echo "copied the pictures to docs/img/ and the scripts to docs/recipes/"
fi
