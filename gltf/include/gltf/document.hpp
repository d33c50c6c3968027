// glTF 2.0 documents (Khronos glTF 2.0 specification, ISO/IEC 12113:2022) read through
// Debian's tinygltf, hardened for untrusted bytes: the GLB container and the JSON depth are
// checked before tinygltf sees them, external files come only through a caller's loader
// (never the file system), and every accessor read is bounds checked (accessors.hpp).
// Used by formats/ (a glTF file as one triangle mesh) and vrml/ (a glTF file as a world).
#pragma once

#include "gltf/detect.hpp"

#include <tiny_gltf.h>

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gs::gltf {

/// A malformed or unreadable glTF asset; what() is "name: what is wrong".
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws Error("name: what").
[[noreturn]] void fail(const std::string& name, const std::string& what);

/// Supplies the bytes behind an external buffer URI (as written in the file, %-escapes
/// decoded), or std::nullopt when it cannot. An exception it throws propagates out of
/// load() unchanged.
using BufferLoader = std::function<std::optional<std::string>(const std::string& uri)>;

/// What load() does with images.
enum class Images {
  skip,  // nothing is kept: image.image stays empty
  /// The encoded bytes of images held in the asset (a data: URI or a GLB bufferView) are
  /// kept, undecoded, in image.image with image.width = -1; images with an external uri
  /// keep their uri and are never requested from the loader.
  keepEncoded,
};

/// Throws Error "name: JSON nested deeper than 64 levels" when `json` nests arrays and
/// objects deeper than that (tinygltf and nlohmann::json recurse without a limit: checked
/// before either parses untrusted JSON).
void checkJsonDepth(std::string_view json, const std::string& name);

/// Reads a glTF 2.0 asset: JSON text, or GLB (detected by isGlb). Buffers may be GLB's
/// BIN chunk, data: URIs, or external URIs resolved only through `loader`. `warnings`,
/// when given, receives tinygltf's warnings (one line each).
///
/// Throws Error "name: ..." on malformed input: JSON errors, GLB chunk errors, JSON nested
/// deeper than 64 levels (tinygltf recurses into extras without a limit), an external
/// buffer the loader cannot supply (naming its URI), input over 4 GiB.
tinygltf::Model load(std::string_view bytes, const std::string& name, const BufferLoader& loader,
                     Images images = Images::skip, std::vector<std::string>* warnings = nullptr);

/// The root nodes to draw (glTF 2.0 clause 3.5.2): those of the default scene, else of
/// scene 0, else every node that is no other node's child. Indices are as written
/// (unchecked).
std::vector<int> sceneRoots(const tinygltf::Model& model);

}  // namespace gs::gltf
