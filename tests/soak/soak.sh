#!/usr/bin/env bash
# Soak test (not run in CI; docs/soak.md): the window under Xvfb with four viewports
# (layout 2x2) streaming QNV files from a loopback nginx, the fourth through the fault
# server (gs_fault_server: a slow drip cut by a reset and a stall, both resumed), automatic
# level of detail on in each, for MINUTES minutes. The window's resident memory (VmRSS) is
# sampled each second into OUT.csv (seconds,rss_kib); the window logs every frame
# (--frame-log, build/soak/frames.csv). At the end it prints the RSS curve per half
# minute and the frame-time percentiles per minute, and fails (exit 1) when, after the
# warm-up, resident memory grew by more than GS_SOAK_RSS_MIB or a frame took longer than
# GS_SOAK_FRAME_MS (the bounds and why: docs/soak.md).
#
#   tests/soak/soak.sh MINUTES [OUT.csv]
#
# Environment: GS_BIN (default build/bin/ghostspace), GS_FAULT_SERVER (default
# build/tests/gs_fault_server), GS_SOAK_WARMUP (seconds, default 120), GS_SOAK_RSS_MIB
# (default 64), GS_SOAK_FRAME_MS (default 1000). Needs /usr/sbin/nginx, /usr/bin/Xvfb and
# the corpus (../shared/corpus: the CT head and the Stanford bunny are encoded once into
# build/soak/root). Exit codes: 0 within the bounds, 1 outside them or the window ended
# early, 2 a tool is missing.
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
minutes=${1:?usage: soak.sh MINUTES [OUT.csv]}
out=${2:-$top/build/soak/rss.csv}
bin=${GS_BIN:-$top/build/bin/ghostspace}
faultd=${GS_FAULT_SERVER:-$top/build/tests/gs_fault_server}
warmup=${GS_SOAK_WARMUP:-120}
rss_bound=${GS_SOAK_RSS_MIB:-64}
frame_bound=${GS_SOAK_FRAME_MS:-1000}
corpus=$top/../shared/corpus
work=$top/build/soak
frames=$work/frames.csv
mkdir -p "$work/root"
for tool in "$bin" "$faultd" /usr/sbin/nginx /usr/bin/Xvfb; do
  [ -x "$tool" ] || { echo "soak: $tool is missing" >&2; exit 2; }
done

# The streams: encoded once.
[ -s "$work/root/head.qnv" ] || "$bin" encode "$corpus/volume/cthead/CThead.nhdr" -o "$work/root/head.qnv"
[ -s "$work/root/bunny.qnv" ] || "$bin" encode "$corpus/mesh/bunny/bun_zipper.ply" -o "$work/root/bunny.qnv"
[ -s "$work/root/head_compact.qnv" ] ||
  "$bin" encode "$corpus/volume/cthead/CThead.nhdr" -o "$work/root/head_compact.qnv" --compact

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

# nginx on a free port, serving build/soak/root.
port=$(free_port)
mkdir -p "$work/nginx/tmp"
cat > "$work/nginx/nginx.conf" <<CONF
daemon off; master_process off; worker_processes 1;
pid $work/nginx/nginx.pid; error_log $work/nginx/error.log warn;
events { worker_connections 64; }
http {
  types { model/x-qnv qnv; } default_type application/octet-stream;
  access_log $work/nginx/access.log;
  client_body_temp_path $work/nginx/tmp/b; proxy_temp_path $work/nginx/tmp/p;
  fastcgi_temp_path $work/nginx/tmp/f; uwsgi_temp_path $work/nginx/tmp/u; scgi_temp_path $work/nginx/tmp/s;
  server { listen 127.0.0.1:$port; root $work/root; }
}
CONF
: > "$work/nginx/access.log"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done; }
trap cleanup EXIT
/usr/sbin/nginx -p "$work/nginx" -c "$work/nginx/nginx.conf" -e "$work/nginx/error.log" &
pids+=($!)

# The fault server: the bunny as a drip that lasts about 3/4 of the run. The window asks
# for the header and a first slice (served), then for the rest: that connection is reset
# after a quarter of the file, the resumed one stalls after another quarter (5 s of
# silence, then closed), the second resume is served; the window resumes both
# (net::FetchRequest::maxResumes is 2).
size=$(stat -c %s "$work/root/bunny.qnv")
rate=$((size * 4 / (minutes * 60 * 3)))
fault_port=$(free_port)
"$faultd" --root "$work/root" --port "$fault_port" --rate "$rate" --cut $((size / 4)) \
  --fault serve --fault reset --fault stall --fault serve --stall-seconds 5 --verbose \
  > /dev/null 2> "$work/fault_server.log" &
pids+=($!)

display=":$((200 + $$ % 500))"
/usr/bin/Xvfb "$display" -screen 0 1280x960x24 -nolisten tcp &
pids+=($!)
sleep 1

url=http://127.0.0.1:$port
{
  echo "layout 2x2"
  i=0
  for u in "$url/head.qnv" "$url/bunny.qnv" "$url/head_compact.qnv" \
    "http://127.0.0.1:$fault_port/bunny.qnv"; do
    echo "viewport $i"
    echo "open $u"
    echo "auto-lod on"
    echo "frame-target 50"
    i=$((i + 1))
  done
  for _ in 1 2 3 4 5 6 7 8 9 10; do echo "frames 1000000"; done  # at most 10^6 per line
  echo "quit"
} > "$work/soak.script"

export no_proxy=127.0.0.1,localhost NO_PROXY=127.0.0.1,localhost
DISPLAY=$display "$bin" --new-instance --size 1280x960 --script "$work/soak.script" \
  --frame-log "$frames" > "$work/window.log" 2>&1 &
app=$!
pids+=($app)

echo "seconds,rss_kib,load1" > "$out"
end=$((SECONDS + minutes * 60))
t0=$SECONDS
while [ $SECONDS -lt $end ] && kill -0 "$app" 2> /dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$app/status" 2> /dev/null || echo 0)
  echo "$((SECONDS - t0)),$rss,$(cut -d' ' -f1 /proc/loadavg)" >> "$out"
  sleep 1
done
kill -0 "$app" 2> /dev/null || { echo "soak: the window ended early (see $work/window.log)" >&2; exit 1; }
kill "$app"

status=0
echo "Resident memory (MiB) and load average per half minute:"
echo "| minutes | RSS min | RSS max | load (1 min) |"
echo "| --- | --- | --- | --- |"
awk -F, 'NR > 1 { b = int($1 / 30); v = $2 / 1024; if (!(b in lo) || v < lo[b]) lo[b] = v;
                  if (v > hi[b]) hi[b] = v; ld[b] += $3; nl[b]++; n = b }
         END { for (i = 0; i <= n; i++)
                 printf("| %.1f-%.1f | %.0f | %.0f | %.1f |\n", i / 2, i / 2 + 0.5, lo[i], hi[i], ld[i] / nl[i]) }' "$out"
# Growth after the warm-up: the highest sample past it minus the first sample past it.
growth=$(awk -F, -v w="$warmup" 'NR > 1 && $1 >= w { v = $2 / 1024; if (!seen) { first = v; seen = 1 }
                                                       if (v > hi) hi = v }
                                 END { printf("%.1f", seen ? hi - first : 0) }' "$out")
echo "RSS growth after ${warmup} s: $growth MiB (bound $rss_bound MiB)"
awk -v g="$growth" -v b="$rss_bound" 'BEGIN { exit !(g > b) }' && { echo "soak: FAIL: memory grew" >&2; status=1; }

# Frame times: percentiles per minute (the warm-up's too, marked) and over all after it.
echo
echo "Frame times (ms) per minute of the run (* = minute within the ${warmup} s warm-up):"
echo "| minute | frames | p50 | p99 | max | vectors drawn (mean, 4 viewports) |"
echo "| --- | --- | --- | --- | --- | --- |"
percentiles() {  # stdin: "frame_ms vectors" lines -> "frames p50 p99 max vectors"
  sort -g | awk '{ v[NR] = $1; s += $2 } END { if (NR == 0) { print "0 - - - -"; exit }
                  i50 = int(NR * 0.50 + 0.5); i99 = int(NR * 0.99 + 0.5); if (i50 < 1) i50 = 1; if (i99 < 1) i99 = 1
                  printf("%d %.1f %.1f %.1f %.0f\n", NR, v[i50], v[i99], v[NR], s / NR) }'
}
last_minute=$(awk -F, 'NR > 1 { m = int($1 / 60) } END { print m + 0 }' "$frames")
for m in $(seq 0 "$last_minute"); do
  read -r n p50 p99 max vec < <(awk -F, -v m="$m" \
    'NR > 1 && int($1 / 60) == m { print $2, $5 + $6 + $7 + $8 }' "$frames" | percentiles)
  mark=$([ $((m * 60)) -lt "$warmup" ] && echo "*" || true)
  [ "$n" = 0 ] || echo "| $m-$((m + 1))$mark | $n | $p50 | $p99 | $max | $vec |"
done
read -r n p50 p99 max vec < <(awk -F, -v w="$warmup" 'NR > 1 && $1 >= w { print $2, $5 + $6 + $7 + $8 }' \
  "$frames" | percentiles)
echo "| after ${warmup} s | $n | $p50 | $p99 | $max | $vec |"
echo "Longest frame after ${warmup} s: $max ms (bound $frame_bound ms)"
awk -v x="$max" -v b="$frame_bound" 'BEGIN { exit !(x != "-" && x > b) }' &&
  { echo "soak: FAIL: a frame took longer than the bound" >&2; status=1; }

echo
echo "requests served by nginx: $(wc -l < "$work/nginx/access.log")"
echo "fault server:"
sed 's/^/  /' "$work/fault_server.log"
grep -E "reset|stall|closed|fail|resum" "$work/window.log" | sed 's/^/  window: /' | head -20 || true
exit $status
