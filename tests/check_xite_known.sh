#!/usr/bin/env bash
# Fails when tests/bench/x3d_vs_xite.known (the worlds that differ from X_ITE's picture, with
# the cause; read by tests/bench/x3d_vs_peer.sh xite) has a line that the bench cannot use: not
# three tab-separated columns, TIMES not "*" or numbers, an empty cause, a world named twice,
# or a world that is not an X3D file of the corpus. Usage: check_xite_known.sh [ROOT [CORPUS]]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
corpus=${2:-$root/../shared/corpus/x3d}
known=$root/tests/bench/x3d_vs_xite.known
if [ ! -d "$corpus" ]; then
  case ${CI:-} in '' | 0 | false)
    [ "${GS_REQUIRE_ALL:-}" = 1 ] || { echo "GS_SKIP: corpus: $corpus is absent"; exit 0; } ;;
  esac
  echo "missing fixture: $corpus (CI or GS_REQUIRE_ALL=1 requires every fixture)"
  exit 1
fi
bad=0 lines=0
declare -A seen=()
line=0
while IFS= read -r text || [ -n "$text" ]; do
  line=$((line + 1))
  case $text in '' | '#'*) continue ;; esac
  lines=$((lines + 1))
  IFS=$'\t' read -r world times cause extra <<< "$text"
  where="$known:$line"
  if [ -n "${extra:-}" ] || [ -z "${cause:-}" ]; then
    echo "$where: expected WORLD<TAB>TIMES<TAB>CAUSE, got '$text'"; bad=1; continue
  fi
  [[ $times == '*' || $times =~ ^[0-9.]+( [0-9.]+)*$ ]] ||
    { echo "$where: expected TIMES '*' or numbers, got '$times'"; bad=1; }
  case $world in *.x3d | *.x3dv | *.x3dz | *.x3dvz | *.x3dj) ;; *)
    echo "$where: expected an X3D file, got '$world'"; bad=1 ;;
  esac
  [ -f "$corpus/$world" ] || { echo "$where: no such world in $corpus: $world"; bad=1; }
  [ -z "${seen[$world]:-}" ] || { echo "$where: $world is also on line ${seen[$world]}"; bad=1; }
  seen[$world]=$line
done < "$known"
[ "$lines" -gt 0 ] || { echo "$known: no worlds"; exit 1; }
[ "$bad" = 0 ] || exit 1
echo "$lines worlds with a cause, every one in the corpus"
