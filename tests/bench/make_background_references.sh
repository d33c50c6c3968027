#!/usr/bin/env bash
# Background panoramas compared with castle-model-viewer (docs/castle-comparison.md, "Text
# and Background"): makes DIR/skies/*.png (six labelled faces and one with a transparent
# hole, with ffmpeg), castle's empty_with_background.wrl and four variants under DIR/vrml_2,
# and castle's reference for each (view3dscene, 1600x900, needs DISPLAY, e.g. Xvfb). Then:
#   build/bin/compare_reference DIR
# Usage: make_background_references.sh DIR [CASTLE_DIR]
set -euo pipefail
dir=${1:?usage: make_background_references.sh DIR [CASTLE_DIR]}
castle=${2:-$(cd "$(dirname "$0")/../.." && pwd)/../shared/corpus/vrml/castle}
mkdir -p "$dir/skies" "$dir/vrml_2"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf
i=0
for f in back bottom front left right top; do
  ffmpeg -loglevel error -y -f lavfi -i "testsrc=size=256x256:rate=1" -frames:v 1 \
    -vf "hue=h=$((i * 60)),drawtext=fontfile=$font:text=$f:fontsize=48:fontcolor=white:box=1:boxcolor=black:x=(w-tw)/2:y=(h-th)/2" \
    "$dir/skies/sky_lake_$f.png"
  i=$((i + 1))
done
ffmpeg -loglevel error -y -f lavfi -i "testsrc=size=256x256:rate=1" -frames:v 1 \
  -vf "format=rgba,geq=r='r(X,Y)':g='g(X,Y)':b='b(X,Y)':a='if(lt(hypot(X-128,Y-128),80),0,255)'" \
  "$dir/skies/holed_front.png"
cp "$castle/vrml_2/empty_with_background.wrl" "$dir/vrml_2/"
for v in "up:1 0 0 0.9" "left:0 1 0 1.2" "down:1 0 0 -1.0"; do
  sed "s|^Group {|Viewpoint { position 0 0 0 orientation ${v#*:} }\nGroup {|" \
    "$dir/vrml_2/empty_with_background.wrl" >"$dir/vrml_2/background_look_${v%%:*}.wrl"
done
cat >"$dir/vrml_2/background_bands_alpha.wrl" <<'WRL'
#VRML V2.0 utf8
# Sky and ground colour bands (6.5) behind a front image with a transparent hole: the
# colours show through the hole.
Viewpoint { position 0 0 0 orientation 1 0 0 0.2 }
Background {
  skyColor [ 0 0 0.4, 0.2 0.4 1, 0.9 0.9 1 ]
  skyAngle [ 1.2, 1.57 ]
  groundColor [ 0.1 0.3 0, 0.4 0.3 0.1, 0.6 0.5 0.3 ]
  groundAngle [ 1.0, 1.57 ]
  frontUrl "../skies/holed_front.png"
}
WRL
cd "$dir/vrml_2"
for w in *.wrl; do
  view3dscene "$w" --geometry 1600x900 --screenshot 0 "${w}_screenshot.png" >/dev/null 2>&1
done
ls "$dir/vrml_2"
