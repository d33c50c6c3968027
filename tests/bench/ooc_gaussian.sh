#!/bin/bash
# Out-of-core Gaussian tileset figures (docs/out-of-core.md, "Gaussian splatting scenes"):
# a larger scene made of N x N copies of a binary INRIA .ply side by side (x and y, 1.1
# box sides apart), then its tileset encoded in memory and under --memory MB, each run's
# wall time and peak memory (GNU time's %M = VmHWM), and a byte comparison of both trees.
#
#   tests/bench/ooc_gaussian.sh GHOSTSPACE SCENE.ply N MEMORY_MB OUTDIR [encode options]
#
# SCENE.ply: e.g. splat-transform -g cpu ../shared/corpus/splat/cthead.spz cthead.ply
# (the peer in ../shared/peers/splat). Needs python3 to write the copies.
set -euo pipefail
gs=$1 scene=$2 n=$3 memory=$4 out=$5
shift 5
mkdir -p "$out"
tiled="$out/tiled_${n}x${n}.ply"
if [ ! -f "$tiled" ]; then
  python3 - "$scene" "$n" "$tiled" <<'PY'
import array, re, sys
src, n, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
data = open(src, "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header, body = data[:end], data[end:]
assert b"binary_little_endian" in header, "a binary little-endian .ply"
count = int(re.search(rb"element vertex (\d+)", header).group(1))
props = re.findall(rb"property (\w+) (\w+)", header)
assert all(t == b"float" for t, _ in props) and props[0][1] == b"x", "float properties, x first"
stride = len(props)
a = array.array("f")
a.frombytes(body[: count * stride * 4])
xs, ys = a[0::stride], a[1::stride]
dx, dy = 1.1 * (max(xs) - min(xs)), 1.1 * (max(ys) - min(ys))
with open(dst, "wb") as out:
    out.write(header.replace(b"element vertex %d" % count, b"element vertex %d" % (count * n * n)))
    for i in range(n):
        for j in range(n):
            b = array.array("f", a)
            for r in range(count):
                b[r * stride] += i * dx
                b[r * stride + 1] += j * dy
            out.write(b.tobytes())
PY
fi
splats=$(head -c 4096 "$tiled" | sed -n 's/^element vertex *//p')
run() { /usr/bin/time -f "%e %M" -o "$out/time.txt" "$@" >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; exit 1; }; }
for mode in memory ooc; do
  rm -rf "${out:?}/$mode"
  if [ "$mode" = memory ]; then
    run "$gs" encode "$tiled" --tileset "$out/$mode" --no-progress "$@"
  else
    run "$gs" encode "$tiled" --tileset "$out/$mode" --memory "$memory" --no-progress "$@"
  fi
  read -r seconds kib <"$out/time.txt"
  cat "$out/log.txt"
  awk -v m="$mode" -v s="$seconds" -v k="$kib" -v n="$splats" \
    'BEGIN { printf "%s: %d splats, %.1f s, %.0f k splats/s, peak %.0f MiB\n", m, n, s, n / s / 1e3, k / 1024 }'
done
if diff -r -q "$out/memory" "$out/ooc" >/dev/null; then
  echo "out of core: byte-identical to the in-memory encode"
else
  echo "out of core: DIFFERS from the in-memory encode"
  exit 1
fi
