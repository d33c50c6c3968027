#!/usr/bin/env bash
# Frame after frame, GhostSpace against castle-model-viewer on the same worlds, in one run
# (issue 22's drawing figure): each world is drawn N frames 0.05 s apart, as PNGs, by
#
#   ghostspace --snapshot OUT.png --size WxH --time 0:0.05:N WORLD            (variants on)
#   ghostspace ... with GS_SHADER_VARIANTS=0 in the environment               (one program)
#   xvfb-run view3dscene WORLD --screenshot-range 0 0.05 N OUT@counter(4).png --geometry WxH
#
# and the whole process is timed; "per frame" is (time of N frames - time of 1 frame) /
# (N - 1), so loading, the first frame and (for castle) Xvfb's start cancel out. Prints a
# markdown table. Both write PNGs (castle at its default compression, we at zlib level 1).
#
#   tests/bench/frames_vs_castle.sh BUILD_DIR [N] [WxH ...] -- WORLD ...
#
# Defaults: N = 40, sizes 640x480 and 1280x960, and five corpus worlds (castle, KiCad,
# a Text world, a textured world, OpenVRML) when no world is given.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [N] [WxH ...] -- WORLD ...}
shift
frames=40
sizes=()
worlds=()
if [ $# -gt 0 ] && [ "$1" != "--" ]; then frames=$1; shift; fi
while [ $# -gt 0 ] && [ "$1" != "--" ]; do sizes+=("$1"); shift; done
[ $# -gt 0 ] && shift
worlds=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(640x480 1280x960)
top=$(cd "$(dirname "$0")/../.." && pwd)
corpus=$(realpath "$top/../shared/corpus/vrml")
if [ ${#worlds[@]} -eq 0 ]; then
  worlds=("$corpus/castle/lights_materials/light_radius.wrl"
          "$corpus/kicad/Capacitor_SMD__CP_Elec_5x3.wrl"
          "$corpus/castle/vrml_2/teapot.wrl"
          "$corpus/castle/vrml_2/castle_extensions/inline_load_control_test_1.wrl"
          "$corpus/castle/lights_materials/specular_demo.wrl")
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

seconds() {  # seconds CMD...: wall time of CMD (its output discarded)
  local s e
  s=$(date +%s.%N)
  "$@" > /dev/null 2>&1 || true
  e=$(date +%s.%N)
  echo "$e - $s" | bc -l
}
per_frame() {  # per_frame T1 TN: ms per frame beyond the first
  echo "scale=1; 1000 * ($2 - $1) / ($frames - 1)" | bc -l
}

echo "| world | size | ghostspace ms/frame | ghostspace, one program | castle ms/frame |"
echo "|---|---|---|---|---|"
for w in "${worlds[@]}"; do
  w=$(realpath "$w")
  for size in "${sizes[@]}"; do
    g1=$(seconds "$build/bin/ghostspace" --snapshot "$out/g.png" --size "$size" --time 0 "$w")
    gn=$(seconds "$build/bin/ghostspace" --snapshot "$out/g.png" --size "$size" --time "0:0.05:$frames" "$w")
    p1=$(GS_SHADER_VARIANTS=0 seconds "$build/bin/ghostspace" --snapshot "$out/p.png" --size "$size" --time 0 "$w")
    pn=$(GS_SHADER_VARIANTS=0 seconds "$build/bin/ghostspace" --snapshot "$out/p.png" --size "$size" --time "0:0.05:$frames" "$w")
    c1=$(seconds xvfb-run -a -s "-screen 0 ${size}x24" view3dscene "$w" --screenshot 0 "$out/c.png" --geometry "$size")
    cn=$(seconds xvfb-run -a -s "-screen 0 ${size}x24" view3dscene "$w" --screenshot-range 0 0.05 "$frames" "$out/c@counter(4).png" --geometry "$size")
    echo "| ${w#"$corpus"/} | $size | $(per_frame "$g1" "$gn") | $(per_frame "$p1" "$pn") | $(per_frame "$c1" "$cn") |"
  done
done
