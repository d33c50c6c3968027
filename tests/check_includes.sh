#!/usr/bin/env bash
# Fails when a module's sources include a header of a module it does not depend on.
# The dependencies are read from the gs_module(...) lines of the top-level CMakeLists.txt
# (gs_module(gs_X X DEPENDS gs_Y gs_Z)); a module may include its own headers and those
# of the modules it depends on, directly or through them. Usage: check_includes.sh [ROOT]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

declare -A deps
modules=()
# One gs_module call per line: gs_module(gs_net net DEPENDS gs_base gs_vrml gs_qnv)
while read -r line; do
  args=${line#*gs_module(}
  args=${args%%)*}
  read -r -a words <<<"$args"
  dir=${words[1]}
  modules+=("$dir")
  list=""
  seen_depends=0
  for w in "${words[@]:2}"; do
    if [[ $w == DEPENDS ]]; then seen_depends=1; continue; fi
    [[ $seen_depends == 1 && $w == gs_* ]] && list+=" ${w#gs_}"
  done
  deps[$dir]=$list
done < <(grep -E '^gs_module\(' CMakeLists.txt)

# The transitive closure of each module's dependencies.
closure() {
  local todo=("$1") out=" $1 " m d
  while ((${#todo[@]})); do
    m=${todo[0]}
    todo=("${todo[@]:1}")
    for d in ${deps[$m]:-}; do
      if [[ $out != *" $d "* ]]; then out+="$d "; todo+=("$d"); fi
    done
  done
  echo "$out"
}

status=0
for m in "${modules[@]}"; do
  allowed=$(closure "$m")
  while IFS=: read -r file lineno text; do
    inc=$(sed -E 's/.*#include "([^"/]+)\/.*/\1/' <<<"$text")
    # Only our modules are checked (other quoted includes are module-private headers).
    [[ " ${modules[*]} " == *" $inc "* ]] || continue
    if [[ $allowed != *" $inc "* ]]; then
      echo "$file:$lineno: module '$m' includes '$inc', which it does not list as a dependency" \
           "(its DEPENDS in CMakeLists.txt:${deps[$m]:- none})"
      status=1
    fi
  done < <(grep -rnE '^#include "[^"/]+/' "$m" --include='*.cpp' --include='*.hpp' || true)
done
# What needs no OpenGL stays free of it: scene/ (traversal, picking, collision, world
# triangles) and the modules above it that draw nothing (outline/: `encode --outline`).
gl=$(grep -rnE '^#include [<"](glad/|GL/|GLFW/|render/)' scene outline --include='*.cpp' --include='*.hpp' || true)
if [[ -n $gl ]]; then
  echo "$gl"
  echo "scene/ and outline/ must not include OpenGL, GLFW or render/ headers (docs/architecture.md)"
  status=1
fi
if ((status == 0)); then echo "check_includes: ${#modules[@]} modules, every include is a listed dependency"; fi
exit $status
