// Where splat sets come from: a decoded .qnv stream, encoder output in memory, the inline
// vectors of a QuantizedNormalVectors node (docs/vrml-extensions.md), or a polygon world
// drawn as splats (--mode splats).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "qnv/encoder.hpp"
#include "render/splat_renderer.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

namespace gs::render {

/// Loads the vectors behind a QuantizedNormalVectors url (already resolved against the
/// world's base URL `referrer`, the URL of the content that names it). Returns null and
/// sets `error` ("head.qnv: not a QNV stream") when nothing can be shown. The set
/// returned may still grow (progressive loading, see SplatSet).
using SplatLoader = std::function<std::shared_ptr<const SplatSet>(
    const std::string& url, const std::string& referrer, std::string& error)>;

/// A local .qnv file decoded whole with qnv::StreamDecoder: damaged packets are skipped
/// (their vectors are missing), a cut-off file gives the vectors that arrived. Null with
/// `error` when the file cannot be read or its header is rejected. `warnings` (may be
/// null) receives the decoder's warnings.
std::shared_ptr<const SplatSet> loadQnvFile(const std::string& path, std::string& error,
                                            std::vector<std::string>* warnings = nullptr);

/// Decodes encoder output in memory (no stream round trip): the same vectors a .qnv file
/// of it would give.
std::shared_ptr<SplatSet> splatSetFromEncoded(const qnv::EncodedVectors& encoded);

/// The inline vectors of a QuantizedNormalVectors node: position (MFVec3f), direction
/// (MFVec3f, normalized here), magnitude (MFFloat, surface: area; missing entries 1) and
/// color (MFColor, missing: white), as a surface set. Null when `position` is empty.
std::shared_ptr<SplatSet> inlineSplatSet(const vrml::Node& node);

/// The inline cloud of a GaussianSplats node (X_ITE's experimental node, the attributes of
/// glTF's KHR_gaussian_splatting; docs/splats.md, "The GaussianSplats node"): positions
/// (MFVec3f, scene units), orientations (MFVec4f, unit quaternions x y z w; missing:
/// identity), scales (MFVec3f, linear standard deviations; missing: 0.01), opacities
/// (MFFloat, 0..1; missing: 1), sphericalHarmonicsDegreeLCoefN (MFVec3f, the SH
/// coefficients; degree L counts when every coefficient of it and of the lower degrees has
/// a value per splat, as X_ITE decides), colorSpace "SRGB_REC709_DISPLAY" (default) or
/// "LIN_REC709_DISPLAY". Sorted by importance, with its level-of-detail tree, as a splat
/// scene file gives. Null when `positions` is empty.
std::shared_ptr<SplatSet> inlineGaussianSet(const vrml::Node& node);

/// A polygon world as splats: every triangle drawn (worldTriangles) through the surface
/// encoder and decoder, so it is exactly what `ghostspace encode` of the world shows.
std::shared_ptr<SplatSet> worldSplatSet(std::shared_ptr<const vrml::Scene> scene);

}  // namespace gs::render
