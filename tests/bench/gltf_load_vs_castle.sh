#!/usr/bin/env bash
# Load to first frame of one glTF (or any world) file, GhostSpace and castle-model-viewer in
# the same run, on the same machine, at the same size (issue 21's load figure):
#
#   tests/bench/gltf_load_vs_castle.sh BUILD_DIR [MODEL] [RUNS] [WIDTHxHEIGHT]
#
# MODEL defaults to the corpus's largest glTF (the cat, 4.6 MB with its textures); RUNS to
# 5. Prints, per program, the median wall time and peak memory over the runs of the whole
# process (read, parse, decode textures, first frame, PNG written): `ghostspace --snapshot`
# and `view3dscene MODEL --screenshot 0` (under xvfb-run, which castle needs for its GL
# context; its start-up is timed too: about 0.1 s, measured by `xvfb-run true`), then
# bench_render's in-process split (parse, set-up, first frame) for GhostSpace.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [MODEL] [RUNS] [WIDTHxHEIGHT]}
top=$(cd "$(dirname "$0")/../.." && pwd)
model=${2:-$top/../shared/corpus/gltf/castle/bump_mapping/tangents/cat-16c3444c8d1440fc97fdf10f60ec58b0/scene.gltf}
runs=${3:-5}
size=${4:-640x480}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# median_of CMD...: runs CMD $runs times; prints "median_s max_rss_MB".
median_of() {
  local times=() mems=()
  for _ in $(seq "$runs"); do
    /usr/bin/time -f "%e %M" -o "$out/t" "$@" > /dev/null 2>&1 || true
    read -r t m < "$out/t"
    times+=("$t")
    mems+=("$m")
  done
  local mt mm
  mt=$(printf '%s\n' "${times[@]}" | sort -g | sed -n "$(( (runs + 1) / 2 ))p")
  mm=$(printf '%s\n' "${mems[@]}" | sort -g | sed -n "$(( (runs + 1) / 2 ))p")
  echo "$mt s, $(( mm / 1024 )) MB"
}

echo "model: $model ($(du -sh "$(dirname "$model")" | cut -f1) with what it references), $size, median of $runs"
echo "ghostspace --snapshot:          $(median_of "$build/bin/ghostspace" --snapshot "$out/gs.png" --size "$size" "$model")"
if command -v view3dscene > /dev/null && command -v xvfb-run > /dev/null; then
  echo "xvfb-run true (castle's start): $(median_of xvfb-run -a true)"
  echo "view3dscene --screenshot 0:     $(median_of xvfb-run -a -s "-screen 0 ${size}x24" view3dscene "$model" --screenshot 0 "$out/castle.png" --geometry "$size")"
else
  echo "view3dscene: not installed (apt-get install view3dscene xvfb)"
fi
if [ -x "$build/bin/bench_render" ]; then
  "$build/bin/bench_render" "$model" "$out/bench.png" "$size" 10 --fit 2> /dev/null
fi
