#!/usr/bin/env bash
# Soak test (not run in CI; docs/soak.md): the window under Xvfb with four viewports
# (layout 2x2) streaming QNV files from a loopback nginx, automatic level of detail on in
# each, for MINUTES minutes. The window's resident memory (VmRSS) is sampled each second;
# the samples go to OUT.csv (seconds,rss_kib) and a table of one row per 30 s is printed.
#
#   tests/soak/soak.sh MINUTES [OUT.csv]
#
# Needs build/bin/ghostspace (or $GS_BIN), /usr/sbin/nginx, /usr/bin/Xvfb and the corpus
# (../shared/corpus: the CT head and the Stanford bunny are encoded once into
# build/soak/). Memory that stays flat after the first minute means no leak per frame.
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
minutes=${1:?usage: soak.sh MINUTES [OUT.csv]}
out=${2:-$top/build/soak/rss.csv}
bin=${GS_BIN:-$top/build/bin/ghostspace}
corpus=$top/../shared/corpus
work=$top/build/soak
mkdir -p "$work/root"
for tool in "$bin" /usr/sbin/nginx /usr/bin/Xvfb; do
  [ -x "$tool" ] || { echo "soak: $tool is missing" >&2; exit 2; }
done

# The streams: encoded once.
[ -s "$work/root/head.qnv" ] || "$bin" encode "$corpus/volume/cthead/CThead.nhdr" -o "$work/root/head.qnv"
[ -s "$work/root/bunny.qnv" ] || "$bin" encode "$corpus/mesh/bunny/bun_zipper.ply" -o "$work/root/bunny.qnv"
[ -s "$work/root/head_compact.qnv" ] ||
  "$bin" encode "$corpus/volume/cthead/CThead.nhdr" -o "$work/root/head_compact.qnv" --compact

# nginx on a free port, serving build/soak/root.
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
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
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done; }
trap cleanup EXIT
/usr/sbin/nginx -p "$work/nginx" -c "$work/nginx/nginx.conf" -e "$work/nginx/error.log" &
pids+=($!)
display=":$((200 + $$ % 500))"
/usr/bin/Xvfb "$display" -screen 0 1280x960x24 -nolisten tcp &
pids+=($!)
sleep 1

url=http://127.0.0.1:$port
{
  echo "layout 2x2"
  i=0
  for f in head.qnv bunny.qnv head_compact.qnv bunny.qnv; do
    echo "viewport $i"
    echo "open $url/$f"
    echo "auto-lod on"
    echo "frame-target 50"
    i=$((i + 1))
  done
  for _ in 1 2 3 4 5 6 7 8 9 10; do echo "frames 1000000"; done  # at most 10^6 per line
  echo "quit"
} > "$work/soak.script"

export no_proxy=127.0.0.1,localhost NO_PROXY=127.0.0.1,localhost
DISPLAY=$display "$bin" --new-instance --size 1280x960 --script "$work/soak.script" \
  > "$work/window.log" 2>&1 &
app=$!
pids+=($app)

echo "seconds,rss_kib" > "$out"
end=$((SECONDS + minutes * 60))
t0=$SECONDS
while [ $SECONDS -lt $end ] && kill -0 "$app" 2> /dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$app/status" 2> /dev/null || echo 0)
  echo "$((SECONDS - t0)),$rss" >> "$out"
  sleep 1
done
kill -0 "$app" 2> /dev/null || { echo "soak: the window ended early (see $work/window.log)" >&2; exit 1; }

echo "| minute | RSS MiB (min) | RSS MiB (max) |"
echo "| --- | --- | --- |"
awk -F, 'NR > 1 { b = int($1 / 30); v = $2 / 1024;
                  if (!(b in lo) || v < lo[b]) lo[b] = v; if (v > hi[b]) hi[b] = v; n = b }
         END { for (i = 0; i <= n; i++) printf("| %.1f | %.0f | %.0f |\n", i / 2, lo[i], hi[i]) }' "$out"
echo "requests served: $(wc -l < "$work/nginx/access.log")"
