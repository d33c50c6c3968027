// glTF 2.0 as a world (Khronos glTF 2.0; X3D 4.0 clause 9.4.2 lets an Inline load one):
// the asset is loaded by document.hpp and built into X3D nodes the way castle-engine and
// X_ITE convert it: a Transform per glTF node, a Shape per primitive (IndexedTriangleSet,
// IndexedLineSet, PointSet), PhysicalMaterial / UnlitMaterial with ImageTextures,
// Viewpoints for cameras, X3D lights for KHR_lights_punctual, and TimeSensors with
// interpolators and ROUTEs for animations. docs/gltf.md lists what is read. The encodings'
// parseVrml and StreamingParser call it for glTF bytes (encodings/parser.hpp).
#pragma once

#include "base/fetch.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace gs::gltf {

/// What an import may read and build. The parser fills it from its ParseOptions.
struct ImportOptions {
  /// Reads the asset's external buffers and images (base::FetchMode::whole, the asset's URL
  /// as referrer; base::fetcherOr: null reads local files and data: URLs only). Not owned.
  base::Fetcher* fetcher = nullptr;
  int maxNesting = 256;              // glTF nodes nested deeper end the import with an error
  std::size_t maxNodes = 4'000'000;  // X3D nodes built, at most
  /// Called with each completed root node (progressive display); may be empty.
  std::function<void(const vrml::NodePtr&)> onRootNode;
  /// The X3D node type called `name` (encodings/node_types.hpp x3dNodeType): every node
  /// the import builds is of such a type. Required.
  std::function<std::shared_ptr<const vrml::NodeType>(std::string_view name)> nodeType;
};

/// True when `bytes` (already gunzipped) are a GLB or a glTF JSON document.
bool isGltf(std::string_view bytes);

/// Reads the glTF asset `bytes` (named `url`, the base of its relative URIs) into `scene`:
/// root nodes, routes and diagnostics; Scene::x3d.encoding is "glTF". External buffers are
/// read through options.fetcher, whose rules keep a remote asset from reading local files.
/// Never throws for bad content: an error Diagnostic ends the import, and nodes built
/// before it stay (none, for an asset that does not load).
void importGltf(std::string_view bytes, const std::string& url, const ImportOptions& options,
                vrml::Scene& scene);

}  // namespace gs::gltf
