#!/usr/bin/env bash
# Every X3D world of the corpus drawn by GhostSpace and by a peer browser at the same size and
# simulated time, compared with the project's image metric:
#
#   tests/bench/x3d_vs_peer.sh castle|xite BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIMES]
#
# castle: castle-model-viewer (`view3dscene WORLD --screenshot T`, under xvfb-run), with
#   `ghostspace --castle-camera` (castle places its own camera where a world has none);
#   issue 20's judge (docs/castle-comparison.md).
# xite: X_ITE 15 in headless Chromium (../shared/peers/xite/shot.mjs; set up once with its
#   setup.sh, in XITE_PEER, default /tmp/peer/xite), the world's own camera (X_ITE's default
#   0 0 10 when it has none, as VRML's) and `ghostspace --samples 4 --texture-quality Q
#   --shading gouraud` (X_ITE's WebGL canvas is anti-aliased, and GOURAUD is its default
#   browser option; docs/rendering.md, "Browser options"); issue 41's judge of X3D 4.
#   Q is XITE_TEXTURE_QUALITY (low, medium or high; default low), set in both browsers: X_ITE's
#   own default, MEDIUM, mipmaps, and under the peer's SwiftShader its mipmap levels past a
#   level of detail of about 4.5 turn black, so a texture repeated many times (the castle
#   level's tower: 28 times up its height) is darkened in X_ITE's picture alone; LOW samples
#   the base level in both (docs/xite-comparison.md, eighteenth session). The peer's pictures
#   are kept as KEY.xite.png (medium) or KEY.xite-Q.png.
#   Every world over 5% or not drawn, at a time, should have a line in x3d_vs_xite.known
#   (beside this script: WORLD<TAB>TIMES<TAB>CAUSE, TIMES "0 2" or "*"): the summary counts
#   those with a documented cause, names those without one and the lines no longer needed.
# TIMES: the simulated times to compare, e.g. "0 2.5" (default "0"): X_ITE loads at SFTime
#   720720 = lcm(1..16) and runs T seconds in fixed steps, so a looping TimeSensor is at the
#   phase `ghostspace --time T` gives; against X_ITE ours is loaded there too
#   (`--load-time 720720 --time 720720+T`), so what runs from the load has run as long.
#
# For each .x3d / .x3dv / .x3dz / .x3dvz (and, for X_ITE, .x3dj) file below
# ../shared/corpus/x3d and each T:
# both pictures, then BUILD_DIR/bin/compare_png --markdown (`differ` at a tolerance of 16 of
# 255, and the background-masked `differ`, where pixels that show each program's own
# background, its corner colour, count as equal). Prints one markdown row per world and time
# and a summary per time: how many are within 1% and 5% masked `differ`. A world either
# program cannot draw is listed as such. Both images stay in OUT_DIR (default: a temporary
# folder, removed) to be looked at. With KEEP_PEER=1 a peer picture already in OUT_DIR is
# used again (the peers do not change between runs: only ours is drawn anew); with
# KEEP_PEER=only the peer is never run (a world it did not draw before stays not drawn). A
# measurement, not a test.
set -euo pipefail
peer=${1:?usage: $0 castle|xite BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIMES]}
build=${2:?usage: $0 castle|xite BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIMES]}
top=$(cd "$(dirname "$0")/../.." && pwd)
corpus=${CORPUS:-$top/../shared/corpus/x3d}
out=${3:-}
size=${4:-300x300}
times=${5:-0}
xite=${XITE_PEER:-/tmp/peer/xite}
case $peer in
  castle) ours_options=(--castle-camera) ;;
  xite)
    # X_ITE draws with WebGL's antialias (4 samples a pixel in its pictures) and at its
    # default Shading GOURAUD: ours too. Both at the same TextureQuality (above).
    quality=${XITE_TEXTURE_QUALITY:-low}
    case $quality in low | medium | high) ;; *)
      echo "$0: XITE_TEXTURE_QUALITY must be low, medium or high, not '$quality'" >&2; exit 2 ;;
    esac
    ours_options=(--samples 4 --texture-quality "$quality" --shading gouraud)
    [ -f "$xite/node_modules/x_ite/package.json" ] ||
      { echo "$0: X_ITE is not set up in $xite (copy ../shared/peers/xite there, run setup.sh)" >&2; exit 1; }
    shot=$xite/shot.mjs
    if [ "$quality" != medium ]; then
      # shot.mjs sets X_ITE's browser options where it turns StraightenHorizon off; a copy
      # beside it (for its node_modules) sets TextureQuality there too.
      shot=$xite/shot-texture-$quality.mjs
      anchor='b.setBrowserOption("StraightenHorizon", false);'
      grep -qF "$anchor" "$xite/shot.mjs" ||
        { echo "$0: $xite/shot.mjs has no '$anchor' line to add TextureQuality to" >&2; exit 1; }
      sed "s|$anchor|$anchor b.setBrowserOption(\"TextureQuality\", \"${quality^^}\");|" \
        "$xite/shot.mjs" > "$shot"
      peer_suffix=-$quality
    fi
    declare -A known=()
    known_file=$(dirname "$0")/x3d_vs_xite.known
    while IFS=$'\t' read -r kworld ktimes kcause; do
      case $kworld in '' | '#'*) continue ;; esac
      known[$kworld]="$ktimes"$'\t'"$kcause"
    done < "$known_file" ;;
  *) echo "$0: unknown peer '$peer' (castle or xite)" >&2; exit 2 ;;
esac
if [ -z "$out" ]; then
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
ghostspace=$build/bin/ghostspace
compare=$build/bin/compare_png

# The peer's picture of world $1 at time $2 in $3.
peer_shot() {
  if [ "$peer" = castle ]; then
    timeout 60 xvfb-run -a view3dscene "$1" --screenshot "$2" "$3" --geometry "$size" \
      > /dev/null 2>&1 || true
  else
    timeout 120 node "$shot" "$1" "$3" --size "$size" --time "$2" --timeout 90 \
      > /dev/null 2>&1 || true
  fi
}

# (castle-model-viewer reads no X3D JSON: its .x3dj worlds are compared with X_ITE only.)
json=()
[ "$peer" = xite ] && json=(-o -name '*.x3dj')
mapfile -t worlds < <(find "$corpus" -type f \( -name '*.x3d' -o -name '*.x3dv' -o -name '*.x3dz' \
  -o -name '*.x3dvz' "${json[@]}" \) | LC_ALL=C sort)
for time in $times; do
  echo "### T = $time s, $size, against $peer"
  echo
  echo "| world | differ % | meanAbs | PSNR | masked differ % | masked PSNR | fg ours % | fg $peer % |"
  echo "|---|--:|--:|--:|--:|--:|--:|--:|"
  within1=0 within5=0 total=0 failed=0 explained=0
  unexplained=() listed_within=()
  for world in "${worlds[@]}"; do
    name=${world#"$corpus"/}
    key=${name//\//__}.t$time
    total=$((total + 1))
    ours=$out/$key.ours.png
    theirs=$out/$key.$peer${peer_suffix:-}.png
    # X_ITE's picture at T is of a world loaded T seconds before, at SFTime 720720: ours too
    # (--load-time), so particles, followers and physics have run as long.
    when=(--time "$time")
    [ "$peer" = xite ] && when=(--load-time 720720 --time "$(awk -v t="$time" 'BEGIN { printf "%.6f", 720720 + t }')")
    timeout 60 "$ghostspace" --snapshot "$ours" --size "$size" "${when[@]}" "${ours_options[@]}" \
      "$world" > /dev/null 2>&1 || true
    case ${KEEP_PEER:-0} in
      only) ;;
      1) [ -s "$theirs" ] || peer_shot "$world" "$time" "$theirs" ;;
      *) peer_shot "$world" "$time" "$theirs" ;;
    esac
    # Is this world at this time in x3d_vs_xite.known?
    cause=
    if [ "$peer" = xite ] && [ -n "${known[$name]:-}" ]; then
      ktimes=${known[$name]%%$'\t'*}
      case " $ktimes " in *" $time "* | " * ") cause=${known[$name]#*$'\t'} ;; esac
    fi
    if [ ! -s "$ours" ] || [ ! -s "$theirs" ]; then
      failed=$((failed + 1))
      echo "| $name | (not drawn by $([ -s "$ours" ] && echo "$peer" || echo GhostSpace)) | | | | | | |"
      if [ -n "$cause" ]; then explained=$((explained + 1)); else unexplained+=("$name"); fi
      continue
    fi
    row=$("$compare" --markdown "$ours" "$theirs")
    echo "| $name | $row |"
    masked=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $4); print $4}')
    awk -v m="$masked" 'BEGIN { exit !(m <= 1.0) }' && within1=$((within1 + 1))
    if awk -v m="$masked" 'BEGIN { exit !(m <= 5.0) }'; then
      within5=$((within5 + 1))
      [ -n "$cause" ] && listed_within+=("$name ($masked%)")
    elif [ -n "$cause" ]; then
      explained=$((explained + 1))
    else
      unexplained+=("$name ($masked%)")
    fi
  done
  echo
  echo "T = $time: $total worlds: masked differ <= 1%: $within1; <= 5%: $within5; not drawn by one program: $failed"
  if [ "$peer" = xite ]; then
    echo
    echo "T = $time: over 5% or not drawn: $explained with a cause in x3d_vs_xite.known, ${#unexplained[@]} without one"
    for w in "${unexplained[@]}"; do echo "- no cause: $w"; done
    for w in "${listed_within[@]}"; do echo "- listed, now within 5%: $w"; done
  fi
  echo
done
