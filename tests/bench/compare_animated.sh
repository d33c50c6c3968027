#!/usr/bin/env bash
# Compares our frames of the corpus's animated worlds with castle-model-viewer's
# (view3dscene) at the same SFTime and prints a markdown table (docs/runtime-comparison.md).
#
#   tests/bench/compare_animated.sh                # from the project root
#   BUILD=build-cmp OUT=/tmp/anim-cmp tests/bench/compare_animated.sh [WORLD.wrl ...]
#
# Worlds: every .wrl below $CORPUS/freewrl and $CORPUS/castle-animation that has a
# TimeSensor and a ROUTE and no Script node (castle-model-viewer has no ECMAScript), or the
# worlds given as arguments. Times: 0.325 and 0.575 of the world's first cycleInterval
# (1.3 s and 2.3 s for the common 4 s cycle): mid-cycle, away from the interpolators'
# usual keys (0, 0.5, 1) and not symmetric about the middle of the cycle (0.325 and 0.675
# give the same frame for a symmetric motion such as 27.wrl's bouncing ball).
#
# Each world is drawn at 300x300 by
#   $BUILD/bin/ghostspace --snapshot ours.png --size 300x300 --time T WORLD
#   xvfb-run -a view3dscene WORLD --screenshot T castle.png --geometry 300x300
# and the two PNGs are compared by $BUILD/bin/compare_png (render::compareImages, channel
# tolerance 16, and the background-masked variant of docs/castle-comparison.md). The last
# figure compares our frame with castle's frame at the *other* time (masked differ), a
# check that the frames move and that the match is a match of the animation.
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

# render_both WORLD T STEM: writes STEM-ours.png and STEM-castle.png (and their logs).
# Prints nothing on success, else the reason for the remark column.
render_both() {
  local world=$1 t=$2 stem=$3
  local w=${SIZE%x*} h=${SIZE#*x}
  if ! "$GHOSTSPACE" --snapshot "$stem-ours.png" --size "$SIZE" --time "$t" "$world" \
      > "$stem-ours.log" 2>&1; then
    echo "ours failed ($stem-ours.log)"
  elif ! xvfb-run -a view3dscene "$world" --screenshot "$t" "$stem-castle.png" \
      --geometry "${w}x${h}" > "$stem-castle.log" 2>&1 || [ ! -s "$stem-castle.png" ]; then
    echo "castle failed ($stem-castle.log)"
  fi
}

# metric OURS.png CASTLE.png: the cells of compare_png --markdown, trimmed, separated by
# single spaces: differ% meanAbs PSNR masked-differ% masked-PSNR fg-ours% fg-castle%.
metric() { "$COMPARE" --markdown "$1" "$2" 2> /dev/null | tr -d '|' | xargs; }

# compare_world LABEL WORLD CAMERA REMARK T1 T2: renders both times, prints two rows.
compare_world() {
  local label=$1 world=$2 camera=$3 remark=$4 t1=$5 t2=$6
  local base stems=() fails=() t i
  base="$OUT/$(echo "$label" | tr '/' '_' | sed 's/\.wrl$//')-$camera"
  for t in "$t1" "$t2"; do
    stems+=("$base-t$t")
    fails+=("$(render_both "$world" "$t" "$base-t$t")")
  done
  for i in 0 1; do
    t=$([ $i = 0 ] && echo "$t1" || echo "$t2")
    if [ -n "${fails[$i]}" ]; then
      echo "| $label | $t | $camera | - | - | - | - | - | - | ${fails[$i]} |"
      continue
    fi
    local m cross differ meanabs psnr mdiffer mpsnr
    m=$(metric "${stems[$i]}-ours.png" "${stems[$i]}-castle.png")
    if [ -z "$m" ]; then
      echo "| $label | $t | $camera | - | - | - | - | - | - | compare_png failed |"
      continue
    fi
    read -r differ meanabs psnr mdiffer mpsnr _ _ <<< "$m"
    # Ours against castle's frame at the other time: when this is much larger than the
    # masked differ of the same time, the animation moved visibly and both agree on where.
    cross="-"
    if [ -z "${fails[$((1 - i))]}" ]; then
      cross=$(metric "${stems[$i]}-ours.png" "${stems[$((1 - i))]}-castle.png" |
              awk '{print $4}')
    fi
    echo "| $label | $t | $camera | $differ | $meanabs | $psnr | $mdiffer | $mpsnr | $cross | $remark |"
  done
}

worlds=()
if [ $# -gt 0 ]; then
  worlds=("$@")
else
  while IFS= read -r f; do
    is_candidate "$f" && worlds+=("$f")
  done < <(find "$CORPUS/freewrl" "$CORPUS/castle-animation" -name '*.wrl' | sort -V)
fi

echo "| world | T (s) | camera | differ % | meanAbs | PSNR dB | masked differ % | masked PSNR dB | masked differ % vs castle at the other T | remark |"
echo "|---|--:|---|--:|--:|--:|--:|--:|--:|---|"
for world in "${worlds[@]}"; do
  label=${world#"$CORPUS"/}
  ci=$(first_cycle_interval "$world")
  remark="cycle ${ci} s; $(facts "$world")"
  remark=${remark%; }
  t1=$(awk -v c="$ci" 'BEGIN { printf "%.4g", c * 0.325 }')
  t2=$(awk -v c="$ci" 'BEGIN { printf "%.4g", c * 0.575 }')
  if has_viewpoint "$world"; then
    compare_world "$label" "$world" "own" "$remark" "$t1" "$t2"
  else
    compare_world "$label" "$world" "default" "$remark" "$t1" "$t2"
    copy=$(with_default_viewpoint "$world" "$OUT/vp/$(echo "$label" | tr '/' '_')")
    compare_world "$label" "$copy" "VP" "$remark" "$t1" "$t2"
  fi
done
