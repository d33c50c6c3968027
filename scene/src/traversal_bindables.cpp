// SceneTraversal set-up: the main URL and the bindable nodes (Viewpoint, NavigationInfo,
// Background, Fog; clauses 4.6.10, 6.29, 6.5, 6.19, 6.53).
#include "base/url.hpp"
#include "geospatial/geo_system.hpp"
#include "scene/node_access.hpp"
#include "scene/node_kind.hpp"
#include "scene/traversal.hpp"
#include "vrml/geo_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace gs::scene {

namespace {

// Depth-first search for bindable nodes through every child list (all Switch choices and
// LOD levels: binding does not depend on what is drawn; a LayerSet's active layer), not into
// Inline files.
// `groups` holds the ViewpointGroups around the node visited, outermost first, each with
// the transform its children are under.
using ViewpointGroups = std::vector<std::pair<const vrml::Node*, glm::mat4>>;

template <class Visit>
void forEachBindable(const std::vector<vrml::NodePtr>& list, const glm::mat4& m, int depth,
                     Visit& visit, ViewpointGroups& groups) {
  if (depth > 1000) return;
  for (const vrml::NodePtr& n : list) {
    if (!n) continue;
    if (n->typeId() == vrml::NodeTypeId::ViewpointGroup) {  // X3D 4.0 clause 23.4.6
      groups.emplace_back(n.get(), m);
      forEachBindable(n->mfnode("children"), m, depth + 1, visit, groups);
      groups.pop_back();
      continue;
    }
    const NodeKind kind = nodeKind(*n);
    switch (kind) {
      case NodeKind::Transform:
        forEachBindable(n->mfnode("children"), m * transformMatrix(*n), depth + 1, visit, groups);
        break;
      case NodeKind::HAnimHumanoid:  // viewpoints in its skeleton's sites
        forEachBindable(n->mfnode("skeleton"), m * transformMatrix(*n), depth + 1, visit, groups);
        break;
      case NodeKind::Anchor:
      case NodeKind::Billboard:  // its rotation depends on the viewer: ignored here
      case NodeKind::Collision:
      case NodeKind::Group:
        forEachBindable(n->mfnode("children"), m, depth + 1, visit, groups);
        break;
      case NodeKind::Switch:
        forEachBindable(n->mfnode("choice"), m, depth + 1, visit, groups);
        break;
      case NodeKind::LOD:
        forEachBindable(n->mfnode("level"), m, depth + 1, visit, groups);
        break;
      case NodeKind::LayerSet: {
        // X3D 4.0 clause 35.4.2: the bindables the user meets are the active layer's
        // (activeLayer 1..N: layers[activeLayer - 1]; 0: the root layer, the nodes outside
        // the LayerSet, met anyway). Other layers' bindables are not bound here.
        const auto& layers = n->mfnode("layers");
        const int active = n->get<vrml::FieldType::SFInt32>("activeLayer", 0);
        if (active >= 1 && static_cast<std::size_t>(active) <= layers.size()) {
          const vrml::NodePtr& layer = layers[static_cast<std::size_t>(active - 1)];
          if (layer) forEachBindable(layer->mfnode("children"), m, depth + 1, visit, groups);
        }
        break;
      }
      case NodeKind::Viewpoint:
      case NodeKind::NavigationInfo:
      case NodeKind::Background:
      case NodeKind::Fog:
        visit(*n, kind, m, groups);
        break;
      default:
        break;
    }
  }
}

std::vector<glm::vec3> colorsOr(const std::vector<glm::vec3>& colors, glm::vec3 fallback) {
  return colors.empty() ? std::vector<glm::vec3>{fallback} : colors;
}

}  // namespace

Camera viewpointCamera(const vrml::Node& n, const glm::mat4& m) {
  Camera camera;
  camera.position = glm::vec3(m * glm::vec4(sfVec3(n, "position", glm::vec3(0, 0, 10)), 1.0f));
  glm::quat local = glm::quat_cast(
      glm::mat3(rotationMatrix(sfRotation(n, "orientation", vrml::Rotation(0, 0, 1, 0)))));
  if (n.typeId() == vrml::NodeTypeId::GeoViewpoint) {
    // X3D 4.0 clause 25.4.10: a geo position; the orientation is relative to the up
    // frame there (+Y up, +X east), as X_ITE turns it.
    const glm::dvec3 geo =
        n.get<vrml::FieldType::SFVec3d>("position", glm::dvec3(0.0, 0.0, 100000.0));
    const glm::dmat4 location = vrml::geoLocationMatrix(n, geo);
    camera.position = glm::vec3(m * glm::vec4(glm::vec3(location[3]), 1.0f));
    local = glm::normalize(glm::quat_cast(glm::mat3(location)) * local);
  }
  camera.orientation = glm::normalize(glm::quat_cast(rotationPart(m)) * local);
  // The scale and shear the turn leaves (Camera::deform): orientation * deform is the
  // Transforms' linear part times the Viewpoint's own orientation.
  const glm::mat3 deform =
      glm::transpose(glm::mat3_cast(camera.orientation)) * glm::mat3(m) * glm::mat3_cast(local);
  constexpr float kSame = 1e-5f;
  bool identity = true;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      identity = identity && std::abs(deform[c][r] - (c == r ? 1.0f : 0.0f)) < kSame;
  // Kept only when it is usable: not flattened (a scale of 0 leaves the turn alone) and
  // not a mirror (the renderer's winding is counterclockwise for every shape).
  const float det = glm::determinant(deform);
  const float size =
      std::max({glm::length(deform[0]), glm::length(deform[1]), glm::length(deform[2])});
  if (!identity && det > 1e-6f * size * size * size && std::isfinite(det)) camera.deform = deform;
  if (n.typeId() == vrml::NodeTypeId::OrthoViewpoint) {
    // X3D 4.0 clause 23.4.5: fieldOfView (minX, minY, maxX, maxY), default -1 -1 1 1.
    const std::vector<float>& f = mfFloat(n, "fieldOfView");
    camera.orthographic = true;
    if (f.size() >= 4 && std::isfinite(f[0]) && std::isfinite(f[1]) && std::isfinite(f[2]) &&
        std::isfinite(f[3]) && f[2] != f[0] && f[3] != f[1])
      camera.orthoRegion = glm::vec4(f[0], f[1], f[2], f[3]);
  } else {
    camera.fieldOfView = sfFloat(n, "fieldOfView", 0.785398f);
  }
  return camera;
}

std::optional<Camera> firstViewpointCamera(const std::vector<vrml::NodePtr>& nodes) {
  std::optional<Camera> found;
  auto visit = [&](const vrml::Node& n, NodeKind kind, const glm::mat4& m, const ViewpointGroups&) {
    if (kind == NodeKind::Viewpoint && !found) found = viewpointCamera(n, m);
  };
  ViewpointGroups groups;
  forEachBindable(nodes, glm::mat4(1.0f), 0, visit, groups);
  return found;
}

bool firstNavigationHeadlight(const std::vector<vrml::NodePtr>& nodes) {
  std::optional<bool> found;
  auto visit = [&](const vrml::Node& n, NodeKind kind, const glm::mat4&, const ViewpointGroups&) {
    if (kind == NodeKind::NavigationInfo && !found) found = sfBool(n, "headlight", true);
  };
  ViewpointGroups groups;
  forEachBindable(nodes, glm::mat4(1.0f), 0, visit, groups);
  return found.value_or(true);
}

SceneTraversal::SceneTraversal(std::shared_ptr<const vrml::Scene> scene, TraversalOptions options)
    : scene_(std::move(scene)), options_(std::move(options)) {
  if (!scene_) scene_ = std::make_shared<const vrml::Scene>();
  mainUrl_ = scene_->url;
  const std::string path = base::localPathOfUrl(mainUrl_);
  if (!path.empty() && path == mainUrl_) {
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(path, ec);
    if (!ec) mainUrl_ = absolute.lexically_normal().string();
  }
  findBindables();
}

void SceneTraversal::sceneChanged() {
  // The main scene's URL may have moved (an HTTP redirect) before its first node.
  if (base::localPathOfUrl(scene_->url).empty() && !scene_->url.empty()) mainUrl_ = scene_->url;
  viewpoints_.clear();
  navigation_ = NavigationSettings{};
  background_ = BackgroundSettings{};
  fog_ = FogSettings{};
  findBindables();
  haveWorldBounds_ = false;
  filledGroups_.clear();
}

void SceneTraversal::findBindables() {
  bool haveNavigation = false, haveBackground = false, haveFog = false;
  // glTF has no background: a glTF asset opened as a world shows castle-model-viewer's
  // dark grey (0.1), where X3D and VRML97 worlds without a Background keep clause 6.5's
  // black. A Background of the world (an X3D world inlining glTF) wins.
  if (scene_->x3d.encoding == "glTF") background_.skyColor = {glm::vec3(0.1f)};
  const auto readNavigation = [&](const vrml::Node& n) {
    navigation_.node = &n;
    if (const auto* f = n.field("type"); f && f->type() == vrml::FieldType::MFString)
      navigation_.type = f->get<vrml::FieldType::MFString>();
    navigation_.headlight = sfBool(n, "headlight", true);
    navigation_.speed = sfFloat(n, "speed", 1.0f);
    if (const auto* f = n.field("avatarSize"); f && f->type() == vrml::FieldType::MFFloat)
      navigation_.avatarSize = f->get<vrml::FieldType::MFFloat>();
    navigation_.visibilityLimit = sfFloat(n, "visibilityLimit", 0.0f);
  };
  auto visit = [&](const vrml::Node& n, NodeKind kind, const glm::mat4& m,
                   const ViewpointGroups& groups) {
    switch (kind) {
      case NodeKind::Viewpoint: {
        ViewpointInfo info;
        info.node = &n;
        info.description = sfString(n, "description");
        if (info.description.empty())
          info.description = "Viewpoint " + std::to_string(viewpoints_.size() + 1);
        info.camera = gs::scene::viewpointCamera(n, m);
        for (const auto& [group, groupMatrix] : groups) {
          if (const std::string& d = sfString(*group, "description"); !d.empty())
            info.groups.push_back(d);
          info.displayed = info.displayed && sfBool(*group, "displayed", true);
          const glm::vec3 size = sfVec3(*group, "size", glm::vec3(0.0f));
          if (size != glm::vec3(0.0f))
            info.groupBoxes.push_back(
                {glm::inverse(groupMatrix), sfVec3(*group, "center", glm::vec3(0.0f)), size});
        }
        viewpoints_.push_back(std::move(info));
        break;
      }
      case NodeKind::NavigationInfo:
        if (runtimeBound_ ? &n != runtimeBound_->navigationInfo : haveNavigation) break;
        haveNavigation = true;
        readNavigation(n);
        break;
      case NodeKind::Background:
        if (runtimeBound_ ? &n != runtimeBound_->background : haveBackground) break;
        haveBackground = true;
        background_.node = &n;
        background_.skyColor = colorsOr(mfColor(n, "skyColor"), glm::vec3(0.0f));
        background_.skyAngle = mfFloat(n, "skyAngle");
        background_.groundColor = mfColor(n, "groundColor");
        background_.groundAngle = mfFloat(n, "groundAngle");
        // One ground colour and no angle: VRML97's ground ends at the nadir (6.5, as
        // castle-model-viewer draws it: none); X3D's, as X_ITE draws it, fills the lower
        // hemisphere with that colour.
        if (!scene_->x3d.version.empty() && background_.groundColor.size() == 1 &&
            background_.groundAngle.empty()) {
          background_.groundColor.push_back(background_.groundColor[0]);
          background_.groundAngle.push_back(1.5707964f);
        }
        background_.rotation = rotationPart(m);
        background_.baseUrl = mainUrl_;
        break;
      case NodeKind::Fog: {
        if (runtimeBound_ ? &n != runtimeBound_->fog : haveFog) break;
        haveFog = true;
        fog_.node = &n;
        fog_.color = sfColor(n, "color", glm::vec3(1.0f));
        fog_.exponential = sfString(n, "fogType") == "EXPONENTIAL";
        fog_.visibilityRange = std::max(sfFloat(n, "visibilityRange", 0.0f), 0.0f) * meanScale(m);
        readVolumetricFog(n, meanScale(m), fog_);
        break;
      }
      default:
        break;
    }
  };
  ViewpointGroups groups;
  forEachBindable(scene_->rootNodes, glm::mat4(1.0f), 0, visit, groups);
  // A NavigationInfo bound outside the graph: a viewpoint's own (X3D 4.0 clause 23.3.1,
  // its `navigationInfo` field), which the runtime binds with it.
  if (runtimeBound_ && runtimeBound_->navigationInfo != nullptr && !haveNavigation)
    readNavigation(*runtimeBound_->navigationInfo);
  boundViewpoint_ = 0;
  if (runtimeBound_) {
    boundViewpoint_ = viewpoints_.size();  // none bound: the default Viewpoint
    for (std::size_t i = 0; i < viewpoints_.size(); ++i)
      if (viewpoints_[i].node == runtimeBound_->viewpoint) boundViewpoint_ = i;
  }
  if (boundViewpoint_ < viewpoints_.size())
    navigation_.speedFactor = viewpointSpeedFactor(*viewpoints_[boundViewpoint_].node);
}

float viewpointSpeedFactor(const vrml::Node& viewpoint) {
  if (viewpoint.typeId() != vrml::NodeTypeId::GeoViewpoint) return 1.0f;
  const geospatial::GeoSystem system = vrml::geoSystemOf(viewpoint);
  const glm::dvec3 position =
      viewpoint.get<vrml::FieldType::SFVec3d>("position", glm::dvec3(0.0, 0.0, 100000.0));
  geospatial::GeoSystem geodetic;  // GD on the same ellipsoid: (latitude, longitude, height)
  geodetic.a = system.a;
  geodetic.f = system.f;
  const double elevation =
      geospatial::fromGeocentric(geodetic, geospatial::toGeocentric(system, position)).z;
  const double factor = (std::max(elevation, 0.0) + 10.0) / 10.0 *
                        viewpoint.get<vrml::FieldType::SFFloat>("speedFactor", 1.0f);
  return std::isfinite(factor) && factor > 0.0 ? static_cast<float>(factor) : 1.0f;
}

void SceneTraversal::setBoundNodes(const BoundNodes& bound) {
  std::uint64_t revision = 0;
  for (const vrml::Node* n : {bound.viewpoint, bound.navigationInfo, bound.background, bound.fog})
    if (n) revision += vrml::revisionWithFields(*n);
  if (runtimeBound_ && *runtimeBound_ == bound && revision == boundRevision_) return;
  runtimeBound_ = bound;
  boundRevision_ = revision;
  viewpoints_.clear();
  navigation_ = NavigationSettings{};
  background_ = BackgroundSettings{};
  fog_ = FogSettings{};
  findBindables();
}

void readVolumetricFog(const vrml::Node& node, float scale, FogSettings& fog) {
  fog.volumetric = false;
  if (!sfBool(node, "volumetric", false)) return;
  const glm::vec3 d = sfVec3(node, "volumetricDirection", glm::vec3(0.0f, -1.0f, 0.0f));
  const float length = glm::length(d);
  const float start = sfFloat(node, "volumetricVisibilityStart", 0.0f) * scale;
  if (!(length > 0.0f) || !std::isfinite(length) || !std::isfinite(start)) return;
  fog.volumetric = true;
  fog.volumetricDirection = d / length;
  fog.volumetricStart = start;
}

bool ViewpointInfo::listedAt(const glm::vec3& viewer) const {
  if (!displayed) return false;
  for (const GroupBox& box : groupBoxes) {
    const glm::vec3 local = glm::vec3(box.worldToGroup * glm::vec4(viewer, 1.0f));
    const glm::vec3 d = glm::abs(local - box.center);
    if (d.x > box.size.x * 0.5f || d.y > box.size.y * 0.5f || d.z > box.size.z * 0.5f) return false;
  }
  return true;
}

}  // namespace gs::scene
