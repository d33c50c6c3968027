// Private to render/: the splat part of a SceneRenderer. QuantizedNormalVectors nodes
// (docs/vrml-extensions.md) load their vectors once through a SplatLoader and draw the
// prefix their level of detail asks for; in RenderMode::splats the polygon world itself
// is drawn as splats (its triangles through the QNV surface encoder).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>

#include "gpu_resources.hpp"
#include "render/splat_renderer.hpp"
#include "render/splat_source.hpp"
#include "scene/traversal.hpp"
#include "volume_raycast.hpp"

namespace gs::base {
class Fetcher;
}

namespace gs::render::detail {

class SceneSplats {
 public:
  SceneSplats(std::shared_ptr<const vrml::Scene> scene, SplatLoader loader, double lod,
              scene::RenderMode mode, SplatPath path = SplatPath::automatic);

  /// The vectors of a QuantizedNormalVectors node: inline ones, or its first url that
  /// loads (resolved against `baseUrl`). Loaded on first use; failures are reported to
  /// `traversal` once. Null when there is nothing to draw.
  std::shared_ptr<const SplatSet> setOf(const vrml::Node& node, const std::string& baseUrl,
                                        scene::SceneTraversal& traversal);
  /// The vectors drawn of `set` for `node`: its count field (>= 0) or fraction of the
  /// set's total() (the whole stream, even while it arrives), times the level of detail
  /// given to the renderer, rounded, at least 1 when the product is positive; then
  /// clamped to the vectors present. Records the prefix wanted in set.wantedVectors.
  std::size_t drawCount(const vrml::Node* node, const SplatSet& set) const;
  /// That prefix before the clamp to the vectors present (0 when nothing is drawn).
  std::uint64_t wantedPrefix(const vrml::Node* node, const SplatSet& set) const;
  /// World bounds of every QNV node of the scene (loads them) and, in splats mode, of the
  /// polygon world.
  vrml::Bounds bounds(scene::SceneTraversal& traversal);
  /// Draws the frame's QNV nodes (and the world's splats in splats mode) over what is in
  /// the framebuffer, and the volume data nodes whose styles need the ray caster
  /// (volume_raycast.hpp; their textures from `textures`). Returns the number of splats
  /// drawn. `heightPixels` is the viewport's height (recorded for view-dependent sets).
  /// `sceneDepth`: whether shapes wrote the depth buffer before (the splats are then
  /// depth-tested against it, SplatBlend::backToFront); without, nothing can hide them and
  /// the cpu path reads no depth back (SplatBlend::frontToBack: the same picture).
  /// `layer`: only the nodes of that X3D layer (SplatInstance::layer; the world's splats in
  /// splats mode are layer 0's), so that each is drawn after its layer's shapes, against
  /// their depth; every node when none is given.
  std::size_t draw(const scene::TraversalFrame& frame, scene::SceneTraversal& traversal,
                   const scene::Camera& camera, float aspect, bool headlight,
                   TextureCache& textures, int heightPixels = 0, bool sceneDepth = true,
                   std::optional<std::uint32_t> layer = std::nullopt);
  scene::RenderMode mode() const { return mode_; }
  /// True when the QNV nodes loaded so far (bounds() loads them) all show volumes (their
  /// sets' stream kind, as their headers say) and there is at least one.
  bool showsVolumesOnly() const {
    bool any = false;
    for (const auto& [node, entry] : sets_) {
      if (!entry.set) continue;
      if (entry.set->gaussians || entry.set->style.kind != qnv::StreamKind::volume) return false;
      any = true;
    }
    return any;
  }
  /// The scene grew (progressive loading): the splats-mode world set is built again when
  /// root nodes were added.
  void sceneChanged() {
    if (scene_->rootNodes.size() != worldRoots_) worldBuilt_ = false;
  }
  void setLod(double lod) { lod_ = lod; }
  /// Where X3D volume data nodes' voxel files load from (null: local files only).
  void setFetcher(base::Fetcher* fetcher) { fetcher_ = fetcher; }
  /// At most this many vectors drawn in all per frame (0: no budget): the level of detail
  /// is lowered to fit (min(lod, budget / vectors of every stream drawn)).
  void setVectorBudget(std::uint64_t budget) { budget_ = budget; }
  void release();

 private:
  std::shared_ptr<const vrml::Scene> scene_;
  SplatLoader loader_;
  base::Fetcher* fetcher_ = nullptr;
  double lod_;
  std::uint64_t budget_ = 0;
  double drawLod_ = 1.0;  // lod_ lowered to the vector budget for the frame being drawn
  scene::RenderMode mode_;
  SplatPath path_ = SplatPath::automatic;  // every SplatRenderer made here takes it
  /// A node's set and the style it is drawn with (the node's mode and opacityScale over
  /// the stream's own; the set itself is shared and may still grow).
  struct NodeSet {
    std::shared_ptr<const SplatSet> set;
    SplatStyle style;
    bool ownStyle = false;
    bool raycast = false;  // a volume data node drawn by the ray caster, not as splats
  };
  const NodeSet& nodeSet(const vrml::Node& node, const std::string& baseUrl,
                         scene::SceneTraversal& traversal);
  vrml::NodeMap<NodeSet> sets_;
  std::map<std::string, std::shared_ptr<const SplatSet>> byUrl_;
  std::shared_ptr<const SplatSet> world_;
  bool worldBuilt_ = false;
  std::size_t worldRoots_ = 0;  // root nodes of the scene when world_ was built
  std::unordered_map<const SplatSet*, std::unique_ptr<SplatRenderer>> renderers_;
  VolumeRaycaster raycaster_;
  /// This renderer's view request on each view-dependent set it drew (released with it:
  /// a closed viewport stops asking for bricks). The sets are kept alive by sets_.
  std::unordered_map<const SplatSet*, std::unique_ptr<SplatViewRequests::Request>> viewRequests_;
};

}  // namespace gs::render::detail
