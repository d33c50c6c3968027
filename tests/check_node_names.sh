#!/usr/bin/env bash
# Fails when a module decides a node's class by comparing its type name with a node type
# name ("Transform", "TimeSensor" ...): classes come from the node model (abstract types
# and NodeTypeId, vrml/node_model.hpp), which only the node table and the generated model
# spell out. Usage: check_node_names.sh [ROOT]
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"
names=$(sed -n 's/^GS_NODE_TYPE(\(.*\))$/\1/p' vrml/include/vrml/node_model_types.inc | paste -sd'|')
[ -n "$names" ] || { echo "no node types in vrml/include/vrml/node_model_types.inc"; exit 1; }
# A comparison with a quoted node type name, or a {"Name", ...} row of a name table.
# runtime/src/script_x3d_info.cpp is left out: its tables name X3D's components, four of
# which (Shape, Text, Sound, Layout) share their names with a node.
pattern="(==|!=) *\"($names)\"|\"($names)\" *(==|!=)|\\{ *\"($names)\" *,"
hits=$(git ls-files 'app/*.cpp' 'app/*.hpp' 'audio/*.cpp' 'audio/*.hpp' 'base/*.cpp' 'base/*.hpp' \
         'formats/*.cpp' 'formats/*.hpp' 'net/*.cpp' 'net/*.hpp' 'outline/*.cpp' 'outline/*.hpp' \
         'qnv/*.cpp' 'qnv/*.hpp' 'render/*.cpp' 'render/*.hpp' 'scene/*.cpp' 'scene/*.hpp' 'runtime/*.cpp' 'runtime/*.hpp' \
         'session/*.cpp' 'session/*.hpp' 'vrml/*.cpp' 'vrml/*.hpp' 'encodings/*.cpp' 'encodings/*.hpp' \
         'geometry/*.cpp' 'geometry/*.hpp' 'gltf/*.cpp' 'gltf/*.hpp' 'splats/*.cpp' 'splats/*.hpp' \
         'encode/*.cpp' 'encode/*.hpp' |
       grep -v -e '^vrml/src/node_table_data.cpp$' -e '^vrml/src/node_model_data_[0-9]*.cpp$' \
         -e '^runtime/src/script_x3d_info.cpp$' |
       xargs grep -nE "$pattern" || true)
if [ -n "$hits" ]; then
  echo "node classes decided by name outside the node table (use NodeTypeId / AbstractType):"
  echo "$hits"
  exit 1
fi
echo "no module lists node type names"
