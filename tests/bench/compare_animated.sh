#!/usr/bin/env bash
# Compares our frames of the corpus's animated worlds with castle-model-viewer's
# (view3dscene) at the same SFTime and prints a markdown table (docs/runtime-comparison.md).
#
#   tests/bench/compare_animated.sh                # from the project root
#   BUILD=build-cmp OUT=/tmp/anim-cmp tests/bench/compare_animated.sh [WORLD.wrl ...]
#
# Worlds: every .wrl below $CORPUS/freewrl and $CORPUS/castle-animation that has a
# TimeSensor and a ROUTE and no Script node (castle-model-viewer has no ECMAScript), or the
# worlds given as arguments. Times: 0.325 and 0.675 of the world's first cycleInterval
# (1.3 s and 2.7 s for the common 4 s cycle), i.e. mid-cycle and away from the
# interpolators' usual keys 0, 0.5, 1.
#
# Each world is drawn at 300x300 by
#   $BUILD/bin/ghostspace --snapshot ours.png --size 300x300 --time T WORLD
#   xvfb-run -a view3dscene WORLD --screenshot T castle.png --geometry 300x300
# and the two PNGs are compared by $BUILD/bin/compare_png (render::compareImages, channel
# tolerance 16, and the background-masked variant of docs/castle-comparison.md).
#
# Worlds without a Viewpoint are drawn twice: as they are (castle then frames the whole
# scene while we use the VRML97 default viewpoint), and as a copy with
# `Viewpoint { }` (the default viewpoint, 0 0 10) inserted after the header, camera "VP",
# so that both browsers use the same camera. The copy lives in $OUT next to symbolic links
# to everything in the world's folder, so relative URLs still resolve.
#
# Environment: BUILD (default build-cmp), OUT (default /tmp/gs-animated-cmp, keeps every
# PNG and the logs), CORPUS (default ../shared/corpus/vrml), SIZE (default 300x300).
set -u

BUILD=${BUILD:-build-cmp}
OUT=${OUT:-/tmp/gs-animated-cmp}
CORPUS=${CORPUS:-../shared/corpus/vrml}
SIZE=${SIZE:-300x300}
GHOSTSPACE=$BUILD/bin/ghostspace
COMPARE=$BUILD/bin/compare_png

for tool in "$GHOSTSPACE" "$COMPARE"; do
  [ -x "$tool" ] || { echo "missing $tool (build targets ghostspace and compare_png)" >&2; exit 2; }
done
command -v view3dscene > /dev/null || { echo "view3dscene not installed" >&2; exit 2; }
command -v xvfb-run > /dev/null || { echo "xvfb-run not installed" >&2; exit 2; }
mkdir -p "$OUT"

# The world's text without comments (a '#' outside a string starts one; good enough here).
strip_comments() { sed 's/#.*//' "$1"; }

is_candidate() {
  local text
  text=$(strip_comments "$1")
  grep -qw TimeSensor <<< "$text" && grep -qw ROUTE <<< "$text" && ! grep -qw Script <<< "$text"
}

first_cycle_interval() {
  local ci
  ci=$(strip_comments "$1" | grep -o 'cycleInterval[[:space:]]*[0-9.eE+-]*' | head -n 1 |
       awk '{print $2}')
  echo "${ci:-1}"
}

has_viewpoint() { strip_comments "$1" | grep -qw Viewpoint; }

# Short automatic facts for the remark column.
facts() {
  local text f=()
  text=$(strip_comments "$1")
  grep -qw Viewpoint <<< "$text" || f+=("no Viewpoint")
  grep -qw Background <<< "$text" && f+=("Background")
  grep -qw ImageTexture <<< "$text" && f+=("ImageTexture")
  grep -qw Inline <<< "$text" && f+=("Inline")
  grep -qw Text <<< "$text" && f+=("Text")
  grep -qw VisibilitySensor <<< "$text" && f+=("VisibilitySensor")
  local IFS=,
  echo "${f[*]}" | sed 's/,/, /g'
}

# A copy of world $1 with a default Viewpoint inserted after line 1, in directory $2 with
# links to the rest of the world's folder. Prints the copy's path.
with_default_viewpoint() {
  local world=$1 dir=$2 name
  name=$(basename "$world")
  rm -rf "$dir" && mkdir -p "$dir"
  for entry in "$(dirname "$world")"/*; do
    [ "$(basename "$entry")" = "$name" ] || ln -s "$(realpath "$entry")" "$dir/"
  done
  { head -n 1 "$world"; echo 'Viewpoint { description "default (inserted)" }'; tail -n +2 "$world"; } \
    > "$dir/$name"
  echo "$dir/$name"
}

# compare_one LABEL WORLD T CAMERA REMARK: renders both, prints one table row.
compare_one() {
  local label=$1 world=$2 t=$3 camera=$4 remark=$5
  local stem
  stem="$OUT/$(echo "$label" | tr '/' '_' | sed 's/\.wrl$//')-$camera-t$t"
  local ours="$stem-ours.png" castle="$stem-castle.png" cells
  if ! "$GHOSTSPACE" --snapshot "$ours" --size "$SIZE" --time "$t" "$world" \
      > "$stem-ours.log" 2>&1; then
    echo "| $label | $t | $camera | - | - | - | - | - | ours failed ($stem-ours.log) |"
    return
  fi
  local w=${SIZE%x*} h=${SIZE#*x}
  if ! xvfb-run -a view3dscene "$world" --screenshot "$t" "$castle" --geometry "${w}x${h}" \
      > "$stem-castle.log" 2>&1 || [ ! -s "$castle" ]; then
    echo "| $label | $t | $camera | - | - | - | - | - | castle failed ($stem-castle.log) |"
    return
  fi
  if ! cells=$("$COMPARE" --markdown "$ours" "$castle" 2> "$stem-compare.log"); then
    echo "| $label | $t | $camera | - | - | - | - | - | compare failed ($stem-compare.log) |"
    return
  fi
  # cells: differ% | meanAbs | PSNR | masked differ% | masked PSNR | fg ours% | fg castle%
  local differ meanabs psnr mdiffer mpsnr
  IFS='|' read -r differ meanabs psnr mdiffer mpsnr _ _ <<< "$cells"
  echo "| $label | $t | $camera |$differ|$meanabs|$psnr|$mdiffer|$mpsnr| $remark |"
}

worlds=()
if [ $# -gt 0 ]; then
  worlds=("$@")
else
  while IFS= read -r f; do
    is_candidate "$f" && worlds+=("$f")
  done < <(find "$CORPUS/freewrl" "$CORPUS/castle-animation" -name '*.wrl' | sort -V)
fi

echo "| world | T (s) | camera | differ % | meanAbs | PSNR dB | masked differ % | masked PSNR dB | remark |"
echo "|---|--:|---|--:|--:|--:|--:|--:|---|"
for world in "${worlds[@]}"; do
  label=${world#"$CORPUS"/}
  ci=$(first_cycle_interval "$world")
  remark="cycle ${ci} s; $(facts "$world")"
  remark=${remark%; }
  for fraction in 0.325 0.675; do
    t=$(awk -v c="$ci" -v f="$fraction" 'BEGIN { printf "%.4g", c * f }')
    if has_viewpoint "$world"; then
      compare_one "$label" "$world" "$t" "own" "$remark"
    else
      compare_one "$label" "$world" "$t" "default" "$remark"
      copy=$(with_default_viewpoint "$world" "$OUT/vp/$(echo "$label" | tr '/' '_')")
      compare_one "$label" "$copy" "$t" "VP" "$remark"
    fi
  done
done
