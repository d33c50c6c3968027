#!/usr/bin/env bash
# A 640x480 movie while four viewports draw (docs/media.md): makes a 10 s, 25 fps MPEG-1
# clip with an MP2 track (ffmpeg) and a world showing it on a quad, then runs the window
# (needs DISPLAY, e.g. Xvfb) in a 2x2 layout for 150 frames and prints the frame-stats
# (frame times; movie frames each viewport showed). Usage: movie_window.sh GHOSTSPACE DIR
set -euo pipefail
exe=${1:?usage: movie_window.sh GHOSTSPACE DIR}
dir=${2:?usage: movie_window.sh GHOSTSPACE DIR}
mkdir -p "$dir"
cd "$dir"
ffmpeg -loglevel error -y -f lavfi -i testsrc=size=640x480:rate=25 \
  -f lavfi -i sine=frequency=440:sample_rate=44100 -t 10 -c:v mpeg1video -b:v 2M -c:a mp2 \
  -b:a 128k movie640.mpg
cat >movie640.wrl <<'WRL'
#VRML V2.0 utf8
Viewpoint { position 0 0 2.2 }
Shape {
  appearance Appearance { texture MovieTexture { url "movie640.mpg" loop TRUE } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -1.333 -1 0, 1.333 -1 0, 1.333 1 0, -1.333 1 0 ] }
    coordIndex [ 0 1 2 3 -1 ]
    texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0 1 ] }
  }
}
WRL
printf 'wait-loaded\nframes 25\nframe-stats %s/warm.txt\nframes 150\nframe-stats %s/stats.txt\nquit\n' \
  "$PWD" "$PWD" >movie.script
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$exe" --new-instance --size 1280x960 --layout 2x2 --script movie.script movie640.wrl 2>/dev/null
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
cat warm.txt stats.txt
