#!/usr/bin/env bash
# Every X3D world of the corpus drawn by GhostSpace and by castle-model-viewer with the same
# camera, size and time, compared (issue 20: "static worlds match castle-model-viewer
# renders with the same camera; say how many match and why the others differ"):
#
#   tests/bench/x3d_vs_castle.sh BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIME]
#
# For each .x3d / .x3dv / .x3dz / .x3dvz file below ../shared/corpus/x3d: `ghostspace
# --snapshot --time TIME` and `view3dscene WORLD --screenshot TIME` (under xvfb-run), then
# BUILD_DIR/bin/compare_png --markdown (docs/castle-comparison.md's metric: `differ` at a
# tolerance of 16 of 255, and the background-masked `differ`, where pixels that show each
# program's own background count as equal: castle's default background is dark grey, ours
# VRML's black). Prints one markdown row per world and a summary: how many worlds are
# within 1% and 5% masked `differ`. A world either program cannot draw is listed as such.
# Both images stay in OUT_DIR (default: a temporary folder, removed) to be looked at.
# Needs view3dscene (Debian's castle-model-viewer) and xvfb-run. A measurement, not a test.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIME]}
top=$(cd "$(dirname "$0")/../.." && pwd)
corpus=$top/../shared/corpus/x3d
out=${2:-}
size=${3:-300x300}
time=${4:-0}
if [ -z "$out" ]; then
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
ghostspace=$build/bin/ghostspace
compare=$build/bin/compare_png
echo "| world | differ % | meanAbs | PSNR | masked differ % | masked PSNR | fg ours % | fg castle % |"
echo "|---|--:|--:|--:|--:|--:|--:|--:|"
within1=0
within5=0
total=0
failed=0
while IFS= read -r world; do
  name=${world#"$corpus"/}
  key=${name//\//__}
  total=$((total + 1))
  ours=$out/$key.ours.png
  theirs=$out/$key.castle.png
  timeout 60 "$ghostspace" --snapshot "$ours" --size "$size" --time "$time" --castle-camera "$world" \
    > /dev/null 2>&1 || true
  timeout 60 xvfb-run -a view3dscene "$world" --screenshot "$time" "$theirs" \
    --geometry "$size" > /dev/null 2>&1 || true
  if [ ! -s "$ours" ] || [ ! -s "$theirs" ]; then
    failed=$((failed + 1))
    echo "| $name | (not drawn by $([ -s "$ours" ] && echo castle || echo GhostSpace)) | | | | | | |"
    continue
  fi
  row=$("$compare" --markdown "$ours" "$theirs")
  echo "| $name | $row |"
  masked=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $4); print $4}')
  awk -v m="$masked" 'BEGIN { exit !(m <= 1.0) }' && within1=$((within1 + 1))
  awk -v m="$masked" 'BEGIN { exit !(m <= 5.0) }' && within5=$((within5 + 1))
done < <(find "$corpus" -type f \( -name '*.x3d' -o -name '*.x3dv' -o -name '*.x3dz' \
  -o -name '*.x3dvz' \) | LC_ALL=C sort)
echo
echo "$total worlds: masked differ <= 1%: $within1; <= 5%: $within5; not drawn by one program: $failed"
