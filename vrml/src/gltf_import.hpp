// glTF 2.0 as a world (Khronos glTF 2.0; X3D 4.0 clause 9.4.2 lets an Inline load one):
// the asset is loaded by gltf/ and built into X3D nodes the way castle-engine and X_ITE
// convert it: a Transform per glTF node, a Shape per primitive (IndexedTriangleSet,
// IndexedLineSet, PointSet), PhysicalMaterial / UnlitMaterial with ImageTextures,
// Viewpoints for cameras, X3D lights for KHR_lights_punctual, and TimeSensors with
// interpolators and ROUTEs for animations. docs/gltf.md lists what is read.
#pragma once

#include "vrml/parser.hpp"

#include "gltf/detect.hpp"

#include <string>
#include <string_view>

namespace gs::vrml::parsing {

/// True when `bytes` (already gunzipped) are a GLB or a glTF JSON document.
bool isGltf(std::string_view bytes);

/// Reads the glTF asset `bytes` (named `url`, the base of its relative URIs) into `scene`:
/// root nodes, routes and diagnostics; Scene::x3d.encoding is "glTF". External buffers are
/// read through options.fetcher (base::fetcherOr), whose rules keep a remote asset
/// from reading local files. Never throws for bad content: an error Diagnostic ends the
/// import, and nodes built before it stay (none, for an asset that does not load).
void importGltf(std::string_view bytes, const std::string& url, const ParseOptions& options,
                Scene& scene);

}  // namespace gs::vrml::parsing
