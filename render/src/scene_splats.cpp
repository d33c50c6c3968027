#include "scene_splats.hpp"

#include "volume_data.hpp"
#include "volume_style_glsl.hpp"

#include "base/url.hpp"

#include <cmath>

namespace gs::render::detail {

SceneSplats::SceneSplats(std::shared_ptr<const vrml::Scene> scene, SplatLoader loader, double lod,
                         scene::RenderMode mode, SplatPath splatPath)
    : scene_(std::move(scene)),
      loader_(std::move(loader)),
      lod_(lod),
      drawLod_(lod),
      mode_(mode),
      path_(splatPath) {
  if (!loader_)
    loader_ = [](const std::string& url, const std::string&,
                 std::string& error) -> std::shared_ptr<const SplatSet> {
      const std::string path = base::localPathOfUrl(url);
      if (path.empty()) {
        error = "cannot read " + url + ": only local files are supported here";
        return nullptr;
      }
      return loadQnvFile(path, error);
    };
}

std::shared_ptr<const SplatSet> SceneSplats::setOf(const vrml::Node& node,
                                                   const std::string& baseUrl,
                                                   scene::SceneTraversal& traversal) {
  return nodeSet(node, baseUrl, traversal).set;
}

const SceneSplats::NodeSet& SceneSplats::nodeSet(const vrml::Node& node, const std::string& baseUrl,
                                                 scene::SceneTraversal& traversal) {
  if (auto it = sets_.find(&node); it != sets_.end()) {
    // A set read in the background that failed (reported once: report() keeps one of each).
    if (const auto& set = it->second.set; set && !set->loadError.empty())
      traversal.report(vrml::Severity::error, node.location,
                       node.typeName() + ": no url could be loaded: " + set->loadError);
    return it->second;
  }
  if (isVolumeDataNode(node) && needsVolumeRaycast(node)) {
    NodeSet entry;
    entry.raycast = true;
    return sets_[&node] = entry;
  }
  if (isVolumeDataNode(node)) {
    VolumeDataSet volume = volumeDataSet(node, baseUrl, fetcher_);
    if (volume.pending) {
      static const NodeSet kNothingYet;  // asked again at the next draw
      return kNothingYet;
    }
    if (!volume.problem.empty())
      traversal.report(vrml::Severity::error, node.location, volume.problem + ": not drawn");
    NodeSet entry;
    entry.set = std::move(volume.set);
    return sets_[&node] = entry;
  }
  const bool gaussianNode = node.typeId() == vrml::NodeTypeId::GaussianSplats;
  std::shared_ptr<const SplatSet> set =
      gaussianNode ? inlineGaussianSet(node) : inlineSplatSet(node);
  if (!set) {
    const auto urls = node.get<vrml::FieldType::MFString>("url", std::vector<std::string>{});
    std::string errors;
    for (const std::string& url : urls) {
      const std::string resolved = base::resolveUrl(baseUrl, url);
      if (auto it = byUrl_.find(resolved); it != byUrl_.end()) {
        set = it->second;
        break;
      }
      std::string error;
      set = loader_(resolved, baseUrl, error);
      if (set) {
        byUrl_[resolved] = set;
        break;
      }
      errors += (errors.empty() ? "" : "; ") + error;
    }
    if (!set && !urls.empty())
      traversal.report(vrml::Severity::error, node.location,
                       node.typeName() + ": no url could be loaded: " + errors);
  }
  NodeSet entry;
  entry.set = set;
  if (set) {
    // A mode field overrides the stream's kind (how the vectors are splatted).
    const std::string mode = node.get<vrml::FieldType::SFString>("mode", std::string());
    const float opacity = node.get<vrml::FieldType::SFFloat>("opacityScale", 1.0f);
    if (!mode.empty() || opacity != 1.0f) {
      entry.ownStyle = true;
      entry.style = set->style;
      if (mode == "SURFACE") entry.style.kind = qnv::StreamKind::surface;
      if (mode == "VOLUME") entry.style.kind = qnv::StreamKind::volume;
      entry.style.opacityScale *= std::max(opacity, 0.0f);
    }
  }
  return sets_[&node] = entry;
}

std::size_t SceneSplats::drawCount(const vrml::Node* node, const SplatSet& set) const {
  const std::uint64_t prefix = wantedPrefix(node, set);
  set.wantedVectors = std::max(set.wantedVectors, prefix);
  return static_cast<std::size_t>(std::min<std::uint64_t>(prefix, set.size()));
}

std::uint64_t SceneSplats::wantedPrefix(const vrml::Node* node, const SplatSet& set) const {
  const double size = static_cast<double>(set.total());
  double n = size;
  if (node != nullptr) {
    const int count = node->get<vrml::FieldType::SFInt32>("count", -1);
    const float fraction = node->get<vrml::FieldType::SFFloat>("fraction", 1.0f);
    n = count >= 0 ? std::min<double>(count, size) : std::clamp<double>(fraction, 0.0, 1.0) * size;
  }
  const double wanted = n * std::clamp(drawLod_, 0.0, 1.0);
  if (wanted <= 0.0 || size <= 0.0) return 0;
  return std::clamp<std::uint64_t>(static_cast<std::uint64_t>(std::llround(wanted)), 1,
                                   set.total());
}

vrml::Bounds SceneSplats::bounds(scene::SceneTraversal& traversal) {
  vrml::Bounds b;
  scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  for (const scene::SplatInstance& s : frame.splats) {
    const NodeSet& entry = nodeSet(*s.node, *s.baseUrl, traversal);
    vrml::Bounds local;
    if (entry.raycast) {  // the box `dimensions`
      const glm::vec3 half =
          0.5f * s.node->get<vrml::FieldType::SFVec3f>("dimensions", glm::vec3(1.0f));
      local.extend(-half);
      local.extend(half);
    } else if (entry.set && !entry.set->bounds.empty()) {
      local = entry.set->bounds;
    } else {
      continue;
    }
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? local.max.x : local.min.x,
                        (corner & 2) ? local.max.y : local.min.y,
                        (corner & 4) ? local.max.z : local.min.z);
      b.extend(glm::vec3(s.model * glm::vec4(p, 1.0f)));
    }
  }
  return b;
}

std::size_t SceneSplats::draw(const scene::TraversalFrame& frame, scene::SceneTraversal& traversal,
                              const scene::Camera& camera, float aspect, bool headlight,
                              TextureCache& textures, int heightPixels, bool sceneDepth,
                              std::optional<std::uint32_t> layer) {
  SplatLight lights[8];
  std::size_t lightCount = 0;
  if (headlight) lights[lightCount++] = {camera.forward(), glm::vec3(1.0f)};
  for (const scene::LightInstance& l : frame.lights)
    if (l.type == scene::LightType::directional && lightCount < 8)
      lights[lightCount++] = {l.direction, l.color * l.intensity};
  const std::span<const SplatLight> lit(lights, lightCount);
  std::size_t drawn = 0;
  // The vector budget: the same fraction of every stream, small enough to fit.
  drawLod_ = lod_;
  if (budget_ > 0) {
    double total = 0.0;
    for (const scene::SplatInstance& s : frame.splats)
      if (const NodeSet& e = nodeSet(*s.node, *s.baseUrl, traversal); e.set)
        total += static_cast<double>(e.set->total());
    if (mode_ == scene::RenderMode::splats && world_) total += static_cast<double>(world_->total());
    if (total > 0.0) drawLod_ = std::min(lod_, static_cast<double>(budget_) / total);
  }
  const glm::mat4 view = scene::viewMatrix(camera);
  auto drawSet = [&](const SplatSet& set, std::size_t count, const glm::mat4& model,
                     const SplatStyle* style, std::span<const glm::vec4> clipPlanes,
                     const SplatFog& fog) {
    auto& renderer = renderers_[&set];
    if (!renderer) {
      renderer = std::make_unique<SplatRenderer>();
      renderer->setPath(path_);
    }
    renderer->setClipPlanes(clipPlanes);
    renderer->setFog(fog);
    renderer->draw(set, count, model, camera, aspect, lit,
                   sceneDepth ? SplatBlend::backToFront : SplatBlend::frontToBack, style);
    drawn += renderer->statistics().splats;
  };
  if (mode_ == scene::RenderMode::splats && (!layer || *layer == 0)) {
    if (!worldBuilt_) {
      if (world_) renderers_.erase(world_.get());  // its address may be reused
      world_ = worldSplatSet(scene_);
      worldBuilt_ = true;
      worldRoots_ = scene_->rootNodes.size();
    }
    if (world_)
      drawSet(*world_, drawCount(nullptr, *world_), glm::mat4(1.0f), nullptr, {},
              splatFogOf(traversal.fog(), view));
  }
  for (const scene::SplatInstance& s : frame.splats) {
    if (layer && s.layer != *layer) continue;
    const NodeSet& entry = nodeSet(*s.node, *s.baseUrl, traversal);
    const std::span<const glm::vec4> clipPlanes(frame.scopedClipPlanes.data() + s.clipPlaneBegin,
                                                s.clipPlaneCount);
    const SplatFog fog = splatFogOf(
        s.localFog >= 0 ? frame.localFogs[static_cast<std::size_t>(s.localFog)] : traversal.fog(),
        view);
    if (entry.raycast) {
      raycaster_.draw(*s.node, *s.baseUrl, s.model, camera, aspect, frame.lights, headlight,
                      {clipPlanes, fog}, textures, traversal, fetcher_);
      continue;
    }
    if (!entry.set) continue;
    const std::size_t count = drawCount(s.node, *entry.set);
    if (entry.set->viewDependent) {
      auto& request = viewRequests_[entry.set.get()];
      if (!request) request = entry.set->viewRequests->request();
      request->update({camera, s.model, aspect, heightPixels, wantedPrefix(s.node, *entry.set)});
    }
    if (const SplatSet* merged = entry.set->merged.get(); merged && merged->size() > 0) {
      SplatStyle style = merged->style;  // a node's opacityScale applies to it too
      if (entry.ownStyle && entry.set->style.opacityScale > 0.0f)
        style.opacityScale *= entry.style.opacityScale / entry.set->style.opacityScale;
      drawSet(*merged, merged->size(), s.model, &style, clipPlanes, fog);
    }
    drawSet(*entry.set, count, s.model, entry.ownStyle ? &entry.style : nullptr, clipPlanes, fog);
  }
  return drawn;
}

void SceneSplats::release() {
  raycaster_.release();
  for (auto& [set, renderer] : renderers_) renderer->release();
  renderers_.clear();
}

}  // namespace gs::render::detail
