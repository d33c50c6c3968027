#!/bin/bash
# Out-of-core mesh tileset figures (docs/out-of-core.md, "Meshes"): the whole encode of
# MESH.ply under --memory MB, its wall time, triangles/s and peak memory (maximum resident
# set, GNU time's %M = VmHWM), then, with SHARES > 1, the split run (each share in turn,
# then the merge) and a byte comparison of both trees.
#
#   tests/bench/ooc_mesh.sh GHOSTSPACE MESH.ply MEMORY_MB OUTDIR [SHARES] [encode options]
#
# Meshes: make_mesh_soup --triangles N [--soup] OUT.ply writes a bumpy torus.
set -euo pipefail
gs=$1 mesh=$2 memory=$3 out=$4 shares=${5:-1}
shift 5 || shift $#
rm -rf "$out/single" "$out/split"
mkdir -p "$out"
triangles=$(head -c 4096 "$mesh" | sed -n 's/^element face *//p')
run() { /usr/bin/time -f "%e %M" -o "$out/time.txt" "$@" >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; exit 1; }; }
run "$gs" encode "$mesh" --tileset "$out/single" --memory "$memory" --no-progress "$@"
read -r seconds kib <"$out/time.txt"
cat "$out/log.txt"
awk -v s="$seconds" -v k="$kib" -v t="$triangles" \
  'BEGIN { printf "single: %.1f s, %.2f M triangles/s, peak %.0f MiB\n", s, t / s / 1e6, k / 1024 }'
du -sb "$out/single" | awk '{ printf "tileset: %.1f MiB\n", $1 / 1048576 }'
if [ "$shares" -gt 1 ]; then
  peak=0 total=0
  for ((i = 0; i < shares; ++i)); do
    run "$gs" encode "$mesh" --tileset "$out/split" --memory "$memory" --no-progress \
      --bricks "$i/$shares" "$@"
    read -r seconds kib <"$out/time.txt"
    tail -n 1 "$out/log.txt"
    total=$(awk -v a="$total" -v b="$seconds" 'BEGIN { print a + b }')
    [ "$kib" -gt "$peak" ] && peak=$kib
  done
  run "$gs" tileset index "$out/split"
  read -r seconds kib <"$out/time.txt"
  echo "merge: $seconds s, peak $((kib / 1024)) MiB"
  echo "shares: $total s in all, peak $((peak / 1024)) MiB"
  if diff -r -q "$out/single" "$out/split" >/dev/null; then
    echo "split run: byte-identical to the single run"
  else
    echo "split run: DIFFERS from the single run"
    exit 1
  fi
fi
