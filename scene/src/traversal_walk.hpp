// Private to scene/: the state and the node handlers of one SceneTraversal::collect()
// walk (traversal.cpp; X3D Layering and LayoutLayer in traversal_layers.cpp).
#pragma once

#include "scene/traversal.hpp"

#include "particles/particle_system.hpp"
#include "vrml/geo_nodes.hpp"

#include "scene/layout.hpp"

#include "scene/node_access.hpp"
#include "scene/node_kind.hpp"
#include "scene/text_mesh.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

namespace gs::scene {

/// Metres per length unit of `scene`'s X3D UNIT statement (1 without one; usable factors
/// only: the parser scaled its root nodes by it).
inline float lengthUnitOf(const vrml::Scene& scene) {
  for (const vrml::X3dUnit& u : scene.x3d.units)
    if (u.category == "length" && std::isfinite(u.conversionFactor) && u.conversionFactor > 0.0)
      return static_cast<float>(u.conversionFactor);
  return 1.0f;
}

/// State of one collect() walk.
struct SceneTraversal::Walk {
  SceneTraversal& self;
  TraversalFrame& frame;
  glm::vec3 viewerPosition;
  glm::vec3 viewerUp;
  std::vector<std::uint32_t>& scope;             // active DirectionalLights
  std::vector<const std::string*>& inlineChain;  // URLs being traversed (recursion guard)
  bool scopeChanged = true;
  std::uint32_t lastScopeBegin = 0;
  /// The innermost scoped EnvironmentLight (index in frame.environmentLights), -1: none.
  std::int32_t environmentScope = -1;
  /// The innermost enabled LocalFog (index in frame.localFogs), -1: none.
  std::int32_t fogScope = -1;
  /// The X3D length unit (metres per unit) of the file being walked (lengthUnitOf).
  float lengthUnit = 1.0f;
  /// The ClipPlanes in scope, world coordinates (SceneTraversal::clipScratch_).
  std::vector<glm::vec4>* clipScope = nullptr;
  bool clipScopeChanged = true;
  std::uint32_t lastClipBegin = 0;
  /// The TextureProjectors with global FALSE in scope (indices into frame.projectors).
  std::vector<std::uint32_t> projectorScope{};
  bool projectorScopeChanged = true;
  std::uint32_t lastProjectorBegin = 0;
  /// groupIds with children in the file being walked (SceneTraversal::filledGroups).
  const std::unordered_set<std::int32_t>* filled = nullptr;
  /// The grouping nodes above the current one when frame.recordPaths (picking).
  std::vector<PathStep> path{};
  /// The X3D layer being walked (ShapeInstance::layer): 0 for the root nodes.
  std::uint32_t layer = 0;
  /// The view of the layer being walked (X3D Layout, clause 36): eye coordinates of its
  /// camera to world coordinates and back, whether it is orthographic, tan of half its
  /// field of view (perspective), its pixels, and the enclosing Layout rectangles.
  glm::mat4 eyeToWorld{1.0f}, worldToEye{1.0f};
  bool orthographic = false;
  float tanHalfFov = 0.41421f;
  glm::vec2 viewPixels{640.0f, 480.0f};
  std::vector<LayoutRectangle> layouts{};
  Camera camera{};  // the world's
  /// Nodes entered and not yet left (node()): past kMaxWalkDepth the walk goes no deeper.
  int depth = 0;
  bool depthReported = false;

  /// The rectangle a top-level Layout of this layer lays out in: the orthographic region,
  /// or the viewport at the near distance as X_ITE takes it.
  LayoutRectangle viewRegion() const {
    if (orthographic) {
      const glm::vec4 r = camera.orthoRegion;
      return viewRectangle(viewPixels, std::min(r.z - r.x, r.w - r.y));
    }
    return viewRectangle(viewPixels, 2.0f * camera.nearClip * tanHalfFov);
  }

  /// X3D Layout's ScreenGroup (clause 36.4.4): its children in pixels, one unit a pixel of
  /// the view at the group's depth, kept where the group's origin is and turned as it is.
  void screenGroup(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    glm::mat4 placed;
    if (pixelUnits(m, placed)) group(&n, n.mfnode("children"), placed, baseUrl, nullptr);
  }
  /// `m` (local to world) made to measure in pixels of the view at its origin's depth, its
  /// origin and turn kept (X_ITE's getScreenScaleMatrix); false behind the viewer.
  bool pixelUnits(const glm::mat4& m, glm::mat4& out) const {
    const glm::mat4 mv = worldToEye * m;
    const glm::vec3 t(mv[3]);
    float perPixel = 0.0f;
    if (orthographic) {
      perPixel = layoutPerPixel;
    } else {
      if (t.z >= 0.0f) return false;  // behind the viewer: no pixels to measure
      perPixel = 2.0f * (-t.z) * tanHalfFov / std::min(viewPixels.x, viewPixels.y);
    }
    glm::mat4 placed(1.0f);
    for (int i = 0; i < 3; ++i) {
      const float len = glm::length(glm::vec3(mv[i]));
      placed[i] = len > 0.0f ? mv[i] / len * perPixel : glm::vec4(0.0f);
    }
    placed[3] = mv[3];
    out = eyeToWorld * placed;
    return true;
  }
  /// Whether `shape` draws Text in a ScreenFontStyle: X3D 4.0 clause 36.4.5, sized in
  /// points of the screen wherever it is (X_ITE's ScreenText measures it in pixels at the
  /// text's depth, in a ScreenGroup or not).
  static bool screenText(const vrml::Node& shape) {
    const vrml::NodePtr& g = shape.sfnode("geometry");
    if (!g || g->unresolved || g->typeId() != vrml::NodeTypeId::Text) return false;
    const vrml::NodePtr& fs = g->sfnode("fontStyle");
    return fs && !fs->unresolved && fs->typeId() == vrml::NodeTypeId::ScreenFontStyle;
  }
  float layoutPerPixel = 0.0f;  // an orthographic layer's metres per pixel

  /// X3D Layout's LayoutGroup (clause 36.4.3) with `layout` (null: a plain group): its
  /// children placed in the enclosing rectangle, as X_ITE does it: the group's origin and
  /// turn kept, moved by the placement and scaled by it (placeLayout).
  void layoutGroup(const vrml::Node* n, const vrml::Node* layout,
                   const std::vector<vrml::NodePtr>& children, const glm::mat4& m,
                   const std::string* baseUrl) {
    if (layout == nullptr || layouts.empty()) return group(n, children, m, baseUrl, nullptr);
    const LayoutPlacement p = placeLayout(*layout, layouts.back());
    const glm::mat4 mv = worldToEye * m;
    glm::mat4 placed(1.0f);
    glm::vec3 shift(0.0f);
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const float len = glm::length(glm::vec3(mv[i]));
      const glm::vec3 axis = len > 0.0f ? glm::vec3(mv[i]) / len : glm::vec3(0.0f);
      const float scale = i == 2 ? 1.0f : p.keepScale[k] ? len : p.scale[i];
      placed[i] = glm::vec4(axis * scale, 0.0f);
      if (i < 2) shift += axis * p.translation[i];
    }
    placed[3] = glm::vec4(glm::vec3(mv[3]) + shift, 1.0f);
    layouts.push_back(p.rectangle);
    group(n, children, eyeToWorld * placed, baseUrl, nullptr);
    layouts.pop_back();
  }

  /// The children of a grouping node, in the coordinate system `m`.
  void group(const vrml::Node* n, const std::vector<vrml::NodePtr>& children, const glm::mat4& m,
             const std::string* baseUrl, const std::vector<vrml::NodePtr>* sensorSiblings) {
    if (frame.recordPaths) path.push_back({n, m, sensorSiblings});
    nodes(children, m, baseUrl);
    if (frame.recordPaths) path.pop_back();
  }

  void nodes(const std::vector<vrml::NodePtr>& list, const glm::mat4& m,
             const std::string* baseUrl) {
    // DirectionalLights light their siblings and the siblings' descendants (clause 6.16).
    // So do EnvironmentLights whose global is FALSE (X3D 4.0 clause 17.2.1.1).
    // ClipPlanes clip them (X3D 4.0 clause 11.4.1).
    const std::size_t scopeSize = scope.size();
    const std::size_t clipSize = clipScope->size();
    const std::size_t projectorSize = projectorScope.size();
    const std::int32_t outerEnvironment = environmentScope;
    const std::int32_t outerFog = fogScope;
    for (const vrml::NodePtr& n : list) {
      if (!n) continue;
      const NodeKind kind = nodeKind(*n);
      // X3D's `global` (clause 17.2.1.1; VRML97's rule without the field): a light that is
      // not global lights only its siblings and their descendants.
      if (kind == NodeKind::DirectionalLight && !sfBool(*n, "global", false))
        directionalLight(*n, m, true);
      if ((kind == NodeKind::PointLight || kind == NodeKind::SpotLight) &&
          !sfBool(*n, "global", true))
        pointOrSpotLight(*n, m, kind == NodeKind::SpotLight, true);
      if (kind == NodeKind::EnvironmentLight) environmentLight(*n, m, baseUrl);
      if (kind == NodeKind::ClipPlane) clipPlane(*n, m);
      if (kind == NodeKind::TextureProjector) textureProjector(*n, m, baseUrl);
      if (kind == NodeKind::LocalFog) localFog(*n, m);
    }
    for (const vrml::NodePtr& n : list)
      if (n) node(*n, m, baseUrl);
    if (scope.size() != scopeSize) {
      scope.resize(scopeSize);
      scopeChanged = true;
    }
    environmentScope = outerEnvironment;
    fogScope = outerFog;
    if (clipScope->size() != clipSize) {
      clipScope->resize(clipSize);
      clipScopeChanged = true;
    }
    if (projectorScope.size() != projectorSize) {
      projectorScope.resize(projectorSize);
      projectorScopeChanged = true;
    }
  }

  // X3D 4.0 clause 42.2: a projector reaches the shapes a light with its `global` would.
  void textureProjector(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    TextureProjectorInstance p;
    if (!textureProjectorInstance(n, m, p)) return;
    p.baseUrl = baseUrl;
    p.layer = layer;
    const auto index = static_cast<std::uint32_t>(frame.projectors.size());
    frame.projectors.push_back(p);
    if (sfBool(n, "global", true)) {
      frame.globalProjectors.push_back(index);
    } else {
      projectorScope.push_back(index);
      projectorScopeChanged = true;
    }
  }

  // X3D 4.0 clause 11.4.1: the plane (a, b, c, d) in the ClipPlane's coordinate system; a
  // plane transforms by the inverse transpose of the point transform.
  void clipPlane(const vrml::Node& n, const glm::mat4& m) {
    if (!sfBool(n, "enabled", true)) return;
    const glm::vec4 local = n.get<vrml::FieldType::SFVec4f>("plane", glm::vec4(0, 1, 0, 0));
    if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z) ||
        !std::isfinite(local.w) || glm::length(glm::vec3(local)) < 1e-12f)
      return;
    clipScope->push_back(glm::transpose(glm::inverse(m)) * local);
    clipScopeChanged = true;
  }

  // X3D 4.0 clause 24.4.4: Fog's fields, for the siblings and their descendants; the
  // visibility range in the LocalFog's coordinate system.
  /// Where the ClipPlanes now in scope start in frame.scopedClipPlanes (appended there
  /// when the scope changed since the last call).
  std::uint32_t clipScopeBegin() {
    if (clipScopeChanged) {
      lastClipBegin = static_cast<std::uint32_t>(frame.scopedClipPlanes.size());
      frame.scopedClipPlanes.insert(frame.scopedClipPlanes.end(), clipScope->begin(),
                                    clipScope->end());
      clipScopeChanged = false;
    }
    return lastClipBegin;
  }

  void localFog(const vrml::Node& n, const glm::mat4& m) {
    if (!sfBool(n, "enabled", true)) return;
    FogSettings f;
    f.node = &n;
    f.color = glm::clamp(sfColor(n, "color", glm::vec3(1.0f)), 0.0f, 1.0f);
    f.exponential = sfString(n, "fogType") == "EXPONENTIAL";
    f.visibilityRange = std::max(sfFloat(n, "visibilityRange", 0.0f), 0.0f) * meanScale(m);
    readVolumetricFog(n, meanScale(m), f);
    fogScope = static_cast<std::int32_t>(frame.localFogs.size());
    frame.localFogs.push_back(f);
  }

  // X3D 4.1 clause 17.4.2: the cube maps turn with the light's coordinate system and its
  // `rotation`; scoped like a DirectionalLight unless global.
  void environmentLight(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    if (!sfBool(n, "on", true)) return;
    EnvironmentLightInstance light;
    light.node = &n;
    const vrml::Rotation r = sfRotation(n, "rotation", vrml::Rotation(0, 0, 1, 0));
    const glm::vec3 axis(r.x, r.y, r.z);
    const glm::mat3 own = glm::length(axis) > 1e-12f
                              ? glm::mat3(glm::rotate(glm::mat4(1.0f), r.w, axis))
                              : glm::mat3(1.0f);
    light.rotation = rotationPart(m) * own;
    light.color = glm::max(sfColor(n, "color", glm::vec3(1.0f)), 0.0f) *
                  std::max(sfFloat(n, "intensity", 1.0f), 0.0f);
    light.ambientIntensity = std::clamp(sfFloat(n, "ambientIntensity", 0.0f), 0.0f, 1.0f);
    light.baseUrl = baseUrl;
    const auto index = static_cast<std::int32_t>(frame.environmentLights.size());
    frame.environmentLights.push_back(light);
    if (sfBool(n, "global", false)) {
      if (self.firstGlobalEnvironment_ < 0) self.firstGlobalEnvironment_ = index;
    } else {
      environmentScope = index;
    }
  }

  // VRML97 bounds intensity to [0, 1] (clause 6.16); X3D 4 lights (those with X3D's
  // `global` field) take any intensity >= 0 (X3D 4.0 clause 17.4.1), as glTF's do.
  static constexpr float kUnboundedRadius = 1.0e30f;  // metres: a light without a bound
  static float lightIntensity(const vrml::Node& n) {
    const float i = std::max(sfFloat(n, "intensity", 1.0f), 0.0f);
    return n.type().findExact("global") >= 0 ? i : std::min(i, 1.0f);
  }

  /// Adds the light to `scope` (its siblings and their descendants) when `scoped`, else to
  /// the frame's global lights.
  void addLight(const LightInstance& light, bool scoped) {
    (scoped ? scope : frame.globalLights)
        .push_back(static_cast<std::uint32_t>(frame.lights.size()));
    frame.lights.push_back(light);
    frame.lights.back().layer = layer;
    if (scoped) scopeChanged = true;
  }

  void directionalLight(const vrml::Node& n, const glm::mat4& m, bool scoped) {
    if (!sfBool(n, "on", true)) return;
    LightInstance light;
    light.type = LightType::directional;
    light.color = sfColor(n, "color", glm::vec3(1.0f));
    light.intensity = lightIntensity(n);
    light.ambientIntensity = std::clamp(sfFloat(n, "ambientIntensity", 0.0f), 0.0f, 1.0f);
    const glm::vec3 d = glm::mat3(m) * sfVec3(n, "direction", glm::vec3(0, 0, -1));
    if (glm::length(d) < 1e-12f) return;
    light.direction = glm::normalize(d);
    addLight(light, scoped);
  }

  void pointOrSpotLight(const vrml::Node& n, const glm::mat4& m, bool spot, bool scoped) {
    if (!sfBool(n, "on", true)) return;
    LightInstance light;
    light.type = spot ? LightType::spot : LightType::point;
    light.color = sfColor(n, "color", glm::vec3(1.0f));
    light.intensity = lightIntensity(n);
    light.ambientIntensity = std::clamp(sfFloat(n, "ambientIntensity", 0.0f), 0.0f, 1.0f);
    light.location = glm::vec3(m * glm::vec4(sfVec3(n, "location", glm::vec3(0.0f)), 1.0f));
    light.attenuation = glm::max(sfVec3(n, "attenuation", glm::vec3(1, 0, 0)), glm::vec3(0.0f));
    // A negative radius reaches everywhere: glTF's lights, whose range is absent, come to
    // X3D as radius -1 (castle-model-viewer writes them so; X_ITE lights them unbounded).
    const float radius = sfFloat(n, "radius", 100.0f);
    light.radius = radius < 0.0f ? kUnboundedRadius : radius * meanScale(m);
    if (spot) {
      const glm::vec3 d = glm::mat3(m) * sfVec3(n, "direction", glm::vec3(0, 0, -1));
      light.direction = glm::length(d) > 1e-12f ? glm::normalize(d) : glm::vec3(0, 0, -1);
      light.beamWidth = sfFloat(n, "beamWidth", 1.570796f);
      light.cutOffAngle = sfFloat(n, "cutOffAngle", 0.785398f);
    }
    addLight(light, scoped);
  }

  void shape(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    const vrml::NodePtr geometry = n.sfnode("geometry");
    if (!geometry || geometry->unresolved) return;
    addShape(n, *geometry, m, baseUrl);
  }

  /// A GeoLOD (X3D 4.0 clause 25.4.4): within `range` metres of its center the worlds of
  /// child1Url ... child4Url once all four have loaded (each shown as an Inline), else its
  /// rootNode, or the world of rootUrl.
  void geoLod(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    const glm::vec3 center =
        glm::vec3(vrml::geoToLocal(n, n.get<vrml::FieldType::SFVec3d>("center", glm::dvec3(0.0))));
    const glm::vec3 viewer = glm::vec3(glm::inverse(m) * glm::vec4(viewerPosition, 1.0f));
    const bool near = glm::length(viewer - center) < sfFloat(n, "range", 10.0f);
    if (near) {
      // The children replace the root once every child url has loaded (none: the root
      // stays, as in X_ITE, whose Inlines without a url never finish loading).
      bool loaded = false, missing = false;
      for (int k = 1; k <= 4; ++k) {
        const vrml::Node& child = self.geoLodInline(n, k);
        if (mfString(child, "url").empty()) continue;
        const InlineScene* inl = self.inlineScene(child, n.urlBaseOr(*baseUrl));
        loaded = true;
        missing = missing || inl == nullptr || inl->scene == nullptr;
      }
      loaded = loaded && !missing;
      if (loaded) {
        if (frame.reportOutputs) {
          std::array<const std::vector<vrml::NodePtr>*, 4> shown{};
          std::size_t lists = 0;
          for (int k = 1; k <= 4; ++k)
            if (const InlineScene* inl =
                    self.inlineScene(self.geoLodInline(n, k), n.urlBaseOr(*baseUrl));
                inl != nullptr && inl->scene)
              shown[lists++] = &inl->scene->rootNodes;
          self.noteShownLevel(n, 1, std::span(shown).first(lists));
        }
        for (int k = 1; k <= 4; ++k) node(self.geoLodInline(n, k), m, baseUrl);
        return;
      }
    }
    if (const auto& root = n.mfnode("rootNode"); !root.empty()) {
      if (frame.reportOutputs) self.noteShownLevel(n, near ? 1 : 0, &root);
      group(&n, root, m, baseUrl, nullptr);
      return;
    }
    if (frame.reportOutputs) {
      const InlineScene* inl = self.inlineScene(self.geoLodInline(n, 0), n.urlBaseOr(*baseUrl));
      const std::vector<vrml::NodePtr> none;
      self.noteShownLevel(n, near ? 1 : 0,
                          inl != nullptr && inl->scene ? &inl->scene->rootNodes : &none);
    }
    node(self.geoLodInline(n, 0), m, baseUrl);
  }

  /// A ParticleSystem (X3D 4.0 clause 40): a shape of its appearance whose geometry is its
  /// particles (one mesh), or for geometryType GEOMETRY its `geometry` node once per
  /// visible particle, translated there (as X_ITE draws them: no rotation, no scale).
  void particleSystem(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    if (!self.particleSource_ || !sfBool(n, "visible", true)) return;
    const particles::ParticleSimulation* simulation = self.particleSource_(n);
    if (simulation == nullptr) return;
    if (particles::geometryTypeOf(sfString(n, "geometryType")) ==
        particles::GeometryType::geometry) {
      const vrml::NodePtr& geometry = n.sfnode("geometry");
      if (!geometry || geometry->unresolved) return;
      for (const particles::Particle& p : simulation->particles())
        if (p.visible) addShape(n, *geometry, glm::translate(m, p.position), baseUrl);
      return;
    }
    if (const vrml::Node* g = self.particleGeometry(n, *simulation, worldToEye * m))
      addShape(n, *g, m, baseUrl);
  }

  /// An OutlineGroup (docs/vrml-extensions.md): children as a Group (not in outlines
  /// mode), and its outline as a shape whose geometry is the node itself while shown.
  void outlineGroup(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    const RenderMode mode = self.options_.mode;
    if (mode != RenderMode::outlines) group(&n, n.mfnode("children"), m, baseUrl, nullptr);
    const auto& outline = fieldRef<vrml::FieldType::MFVec3f>(n, "outline", kNoPoints);
    if (outline.empty()) return;
    const int id = sfInt(n, "groupId", -1);
    if (mode != RenderMode::outlines && id >= 0 && filled != nullptr && filled->contains(id))
      return;  // the group's polygons have arrived: they replace the outline
    addShape(n, n, m, baseUrl);
  }
  static inline const std::vector<glm::vec3> kNoPoints{};

  void addShape(const vrml::Node& n, const vrml::Node& geometry, const glm::mat4& m,
                const std::string* baseUrl) {
    ShapeInstance s;
    s.shape = &n;
    const vrml::NodePtr appearance = n.sfnode("appearance");
    s.appearance = appearance && !appearance->unresolved ? appearance.get() : nullptr;
    s.geometry = &geometry;
    s.model = m;
    s.baseUrl = baseUrl;
    s.layer = layer;
    if (scopeChanged) {
      lastScopeBegin = static_cast<std::uint32_t>(frame.scopedLights.size());
      frame.scopedLights.insert(frame.scopedLights.end(), scope.begin(), scope.end());
      scopeChanged = false;
    }
    s.scopedLightBegin = lastScopeBegin;
    s.scopedLightCount = static_cast<std::uint32_t>(scope.size());
    s.environmentLight = environmentScope;
    s.localFog = fogScope;
    s.clipPlaneBegin = clipScopeBegin();
    s.clipPlaneCount = static_cast<std::uint32_t>(clipScope->size());
    if (projectorScopeChanged) {
      lastProjectorBegin = static_cast<std::uint32_t>(frame.scopedProjectors.size());
      frame.scopedProjectors.insert(frame.scopedProjectors.end(), projectorScope.begin(),
                                    projectorScope.end());
      projectorScopeChanged = false;
    }
    s.projectorBegin = lastProjectorBegin;
    s.projectorCount = static_cast<std::uint32_t>(projectorScope.size());
    if (frame.recordPaths) {
      s.pathBegin = static_cast<std::uint32_t>(frame.paths.size());
      frame.paths.insert(frame.paths.end(), path.begin(), path.end());
      frame.paths.push_back({&n, m, nullptr});
      s.pathCount = static_cast<std::uint32_t>(frame.paths.size()) - s.pathBegin;
    }
    frame.shapes.push_back(s);
  }

  /// A Collision (6.8) when collecting collision geometry: nothing with collide FALSE,
  /// else its proxy when it has one, else its children.
  void collision(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    if (!sfBool(n, "collide", true)) return;
    const vrml::NodePtr proxy = n.sfnode("proxy");
    if (!proxy || proxy->unresolved) return group(&n, n.mfnode("children"), m, baseUrl, nullptr);
    if (frame.recordPaths) path.push_back({&n, m, nullptr});
    node(*proxy, m, baseUrl);
    if (frame.recordPaths) path.pop_back();
  }

  /// X3D Layering (clause 35): the first LayerSet among the world's root nodes makes them
  /// layer 0 and the children of its i-th Layer layer i, each in world coordinates; its
  /// `order` (indices into 0 and the layers) fills frame.layerOrder. A LayerSet elsewhere
  /// (inside a group, in an Inline) draws nothing: the spec allows it at the root only.
  void layers();
  static inline const std::vector<std::int32_t> kNoOrder{};

  /// A Layer that is not the active one and holds a Viewpoint (clause 35.2: each layer is
  /// seen through its own bound Viewpoint, as X_ITE draws a HUD layer): its children placed
  /// so that the world's camera sees them as that viewpoint would. A perspective viewpoint:
  /// the layer's eye coordinates are the world camera's, x and y scaled by the ratio of the
  /// two fields of view. An OrthoViewpoint: its region put square in front of the world
  /// camera at twice the near distance, depths compressed, as layoutLayer does. A
  /// LayoutLayer holding a viewpoint is seen so too, its `layout` laying out in that view
  /// (the region, or the viewport at the near distance). Inside, pixels are the layer's
  /// (its own field of view). Restores the walk's view afterwards.
  void layerWithOwnView(const vrml::Node& l, const std::vector<vrml::NodePtr>& children,
                        const Camera& own);

  /// X3D Layout's LayoutLayer (clause 36.4.2): its children seen by a view of its own,
  /// X_ITE's default OrthoViewpoint (at 0 0 10, the region -1 -1 1 1 on the smaller
  /// side), laid out by its `layout` in that region. Drawn with the world's camera, the
  /// layer's view plane is put square in front of it at twice the near distance, so that
  /// the perspective shows what the orthographic view would (depths within the layer are
  /// kept, compressed, for their order). Restores the walk's view afterwards.
  void layoutLayer(const vrml::Node& l, const std::vector<vrml::NodePtr>& children);

  void node(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    // A node graph deeper than any file makes (a file nests at most 256 nodes,
    // encodings::ParseLimits), or a cycle a Script made (a Group put among its own
    // descendants' children): the walk stops there, said once, instead of exhausting the
    // stack.
    if (depth >= kMaxWalkDepth) {
      if (!depthReported)
        self.report(vrml::Severity::error, n.location,
                    "the scene graph is deeper than " + std::to_string(kMaxWalkDepth) +
                        " nodes here (a node among its own descendants?): not drawn below");
      depthReported = true;
      return;
    }
    ++depth;
    nodeChecked(n, m, baseUrl);
    --depth;
  }

  void nodeChecked(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    // X3D 4.0's X3DBoundedObject.visible (clause 10.3.1): FALSE draws neither the node nor
    // its children, and the pointer does not reach them; collisions still see them.
    if (!frame.collisionGeometry && n.type().builtIn && !sfBool(n, "visible", true)) return;
    // X3DBoundedObject.bboxDisplay: the node's box outlined after its children, in their
    // coordinates (traversal_bbox.cpp); drawn only, never picked or collided with.
    if (frame.collisionGeometry || frame.recordPaths || !n.type().builtIn ||
        !sfBool(n, "bboxDisplay", false))
      return nodeBody(n, m, baseUrl);
    const std::size_t first = frame.shapes.size();
    nodeBody(n, m, baseUrl);
    const glm::mat4 inner = vrml::placesChildren(n.typeId()) ? m * transformMatrix(n) : m;
    const vrml::Bounds box =
        self.boundedBox(n, std::span<const ShapeInstance>(frame.shapes).subspan(first), inner);
    if (box.empty()) return;
    if (const BoxOutline o = self.boxOutline(n, box); o.shape != nullptr)
      addShape(*o.shape, *o.geometry, inner, baseUrl);
  }

  void nodeBody(const vrml::Node& n, const glm::mat4& m, const std::string* baseUrl) {
    switch (nodeKind(n)) {
      case NodeKind::Collision:  // the proxy is for collisions only: not drawn
        if (frame.collisionGeometry) {
          collision(n, m, baseUrl);
          break;
        }
        [[fallthrough]];
      case NodeKind::Anchor:
      case NodeKind::Group:
        group(&n, n.mfnode("children"), m, baseUrl, nullptr);
        break;
      case NodeKind::Transform:
        group(&n, n.mfnode("children"), m * transformMatrix(n), baseUrl, nullptr);
        break;
      case NodeKind::ScreenGroup:
        screenGroup(n, m, baseUrl);
        break;
      case NodeKind::LayoutGroup: {
        const vrml::NodePtr& layout = n.sfnode("layout");
        layoutGroup(&n, layout && !layout->unresolved ? layout.get() : nullptr,
                    n.mfnode("children"), m, baseUrl);
        break;
      }
      case NodeKind::HAnimHumanoid: {
        // Clause 26.3.1: the humanoid's Transform fields place its skeleton (the root
        // joints) and its skin; the skin is drawn as given (bind pose: not deformed by the
        // joints' skinCoordWeight).
        const glm::mat4 hm = m * transformMatrix(n);
        group(&n, n.mfnode("skeleton"), hm, baseUrl, nullptr);
        group(&n, n.mfnode("skin"), hm, baseUrl, nullptr);
        break;
      }
      case NodeKind::CADFace:
        if (const vrml::NodePtr& s = n.sfnode("shape"); s && !s->unresolved) {
          if (frame.recordPaths) path.push_back({&n, m, nullptr});
          node(*s, m, baseUrl);
          if (frame.recordPaths) path.pop_back();
        }
        break;
      case NodeKind::Billboard: {
        const glm::mat4 inverse = glm::inverse(m);
        const glm::vec3 viewer = glm::vec3(inverse * glm::vec4(viewerPosition, 1.0f));
        const glm::vec3 up = glm::mat3(inverse) * viewerUp;
        const glm::vec3 axis = sfVec3(n, "axisOfRotation", glm::vec3(0, 1, 0));
        group(&n, n.mfnode("children"), m * billboardRotation(axis, viewer, up), baseUrl, nullptr);
        break;
      }
      case NodeKind::Switch: {
        const auto& choice = n.mfnode("choice");
        const int which = sfInt(n, "whichChoice", -1);
        if (which >= 0 && static_cast<std::size_t>(which) < choice.size() &&
            choice[static_cast<std::size_t>(which)])
          node(*choice[static_cast<std::size_t>(which)], m, baseUrl);
        break;
      }
      case NodeKind::LOD: {
        const auto& level = n.mfnode("level");
        const glm::vec3 center = sfVec3(n, "center", glm::vec3(0.0f));
        const glm::vec3 viewer = glm::vec3(glm::inverse(m) * glm::vec4(viewerPosition, 1.0f));
        const int chosen =
            selectLodLevel(mfFloat(n, "range"), glm::length(viewer - center), level.size());
        if (frame.reportOutputs) self.noteShownLevel(n, chosen, nullptr);
        if (chosen >= 0 && level[static_cast<std::size_t>(chosen)])
          node(*level[static_cast<std::size_t>(chosen)], m, baseUrl);
        break;
      }
      case NodeKind::Inline: {
        // An Inline written in an EXTERNPROTO's file resolves against that file.
        const InlineScene* inl = self.inlineScene(n, n.urlBaseOr(*baseUrl));
        if (inl == nullptr || !inl->scene) break;
        if (static_cast<int>(inlineChain.size()) >= self.options_.maxInlineDepth) {
          self.report(vrml::Severity::error, n.location,
                      "Inline nesting deeper than " + std::to_string(self.options_.maxInlineDepth) +
                          " files (TraversalOptions::maxInlineDepth) at " + inl->url +
                          ": not drawn");
          break;
        }
        for (const std::string* url : inlineChain) {
          if (*url == inl->url) {
            self.report(vrml::Severity::error, n.location,
                        "Inline " + inl->url + " includes itself: the recursion is not drawn");
            return;
          }
        }
        inlineChain.push_back(&inl->url);
        const auto* outerFilled = filled;
        filled = &self.filledGroups(*inl->scene);
        // URLs inside resolve against where the file really came from (after redirects).
        // The parser put this file's root nodes in a Transform scaled by its length unit
        // (X3D clause 4.3.6): an inlined file keeps its own unit, so the outer file's scale
        // is undone here (castle's units.x3dv).
        const float outerUnit = lengthUnit;
        lengthUnit = lengthUnitOf(*inl->scene);
        group(&n, inl->scene->rootNodes,
              outerUnit != 1.0f ? m * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / outerUnit)) : m,
              inl->scene->url.empty() ? &inl->url : &inl->scene->url, &inl->scene->rootNodes);
        lengthUnit = outerUnit;
        filled = outerFilled;
        inlineChain.pop_back();
        break;
      }
      case NodeKind::Shape:
        if (glm::mat4 placed; screenText(n)) {
          if (pixelUnits(m, placed)) shape(n, placed, baseUrl);
        } else {
          shape(n, m, baseUrl);
        }
        break;
      case NodeKind::ParticleSystem:
        particleSystem(n, m, baseUrl);
        break;
      case NodeKind::GeoLOD:
        geoLod(n, m, baseUrl);
        break;
      case NodeKind::Collidable: {
        // X3D 4.0 clauses 37.4.3, 37.4.4: a CollidableShape draws its `shape`, a
        // CollidableOffset its `collidable`, moved by their translation and rotation (where
        // its RigidBody puts them, runtime/src/rigid_body_physics.cpp). `enabled` says
        // whether it collides, not whether it shows (as X_ITE draws it).
        const vrml::NodePtr& c = n.typeId() == vrml::NodeTypeId::CollidableShape
                                     ? n.sfnode("shape")
                                     : n.sfnode("collidable");
        if (c && !c->unresolved) node(*c, m * transformMatrix(n), baseUrl);
        break;
      }
      case NodeKind::QuantizedNormalVectors: {
        scene::SplatInstance splat{&n, m, &n.urlBaseOr(*baseUrl), layer};  // its file's base
        splat.clipPlaneBegin = clipScopeBegin();
        splat.clipPlaneCount = static_cast<std::uint32_t>(clipScope->size());
        splat.localFog = fogScope;
        frame.splats.push_back(splat);
        break;
      }
      case NodeKind::OutlineGroup:
        outlineGroup(n, m, baseUrl);
        break;
      // Global lights light everything (scoped ones were handled with their siblings).
      case NodeKind::PointLight:
      case NodeKind::SpotLight:
        if (sfBool(n, "global", true))
          pointOrSpotLight(n, m, nodeKind(n) == NodeKind::SpotLight, false);
        break;
      case NodeKind::DirectionalLight:
        if (sfBool(n, "global", false)) directionalLight(n, m, false);
        break;
      default:  // others draw nothing
        // A NurbsSet (X3D 4.0 27.4.6) draws nothing itself: its surfaces, drawn where
        // Shapes hold them, take its tessellationScale.
        if (n.typeId() == vrml::NodeTypeId::NurbsSet) self.noteNurbsSet(n);
        break;
    }
  }
};

}  // namespace gs::scene
