// Telling a glTF 2.0 asset from other content by its first bytes, without tinygltf.
#pragma once

#include <string_view>

namespace gs::gltf {

/// True when `bytes` start with the GLB magic "glTF" (glTF 2.0 clause 4.4.3).
bool isGlb(std::string_view bytes);

/// True when `bytes` hold a glTF JSON document rather than X3D's JSON encoding: a JSON
/// object whose first member is not "X3D" and that has an "asset" member somewhere.
/// Only a cheap look at the text: load() still validates everything.
bool looksLikeGltfJson(std::string_view bytes);

}  // namespace gs::gltf
