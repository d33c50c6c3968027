// Private to render/: X3D's VolumeRendering data nodes (ISO/IEC 19775-1 X3D 4.0 clause 41)
// drawn the paper's way: the voxels of their Texturing3D texture become one gradient
// vector per voxel (Beyond VRML section 3.2, qnv::encodeVolume), sorted largest first and
// splatted front to back by equation (1), with the level of detail QNV gives.
//
// - VolumeData (41.4.6) and SegmentedVolumeData (41.4.5, its segments not told apart): every
//   voxel with a gradient. An OpacityMapVolumeStyle whose transferFunction is a
//   PixelTexture colours the values by it (its texels stretched over the 256 palette
//   slices of the value range); otherwise the stream's default transfer function.
// - IsoSurfaceVolumeData (41.4.3): only voxels whose value lies within surfaceTolerance
//   (5% of the value range when 0) of a surfaceValues entry: the gradient vectors of the
//   iso-surfaces.
//
// The volume fills the box `dimensions` (metres) centred at the node's origin: voxel
// (i, j, k) of an N x M x L grid sits at -dimensions / 2 + (i + 0.5, j + 0.5, k + 0.5) *
// dimensions / (N, M, L).
//
// Voxels come from a PixelTexture3D (clause 33.4.4: components, width, height, depth, then
// the pixels; grey and grey-alpha read their grey, RGB(A) its luminance), an ImageTexture3D
// (33.4.3) whose url is a NRRD file (raw, gzip or ascii; its data attached, or in a file
// beside the header, fetched by the same rules; the formats/ reader), or a ComposedTexture3D
// (33.4.1) of 2D ImageTextures and PixelTextures, one slice each, as grey.
#pragma once

#include "render/splat_renderer.hpp"
#include "vrml/node.hpp"

#include <memory>
#include <string>

namespace gs::base {
class Fetcher;
}

namespace gs::render::detail {

/// Whether `node` is a VolumeData, IsoSurfaceVolumeData or SegmentedVolumeData.
bool isVolumeDataNode(const vrml::Node& node);

struct VolumeDataSet {
  std::shared_ptr<SplatSet> set;  // null: nothing to draw (see problem) or pending
  bool pending = false;           // the voxels' file is still on its way: ask again
  std::string problem;            // why nothing is drawn, for an error at the node
};

/// The vectors of volume data node `node`; its textures' urls resolve against `baseUrl`
/// and load through `fetcher` (null: local files only, as base::fetcherOr gives). Never
/// throws for bad voxels: a malformed PixelTexture3D or an unreadable file is a problem.
VolumeDataSet volumeDataSet(const vrml::Node& node, const std::string& baseUrl,
                            base::Fetcher* fetcher);

}  // namespace gs::render::detail
