// X3D Layering (clause 35) and Layout's LayoutLayer (clause 36.4.2) in the collect() walk
// (traversal_walk.hpp).
#include "traversal_walk.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace gs::scene {

void SceneTraversal::Walk::layers() {
  const vrml::Node* set = nullptr;
  for (const vrml::NodePtr& n : self.scene_->rootNodes)
    if (n && nodeKind(*n) == NodeKind::LayerSet) {
      set = n.get();
      break;
    }
  if (set == nullptr) return;
  const auto& list = set->mfnode("layers");
  const auto isLayer = [](const vrml::Node& l) {
    const NodeKind k = nodeKind(l);
    return (k == NodeKind::Layer || k == NodeKind::LayoutLayer) && sfBool(l, "visible", true);
  };
  const int active = set->get<vrml::FieldType::SFInt32>("activeLayer", 0);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i] || !isLayer(*list[i])) continue;
    layer = static_cast<std::uint32_t>(i + 1);
    const auto& children = list[i]->mfnode("children");
    if (nodeKind(*list[i]) == NodeKind::LayoutLayer) {
      // Seen through its own first Viewpoint or OrthoViewpoint when it holds one (35.2.1),
      // else through X_ITE's default OrthoViewpoint.
      if (const std::optional<Camera> own = firstViewpointCamera(children))
        layerWithOwnView(*list[i], children, *own);
      else
        layoutLayer(*list[i], children);
    } else if (static_cast<int>(i) + 1 == active) {
      group(list[i].get(), children, glm::mat4(1.0f), &self.mainUrl_, &children);
    } else {
      // A layer other than the active one is seen from its own first Viewpoint, else
      // from the default one (X3D 4.0 clause 35.2.1: each layer has its own bindable
      // stacks; 23.4.6: the default Viewpoint at 0 0 10), not from the user's.
      const std::optional<Camera> own = firstViewpointCamera(children);
      layerWithOwnView(*list[i], children, own ? *own : Camera{});
    }
  }
  layer = 0;
  for (const std::int32_t index : fieldRef<vrml::FieldType::MFInt32>(*set, "order", kNoOrder)) {
    LayerInstance l;
    if (index < 0 || static_cast<std::size_t>(index) > list.size()) continue;
    if (index > 0) {
      const vrml::NodePtr& n = list[static_cast<std::size_t>(index) - 1];
      if (!n || !isLayer(*n)) continue;
      l.node = n.get();
      if (index != active) l.headlight = firstNavigationHeadlight(n->mfnode("children")) ? 1 : 0;
      if (const vrml::NodePtr& v = n->sfnode("viewport"); v && !v->unresolved) {
        const std::vector<float>& c = mfFloat(*v, "clipBoundary");
        for (std::size_t k = 0; k < 4 && k < c.size(); ++k)
          if (std::isfinite(c[k]))
            l.clipBoundary[static_cast<int>(k)] = std::clamp(c[k], 0.0f, 1.0f);
      }
    }
    l.number = static_cast<std::uint32_t>(index);
    frame.layerOrder.push_back(l);
  }
}

void SceneTraversal::Walk::layerWithOwnView(const vrml::Node& l,
                                            const std::vector<vrml::NodePtr>& children,
                                            const Camera& own) {
  const glm::mat4 outerEyeToWorld = eyeToWorld, outerWorldToEye = worldToEye;
  const bool outerOrtho = orthographic;
  glm::mat4 layerEyeToWorldEye(1.0f);
  if (own.orthographic || camera.orthographic) {
    const glm::vec4 r = own.orthographic ? own.orthoRegion : glm::vec4(-1, -1, 1, 1);
    const float half = std::max(std::min(r.z - r.x, r.w - r.y) / 2.0f, 1e-6f);
    const float distance = 2.0f * camera.nearClip;
    const float k = camera.orthographic ? std::min(camera.orthoRegion.z - camera.orthoRegion.x,
                                                   camera.orthoRegion.w - camera.orthoRegion.y) /
                                              2.0f
                                        : distance * tanHalfFov;
    layerEyeToWorldEye =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance)) *
        glm::scale(glm::mat4(1.0f), glm::vec3(k / half, k / half, k / half * 1e-3f)) *
        glm::translate(glm::mat4(1.0f), glm::vec3(-(r.x + r.z) / 2.0f, -(r.y + r.w) / 2.0f, 0.0f));
    orthographic = true;
  } else {
    const float s = tanHalfFov / std::tan(std::clamp(own.fieldOfView, 0.001f, 3.1f) / 2.0f);
    layerEyeToWorldEye = glm::scale(glm::mat4(1.0f), glm::vec3(s, s, 1.0f));
  }
  eyeToWorld = outerEyeToWorld * layerEyeToWorldEye;
  worldToEye = glm::inverse(eyeToWorld);
  // The layer's own field of view measures its pixels (ScreenGroup, PIXEL layouts).
  const float outerTanHalfFov = tanHalfFov;
  const float outerPerPixel = layoutPerPixel;
  auto outerLayouts = std::move(layouts);
  if (!orthographic) tanHalfFov = std::tan(std::clamp(own.fieldOfView, 0.001f, 3.1f) / 2.0f);
  // Its top-level layouts lay out in its own view: the orthographic region, or the viewport
  // at the near distance (viewRegion's rule, with the layer's view).
  const glm::vec4 region = own.orthographic ? own.orthoRegion : glm::vec4(-1, -1, 1, 1);
  layouts.assign(
      1, viewRectangle(viewPixels, orthographic ? std::min(region.z - region.x, region.w - region.y)
                                                : 2.0f * camera.nearClip * tanHalfFov));
  if (orthographic) layoutPerPixel = layouts.front().metresPerPixel.x;
  const glm::mat4 layerToWorld = eyeToWorld * viewMatrix(own);
  if (nodeKind(l) == NodeKind::LayoutLayer) {
    const vrml::NodePtr& layout = l.sfnode("layout");
    layoutGroup(&l, layout && !layout->unresolved ? layout.get() : nullptr, children, layerToWorld,
                &self.mainUrl_);
  } else {
    group(&l, children, layerToWorld, &self.mainUrl_, &children);
  }
  eyeToWorld = outerEyeToWorld;
  worldToEye = outerWorldToEye;
  orthographic = outerOrtho;
  tanHalfFov = outerTanHalfFov;
  layoutPerPixel = outerPerPixel;
  layouts = std::move(outerLayouts);
}

void SceneTraversal::Walk::layoutLayer(const vrml::Node& l,
                                       const std::vector<vrml::NodePtr>& children) {
  const glm::mat4 outerEyeToWorld = eyeToWorld, outerWorldToEye = worldToEye;
  const bool outerOrtho = orthographic;
  const float outerPerPixel = layoutPerPixel;
  auto outerLayouts = std::move(layouts);
  // The world camera's view plane at distance D: a layer metre is k world-eye metres.
  const float distance = 2.0f * camera.nearClip;
  const float k = camera.orthographic ? std::min(camera.orthoRegion.z - camera.orthoRegion.x,
                                                 camera.orthoRegion.w - camera.orthoRegion.y) /
                                            2.0f
                                      : distance * tanHalfFov;
  const glm::mat4 layerEyeToWorldEye =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance)) *
      glm::scale(glm::mat4(1.0f), glm::vec3(k, k, k * 1e-3f)) *
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 10.0f));
  eyeToWorld = outerEyeToWorld * layerEyeToWorldEye;
  worldToEye = glm::inverse(eyeToWorld);
  orthographic = true;
  const LayoutRectangle region = viewRectangle(viewPixels, 2.0f);  // the region -1 .. 1
  layoutPerPixel = region.metresPerPixel.x;
  layouts.assign(1, region);
  const glm::mat4 layerToWorld = eyeToWorld * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -10));
  const vrml::NodePtr& layout = l.sfnode("layout");
  layoutGroup(&l, layout && !layout->unresolved ? layout.get() : nullptr, children, layerToWorld,
              &self.mainUrl_);
  eyeToWorld = outerEyeToWorld;
  worldToEye = outerWorldToEye;
  orthographic = outerOrtho;
  layoutPerPixel = outerPerPixel;
  layouts = std::move(outerLayouts);
}

}  // namespace gs::scene
