// Private to gltf/: decoding compressed glTF data into plain buffers after tinygltf has
// parsed the document (document.cpp's load calls these).
#pragma once

#include "gltf/document.hpp"

#include <cstddef>
#include <optional>
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

/// EXT_meshopt_compression's uncompressed "fallback" buffers have no uri (the data exists
/// only compressed), which tinygltf 2.7 rejects. The glTF JSON `json` with each such
/// buffer (extensions.EXT_meshopt_compression.fallback true, no uri) given the uri
/// "gs-meshopt-fallback:BYTELENGTH", which load() serves as that many zero bytes
/// (meshoptFallbackBytes; at most maxMeshoptFallbackBytes() for all of one asset's, also
/// when the asset writes such a uri itself), or "" when nothing needed it or the fallback
/// buffers together exceed that (tinygltf then reports the buffer as missing).
std::string placeMeshoptFallbacks(std::string_view json);

/// 512 MiB: the zero bytes load() serves for one asset's fallback buffers at most.
std::size_t maxMeshoptFallbackBytes();

/// The byte count of a fallback uri written by placeMeshoptFallbacks, else nullopt.
std::optional<std::size_t> meshoptFallbackBytes(std::string_view uri);

/// Decodes every bufferView's EXT_meshopt_compression (meshopt.cpp, Debian's
/// libmeshoptimizer: modes ATTRIBUTES, TRIANGLES, INDICES; filters NONE, OCTAHEDRAL,
/// QUATERNION, EXPONENTIAL) into the bytes of the view's own buffer, and removes the
/// extension from the view. Throws Error "name: EXT_meshopt_compression of bufferView N:
/// ..." for compressed bytes outside their buffer, a stride or count out of range, decoded
/// bytes that do not fit the view, or a damaged stream.
void decodeMeshopt(tinygltf::Model& m, const std::string& name);

}  // namespace gs::gltf::detail
