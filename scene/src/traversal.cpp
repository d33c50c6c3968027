// Per-frame scene-graph traversal: shapes with world matrices and scoped lights (the walk
// itself: traversal_walk.hpp).
#include "traversal_walk.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace gs::scene {

void SceneTraversal::collect(const Camera& viewer, TraversalFrame& frame) {
  frame.clear();
  scopeScratch_.clear();
  chainScratch_.clear();
  Walk walk{*this, frame, viewer.position, viewer.up(), scopeScratch_, chainScratch_};
  walk.inlineChain.push_back(&mainUrl_);
  walk.filled = &filledGroups(*scene_);
  firstGlobalEnvironment_ = -1;
  clipScratch_.clear();
  walk.clipScope = &clipScratch_;
  walk.lengthUnit = lengthUnitOf(*scene_);
  walk.camera = viewer;
  walk.worldToEye = viewMatrix(viewer);
  walk.eyeToWorld = glm::inverse(walk.worldToEye);
  walk.orthographic = viewer.orthographic;
  walk.tanHalfFov = std::tan(std::clamp(viewer.fieldOfView, 0.001f, 3.1f) / 2.0f);
  walk.viewPixels = viewportPixels_;
  walk.layouts.assign(1, walk.viewRegion());
  if (viewer.orthographic) walk.layoutPerPixel = walk.layouts.front().metresPerPixel.x;
  walk.group(nullptr, scene_->rootNodes, glm::mat4(1.0f), &mainUrl_, &scene_->rootNodes);
  walk.layers();
  if (firstGlobalEnvironment_ >= 0)
    for (ShapeInstance& s : frame.shapes)
      if (s.environmentLight < 0) s.environmentLight = firstGlobalEnvironment_;
}

void SceneTraversal::report(vrml::Severity severity, const vrml::SourceLocation& where,
                            const std::string& message) {
  vrml::Diagnostic d{severity, where, message};
  std::string key = d.format();
  if (!reported_.insert(std::move(key)).second) return;
  diagnostics_.items.push_back(std::move(d));
}

}  // namespace gs::scene
