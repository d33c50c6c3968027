// Private to gltf/: decoding compressed glTF data into plain buffers after tinygltf has
// parsed the document (document.cpp's load calls these).
#pragma once

#include "gltf/document.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace gs::gltf::detail {

/// Points accessor `a` at a new buffer and buffer view holding `bytes` bytes copied from
/// `data`: `count` elements of `componentType` (tightly packed, not normalized, not sparse,
/// byteOffset 0). The accessor's type (SCALAR, VEC3 ...) is kept.
void replaceAccessorData(tinygltf::Model& m, tinygltf::Accessor& a, int componentType,
                         std::size_t count, const void* data, std::size_t bytes);

/// tinygltf 2.7 rejects a primitive whose indices accessor has no bufferView, which is
/// how KHR_draco_mesh_compression writes them (the data is in the compressed stream). The
/// glTF JSON `json` with each such accessor of a Draco primitive given the primitive's
/// compressed bufferView as a placeholder (decodeDraco replaces it), or "" when nothing
/// needed it (no Draco primitive, or JSON tinygltf will report as malformed anyway).
std::string placeDracoAccessors(std::string_view json);

/// Decodes every primitive's KHR_draco_mesh_compression (draco.cpp) with Debian's libdraco:
/// its indices accessor then holds UNSIGNED_INT indices and each attribute it names FLOAT
/// values, and the extension is removed from the primitive. Throws Error "name: ..." for a
/// missing buffer view, buffer, accessor or Draco attribute, a stream Draco rejects, or more
/// than 2^26 points or faces.
void decodeDraco(tinygltf::Model& m, const std::string& name);

}  // namespace gs::gltf::detail
