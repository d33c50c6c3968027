#!/usr/bin/env bash
# The window at rest (issue 42, friction 4): CPU time the ghostspace window uses over a
# quiet interval on a static world, under Xvfb, as a share of one core.
#   tests/bench/idle_cpu.sh [GHOSTSPACE] [WORLD] [SECONDS]
# Defaults: build/bin/ghostspace, assets/worlds/welcome.wrl, 10. Prints one line:
#   idle_cpu world=... seconds=10 cpu_percent=1.3 (utime+stime ticks ...)
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=${1:-build/bin/ghostspace}
WORLD=${2:-assets/worlds/welcome.wrl}
SECONDS_MEASURED=${3:-10}
command -v Xvfb >/dev/null || { echo "idle_cpu: Xvfb is not installed" >&2; exit 2; }
DISPLAY_NUMBER=$((90 + RANDOM % 100))
Xvfb ":$DISPLAY_NUMBER" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
XVFB=$!
trap 'kill $XVFB 2>/dev/null || true; [ -n "${GS:-}" ] && kill $GS 2>/dev/null || true' EXIT
sleep 1
DISPLAY=":$DISPLAY_NUMBER" "$BIN" --new-instance --size 800x600 "$WORLD" >/dev/null 2>&1 &
GS=$!
sleep 4  # start-up: load, first frames, ImGui settling
ticks() { awk '{print $14 + $15}' "/proc/$GS/stat"; }
HZ=$(getconf CLK_TCK)
before=$(ticks)
sleep "$SECONDS_MEASURED"
after=$(ticks)
percent=$(awk -v a="$after" -v b="$before" -v hz="$HZ" -v s="$SECONDS_MEASURED" \
  'BEGIN { printf "%.2f", 100 * (a - b) / hz / s }')
echo "idle_cpu world=$WORLD seconds=$SECONDS_MEASURED cpu_percent=$percent (utime+stime ticks $((after - before)) at $HZ Hz)"
