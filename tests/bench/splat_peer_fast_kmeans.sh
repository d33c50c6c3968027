#!/bin/bash
# A copy of the splat peer (../shared/peers/splat, set up by its setup.sh) whose CPU k-means
# finds each point's nearest centroid by a plain exact search instead of a k-d tree, so that
# a SOG of a capture with three SH bands (CThead: 122,000 splats, 65,536 palette entries of
# 45 coefficients) is made in about an hour on one core instead of many (docs/splats.md,
# "Bytes and pictures"). The labels are the same as the k-d tree's (nearest by squared
# distance; ties aside): each point starts from its last centroid and leaves a candidate
# once its partial sum passes the best. The shared peer is not touched.
#
#   tests/bench/splat_peer_fast_kmeans.sh PEER_DIR OUT_DIR
#   OUT_DIR/node_modules/.bin/splat-transform -w -g cpu cthead.spz cthead.sog
set -euo pipefail
peer=${1:?PEER_DIR: a splat peer set up by setup.sh}
out=${2:?OUT_DIR}
[ -x "$peer/node_modules/.bin/splat-transform" ] || { echo "$peer: run its setup.sh first" >&2; exit 1; }
mkdir -p "$out"
cp -r "$peer/node_modules" "$out/"
cli="$out/node_modules/@playcanvas/splat-transform/dist/cli.mjs"
/usr/bin/python3 - "$cli" <<'PY'
import sys
p = sys.argv[1]
s = open(p).read()
head = "const assignCpu = (points, numRows, nc, centroids, k, labels) => {"
start = s.find(head)
end = s.find("/**\n * k-means over row-major interleaved points", start)
if start < 0 or end < 0:
    sys.exit("splat_peer_fast_kmeans.sh: assignCpu not found (another splat-transform version?)")
new = head + '''
    // Patched (GhostSpace tests/bench/splat_peer_fast_kmeans.sh): exact nearest centroid,
    // starting from the last label, a candidate left once its partial sum passes the best.
    const t0 = Date.now();
    for (let r = 0; r < numRows; ++r) {
        const pb = r * nc;
        let bi = labels[r];
        let best = 0;
        const c0 = bi * nc;
        for (let j = 0; j < nc; ++j) { const d = points[pb + j] - centroids[c0 + j]; best += d * d; }
        for (let i = 0; i < k; ++i) {
            if (i === bi) continue;
            const cb = i * nc;
            let s = 0;
            let j = 0;
            while (j < nc) {
                const e = Math.min(nc, j + 5);
                for (; j < e; ++j) { const d = points[pb + j] - centroids[cb + j]; s += d * d; }
                if (s >= best) break;
            }
            if (s < best) { best = s; bi = i; }
        }
        labels[r] = bi;
    }
    process.stderr.write(`assign pass: ${numRows} x ${k} in ${(Date.now() - t0) / 1000} s\\n`);
};
'''
open(p, 'w').write(s[:start] + new + s[end:])
PY
echo "patched k-means in $cli"
