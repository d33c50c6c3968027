// Scene-graph traversal on the CPU (no OpenGL): which shapes are drawn this frame, with
// which world matrix and which lights; the bound Viewpoint, NavigationInfo, Background
// and Fog; Inline loading; the tessellation cache; the scene's bounding box.
// References are to ISO/IEC 14772-1:1997 (VRML97). Units: metres, radians; matrices are
// glm's, column-major.
#pragma once

#include "base/fetch.hpp"
#include "geometry/geometry.hpp"
#include "scene/camera.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"
#include "vrml/transform.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace gs::particles {
class ParticleSimulation;
}

namespace gs::scene {

/// The simulation of a ParticleSystem node (runtime::ExecutionModel::particleSimulation),
/// or null when none runs it.
using ParticleSource = std::function<const particles::ParticleSimulation*(const vrml::Node&)>;

enum class LightType : std::uint8_t { directional, point, spot };

/// A light in world coordinates (clause 4.14.4 and 6.16 DirectionalLight, 6.35
/// PointLight, 6.45 SpotLight).
struct LightInstance {
  LightType type = LightType::directional;
  /// The layer it is in (TraversalFrame::layerOrder): a global light lights only its own
  /// layer's shapes (X3D 4.0 clause 35.2.1); 0: the root layer.
  std::uint32_t layer = 0;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float ambientIntensity = 0.0f;
  glm::vec3 location{0.0f};                 // point and spot lights
  glm::vec3 direction{0.0f, 0.0f, -1.0f};   // unit; directional and spot lights
  glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // constant, linear, quadratic
  float radius = 100.0f;                    // metres, world (scaled by the light's transform)
  float beamWidth = 1.570796f;              // radians
  float cutOffAngle = 0.785398f;            // radians
};

/// An EnvironmentLight (X3D 4.1 clause 17.4.2): image-based lighting of the
/// PhysicalMaterial shapes it lights (docs/rendering.md, "Image-based lighting").
struct EnvironmentLightInstance {
  const vrml::Node* node = nullptr;
  /// Environment (cube map) coordinates to world: the light's transform's rotation times
  /// its `rotation` field; orthonormal.
  glm::mat3 rotation{1.0f};
  glm::vec3 color{1.0f};  // times intensity (>= 0)
  float ambientIntensity = 0.0f;
  const std::string* baseUrl = nullptr;  // the base for its textures' urls; never null
};

/// A TextureProjector or TextureProjectorParallel (X3D 4.0 clause 42) that is on and has a
/// texture, in world coordinates: it multiplies the colour of the shapes in its scope
/// (global: every shape of its layer; else its siblings and their descendants) by its
/// texture where they lie in its frustum and face it (docs/x3d.md "Texture projection").
struct TextureProjectorInstance {
  const vrml::Node* node = nullptr;      // its `texture` is projected
  const std::string* baseUrl = nullptr;  // the base for the texture's urls; never null
  std::uint32_t layer = 0;               // as LightInstance::layer
  /// Projector coordinates to world: the projector's transform times translation to
  /// `location` times the rotation that turns -Z onto `direction` with +Y towards
  /// `upVector` (the projector looks down -Z, image top at +Y, like a Viewpoint).
  glm::mat4 projectorToWorld{1.0f};
  bool parallel = false;                     // TextureProjectorParallel
  float fieldOfView = 0.785398f;             // radians, of the image's shorter side (perspective)
  glm::vec4 area{-1.0f, -1.0f, 1.0f, 1.0f};  // parallel: min x, min y, max x, max y (metres)
  float nearDistance = -1.0f;                // metres in projector coordinates; < 0: no near limit
  float farDistance = -1.0f;                 // < 0: no far limit
  glm::vec3 color{1.0f};                     // multiplies the texels
  float intensity = 1.0f;                    // > 0: how much of the texel colour replaces white
};

/// The instance of TextureProjector or TextureProjectorParallel `node` under transform `m`,
/// or false when it projects nothing (on FALSE, intensity <= 0, no texture, a zero
/// direction). clause 42.4.1, 42.4.2; scene/src/texture_projectors.cpp.
bool textureProjectorInstance(const vrml::Node& node, const glm::mat4& m,
                              TextureProjectorInstance& out);

/// The projection of `p` for an image of `width` x `height` pixels (either 0: square):
/// projector coordinates to clip coordinates (OpenGL's, x and y in [-1, 1] inside the
/// frustum, z in [-1, 1] between the near and far planes, which are 0.125 and 100000 when
/// not given). Perspective: fieldOfView spans the image's shorter side; parallel: the
/// area widened about its centre along one axis to the image's aspect.
glm::mat4 textureProjection(const TextureProjectorInstance& p, int width, int height);

/// One grouping node on the way from the root to a Shape (recorded when
/// TraversalFrame::recordPaths is set; scene/picking.hpp).
struct PathStep {
  /// Anchor, Billboard, Collision, Group, Transform, Inline, OutlineGroup, or the Shape
  /// last; null for the root of the main scene.
  const vrml::Node* node = nullptr;
  glm::mat4 localToWorld{1.0f};  // the coordinate system of the node's children
  /// The children among which its sibling sensors are: null for the node's `children`
  /// field, the root nodes of the scene for the root or an Inline.
  const std::vector<vrml::NodePtr>* children = nullptr;
};

/// The bound Fog (clause 6.19), or an X3D LocalFog (X3D 4.0 clause 24.4.4).
struct FogSettings {
  glm::vec3 color{1.0f};
  bool exponential = false;      // fogType "EXPONENTIAL", else "LINEAR"
  float visibilityRange = 0.0f;  // world metres (scaled by the Fog's transform); 0 = no fog
  const vrml::Node* node = nullptr;
  /// castle-engine's volumetric fog (X3D worlds' Fog and LocalFog `volumetric`,
  /// `volumetricDirection`, `volumetricVisibilityStart`; docs/x3d.md "Volumetric fog"): the
  /// fog distance of a point p (world coordinates) is dot(p, normalize(direction)) -
  /// start instead of its distance to the eye. direction is unit length (world axes, not
  /// turned by the Fog's transform, as castle does); start in world metres (scaled).
  bool volumetric = false;
  glm::vec3 volumetricDirection{0.0f, -1.0f, 0.0f};
  float volumetricStart = 0.0f;
};

/// Fills `fog`'s volumetric fields from Fog or LocalFog `node` (castle-engine's fields,
/// absent in VRML97 worlds: not volumetric), `scale` being the node's transform's mean
/// scale. A zero or non-finite direction turns volumetric fog off.
void readVolumetricFog(const vrml::Node& node, float scale, FogSettings& fog);

/// One Shape to draw: its nodes, world matrix and scoped lights.
struct ShapeInstance {
  const vrml::Node* shape = nullptr;
  const vrml::Node* appearance = nullptr;  // may be null (unlit white)
  const vrml::Node* geometry = nullptr;    // never null
  glm::mat4 model{1.0f};                   // local to world
  /// Range in TraversalFrame::scopedLights of the DirectionalLights that light it.
  std::uint32_t scopedLightBegin = 0;
  std::uint32_t scopedLightCount = 0;
  /// Index in TraversalFrame::environmentLights of the EnvironmentLight that lights it:
  /// the innermost scoped one (global FALSE: its siblings and their descendants), else the
  /// first global one; -1 for none.
  std::int32_t environmentLight = -1;
  /// Range in TraversalFrame::scopedProjectors of the TextureProjectors whose global is
  /// FALSE that project onto it (the global ones of its layer do too).
  std::uint32_t projectorBegin = 0;
  std::uint32_t projectorCount = 0;
  /// Range in TraversalFrame::scopedClipPlanes of the ClipPlanes that clip it.
  std::uint32_t clipPlaneBegin = 0;
  std::uint32_t clipPlaneCount = 0;
  /// Index in TraversalFrame::localFogs of the innermost X3D LocalFog that fogs it (its
  /// siblings and their descendants, X3D 4.0 clause 24.4.4), -1: the bound Fog's.
  std::int32_t localFog = -1;
  /// URL of the file the shape comes from (the base for texture URLs); never null.
  const std::string* baseUrl = nullptr;
  /// Range in TraversalFrame::paths of its path, the root first and the Shape last
  /// (only when TraversalFrame::recordPaths is set).
  std::uint32_t pathBegin = 0;
  std::uint32_t pathCount = 0;
  /// The X3D layer it is in (clause 35.2.1): 0 for the world's root nodes, i for the
  /// children of the i-th Layer in the root LayerSet's `layers` (1-based, clause 35.4.2).
  std::uint32_t layer = 0;
};

/// One layer to draw (X3D 4.0 clause 35): a LayerSet's `order` lists them.
struct LayerInstance {
  /// 0: the root layer (the world's root nodes outside the LayerSet); i: the i-th Layer of
  /// the LayerSet's `layers` (ShapeInstance::layer).
  std::uint32_t number = 0;
  /// The Layer's Viewport clipBoundary (clause 35.4.4): left, right, bottom, top as
  /// fractions of the render surface, clamped to [0, 1]; the whole surface without one.
  glm::vec4 clipBoundary{0.0f, 1.0f, 0.0f, 1.0f};
  const vrml::Node* node = nullptr;  // the Layer, null for the root layer
  /// Whether its shapes have a headlight: -1 the world's (the bound NavigationInfo's, or the
  /// user's choice) for the root and the active layer; 0 or 1 another layer's own, from its
  /// first NavigationInfo (X3D 4.0 clause 35.2.1: each layer has its own bindable stacks).
  std::int8_t headlight = -1;
};

/// The camera of viewpoint node `viewpoint` (Viewpoint, OrthoViewpoint, GeoViewpoint:
/// position, orientation, fieldOfView or the orthographic region; clauses 6.53, 23.4.5,
/// 25.4.10) placed by `m`, its parents' transform (local to world). Clip planes are the
/// defaults.
Camera viewpointCamera(const vrml::Node& viewpoint, const glm::mat4& m);
/// NavigationSettings::speedFactor for viewpoint node `viewpoint`: for a GeoViewpoint
/// (X3D 4.0 clause 25.4.10) (max(elevation, 0) + 10) / 10 times its speedFactor, where
/// elevation is its position's height in metres above its geoSystem's ellipsoid (X_ITE
/// 15's rule); 1 for other viewpoints and for a result that is not a positive number.
float viewpointSpeedFactor(const vrml::Node& viewpoint);
/// The camera of the first viewpoint among `nodes` and below them (depth first, through
/// grouping nodes, every Switch choice and LOD level, not into Inlines); none when they hold
/// none.
std::optional<Camera> firstViewpointCamera(const std::vector<vrml::NodePtr>& nodes);
/// The `headlight` of the first NavigationInfo among `nodes` and below them (found as
/// firstViewpointCamera finds a viewpoint); TRUE, the default NavigationInfo's (X3D 4.0
/// clause 23.4.4), when they hold none.
bool firstNavigationHeadlight(const std::vector<vrml::NodePtr>& nodes);

/// The pixel rectangle (x, y, width, height; origin bottom left, as glScissor takes it) of
/// a clipBoundary (left, right, bottom, top fractions, clause 35.4.4) inside the viewport
/// rectangle (x, y, width, height) in pixels; width and height are never negative.
glm::ivec4 layerRectangle(const glm::vec4& clipBoundary, int x, int y, int width, int height);

/// One QuantizedNormalVectors node to draw as splats (docs/vrml-extensions.md).
struct SplatInstance {
  const vrml::Node* node = nullptr;
  glm::mat4 model{1.0f};                 // local to world
  const std::string* baseUrl = nullptr;  // the base for its url; never null
  std::uint32_t layer = 0;               // as ShapeInstance::layer
  /// The ClipPlanes and the LocalFog around it, as ShapeInstance's (the volume ray caster
  /// clips and fogs its samples with them).
  std::uint32_t clipPlaneBegin = 0;
  std::uint32_t clipPlaneCount = 0;
  std::int32_t localFog = -1;
};

/// What one traversal collects. Reused from frame to frame: clear() keeps capacity.
struct TraversalFrame {
  std::vector<ShapeInstance> shapes;
  std::vector<SplatInstance> splats;
  std::vector<LightInstance> lights;        // every light met, world coordinates
  std::vector<std::uint32_t> scopedLights;  // indices into lights (ShapeInstance ranges)
  /// Lights whose X3D `global` is TRUE (VRML97: every point and spot light), indices into
  /// lights; the others are in scopedLights (clause 17.2.1.1).
  std::vector<std::uint32_t> globalLights;
  std::vector<EnvironmentLightInstance> environmentLights;  // every one that is on
  /// Every TextureProjector that projects, and indices into it: the global ones (each for
  /// its layer's shapes) and the scoped ones (ShapeInstance ranges).
  std::vector<TextureProjectorInstance> projectors;
  std::vector<std::uint32_t> globalProjectors, scopedProjectors;
  /// Enabled ClipPlanes (X3D 4.0 clause 11.4.1) in world coordinates, as (a, b, c, d): a
  /// point p is kept where a p.x + b p.y + c p.z + d >= 0 (ShapeInstance ranges).
  std::vector<glm::vec4> scopedClipPlanes;
  /// Enabled LocalFogs (ShapeInstance::localFog), visibility ranges in world metres.
  std::vector<FogSettings> localFogs;
  /// Set by the caller: collect() records each Shape's path of grouping nodes (picking).
  bool recordPaths = false;
  /// Set by the caller that draws the user's view: collect() notes the levels LODs and
  /// GeoLODs show, for SceneTraversal::takeDrawnOutputs (other cameras, such as the bound
  /// Viewpoint's for bounds, leave them alone).
  bool reportOutputs = false;
  /// Set by the caller: collect() gathers what the avatar collides with (clause 6.8)
  /// instead of what is drawn: the children of a Collision with collide FALSE are
  /// skipped, and a Collision's proxy (not drawn otherwise) replaces its children.
  bool collisionGeometry = false;
  std::vector<PathStep> paths;  // ShapeInstance::pathBegin ranges
  /// The layers to draw, in order, each over the previous with the depth buffer cleared
  /// (the root LayerSet's `order`, X3D 4.0 clause 35.4.2); empty without a LayerSet at the
  /// world's root: then every shape is drawn as one layer.
  std::vector<LayerInstance> layerOrder;
  void clear() {
    layerOrder.clear();
    paths.clear();
    shapes.clear();
    splats.clear();
    lights.clear();
    scopedLights.clear();
    globalLights.clear();
    environmentLights.clear();
    projectors.clear();
    globalProjectors.clear();
    scopedProjectors.clear();
    scopedClipPlanes.clear();
    localFogs.clear();
  }
};

/// A Viewpoint of the scene (clause 6.53) in world coordinates.
struct ViewpointInfo {
  std::string description;  // the node's description, or "Viewpoint N" if empty
  Camera camera;            // position, orientation, fieldOfView; clip planes unset
  const vrml::Node* node = nullptr;
  /// The ViewpointGroups around it (X3D 4.0 clause 23.4.6), outermost first: the
  /// descriptions of those that have one (a menu's levels), whether all are `displayed`,
  /// and the boxes (`center`, `size`, in the group's coordinates) of those whose size is
  /// not 0 0 0, inside which the viewer must be for it to be listed.
  std::vector<std::string> groups;
  bool displayed = true;
  struct GroupBox {
    glm::mat4 worldToGroup{1.0f};
    glm::vec3 center{0.0f}, size{0.0f};
  };
  std::vector<GroupBox> groupBoxes;
  /// Whether a viewpoint menu lists it for a viewer at `viewer` (world coordinates):
  /// every ViewpointGroup around it is displayed and holds the viewer in its box (X_ITE
  /// 15's rule). Binding it does not depend on this.
  bool listedAt(const glm::vec3& viewer) const;
};

/// The bound NavigationInfo (clause 6.29), or its defaults when the scene has none.
struct NavigationSettings {
  std::vector<std::string> type{"WALK", "ANY"};
  bool headlight = true;
  float speed = 1.0f;  // metres per second
  /// What `speed` is multiplied by for the bound Viewpoint: for a GeoViewpoint (X3D 4.0
  /// clause 25.4.10, X_ITE 15's rule) (max(elevation, 0) + 10) / 10 times its speedFactor,
  /// the elevation being its position's height above the ellipsoid in metres, so that
  /// the Earth seen from orbit is crossed as fast as a street is walked; 1 otherwise.
  float speedFactor = 1.0f;
  std::vector<float> avatarSize{0.25f, 1.6f, 0.75f};  // metres
  float visibilityLimit = 0.0f;                       // metres, 0 = infinite
  const vrml::Node* node = nullptr;
  /// Near clip plane per clause 6.29: avatarSize[0] / 2 (0.125 when unset).
  float nearClip() const;
};

/// The bound Background (clause 6.5): sky and ground gradients; the panorama URLs are
/// read from `node` (backUrl ...) and resolved against `baseUrl`.
struct BackgroundSettings {
  /// Black without a Background (clause 6.5); dark grey (0.1) for a glTF asset opened as a
  /// world, as castle-model-viewer shows one (docs/gltf.md).
  std::vector<glm::vec3> skyColor{glm::vec3(0.0f)};
  std::vector<float> skyAngle;  // radians from the zenith, increasing
  std::vector<glm::vec3> groundColor;
  std::vector<float> groundAngle;  // radians from the nadir, increasing
  glm::mat3 rotation{1.0f};        // world rotation of the Background's coordinate system
  const vrml::Node* node = nullptr;
  std::string baseUrl;  // URL of the file holding the node
};

/// What a traversal draws of the polygon-group extension (OutlineGroup, paper section
/// 1.1; docs/vrml-extensions.md).
enum class RenderMode : std::uint8_t {
  /// Polygons as they arrive: an OutlineGroup's outline is drawn only while no
  /// OutlineGroup of the same groupId (>= 0) in the same file has children; groupId -1
  /// draws outline and children as given.
  polygons,
  /// Only outlines: the children of OutlineGroups are skipped (Shapes outside any
  /// OutlineGroup are still drawn) and every outline is drawn.
  outlines,
  /// QNV splats; for OutlineGroups the same as polygons for now.
  splats,
};

/// One row of the render-mode table: the mode's name on the command line (--mode), in
/// window scripts and in status files.
struct RenderModeInfo {
  RenderMode mode;
  std::string_view name;
};

inline constexpr std::array<RenderModeInfo, 3> kRenderModes = {{
    {RenderMode::polygons, "polygons"},
    {RenderMode::splats, "splats"},
    {RenderMode::outlines, "outlines"},
}};

/// The name of `mode` ("polygons", "splats", "outlines").
constexpr std::string_view renderModeName(RenderMode mode) {
  for (const RenderModeInfo& info : kRenderModes)
    if (info.mode == mode) return info.name;
  return "polygons";
}

/// The mode named `name` (exactly as in kRenderModes), or nullopt.
constexpr std::optional<RenderMode> renderModeFromName(std::string_view name) {
  for (const RenderModeInfo& info : kRenderModes)
    if (info.name == name) return info.mode;
  return std::nullopt;
}

/// How a traversal reads Inline files and tessellates geometry.
/// How many nodes deep a walk of the scene graph goes (SceneTraversal::collect and the
/// walks made for bounds, picking and collisions): a file nests at most 256 nodes
/// (encodings' ParseLimits::maxNesting), a chain of Inlines a few more; deeper, or a node
/// a Script put among its own descendants (a cycle), is not walked below, with one error.
/// Twice a file's nesting, and within an 8 MiB stack under AddressSanitizer (which went
/// about 700 levels deep before it ran out, measured).
inline constexpr int kMaxWalkDepth = 512;

struct TraversalOptions {
  /// Reads Inline worlds whole (clause 6.25; FetchMode::whole, the Inline's world as the
  /// referrer) and their EXTERNPROTOs when inlineSource is empty; not owned, must outlive
  /// the traversal. Null: local files and data: URLs only (base::LocalFetcher); other
  /// schemes fail with a diagnostic.
  base::Fetcher* fetcher = nullptr;
  /// Progressive Inline worlds (wins over fetcher): the scene at an already
  /// resolved `url` named by content from `referrer`, which may still be loading and
  /// grows in place (call SceneTraversal::sceneChanged() after it grew). Null with
  /// `error` set when the URL is refused or cannot be loaded.
  std::function<std::shared_ptr<const vrml::Scene>(const std::string& url,
                                                   const std::string& referrer, std::string& error)>
      inlineSource;
  /// Tessellates a geometry node. Empty: scene::tessellateGeometry (vrml::tessellate, and
  /// Text through scene/text_mesh.hpp).
  std::function<vrml::Mesh(const vrml::Node& geometry, vrml::Diagnostics* diag)> tessellator;
  /// Nesting limit for Inline files inlining others.
  int maxInlineDepth = 16;
  /// What to draw of OutlineGroups.
  RenderMode mode = RenderMode::polygons;
};

/// The nodes on top of the four bindable stacks (clause 4.6.10), as the execution model
/// (runtime::ExecutionModel::bound) says; null: that stack is empty (defaults apply).
struct BoundNodes {
  const vrml::Node* viewpoint = nullptr;
  const vrml::Node* navigationInfo = nullptr;
  const vrml::Node* background = nullptr;
  const vrml::Node* fog = nullptr;
  bool operator==(const BoundNodes&) const = default;
};

/// Walks one scene. Not thread-safe. Results are cached per node: the scene (and its
/// Inline scenes) may only grow by root nodes appended between calls (progressive
/// loading), each time followed by sceneChanged().
class SceneTraversal {
 public:
  /// Finds the bindable nodes (first Viewpoint, NavigationInfo, Background, Fog in
  /// depth-first file order, with their world transforms; bindable nodes inside Inline
  /// files are not bound, as the Inline file is only geometry to its parent) and lists
  /// every Viewpoint. Loads nothing yet.
  explicit SceneTraversal(std::shared_ptr<const vrml::Scene> scene, TraversalOptions options = {});

  const vrml::Scene& scene() const { return *scene_; }
  const std::shared_ptr<const vrml::Scene>& sharedScene() const { return scene_; }
  /// Every Viewpoint of the main file in depth-first order (the first is bound).
  const std::vector<ViewpointInfo>& viewpoints() const { return viewpoints_; }
  /// The scene or an Inline scene gained root nodes: finds the bindable nodes again and
  /// forgets the world bounds (tessellations and loaded Inlines are kept).
  void sceneChanged();
  const NavigationSettings& navigation() const { return navigation_; }
  const BackgroundSettings& background() const { return background_; }
  const FogSettings& fog() const { return fog_; }

  /// Camera of viewpoint `index` (of viewpoints()), or of the VRML97 default Viewpoint
  /// (position 0 0 10, looking along -Z, fieldOfView 0.785398) when `index` is out of
  /// range, with clip planes: near = NavigationInfo avatarSize[0] / 2 (lowered when the
  /// scene is closer than that), far = visibilityLimit, or just beyond the scene's
  /// bounding sphere when that is 0. Computes worldBounds() (loading Inlines).
  Camera viewpointCamera(std::size_t index);
  /// Where ParticleSystems' particles come from (X3D 4.0 clause 40; session::WorldView
  /// gives the world's execution model). Without one a ParticleSystem draws nothing.
  void setParticleSource(ParticleSource source) { particleSource_ = std::move(source); }

  /// The camera of the bound Viewpoint (the first one until setBoundNodes() says
  /// otherwise), or the default one.
  Camera boundViewpointCamera() { return viewpointCamera(boundViewpoint_); }
  /// Index in viewpoints() of the bound Viewpoint; out of range when none is bound.
  std::size_t boundViewpointIndex() const { return boundViewpoint_; }

  /// From now on the bound nodes are those the execution model names (instead of the
  /// first of each type in file order); the settings are read again when the nodes or
  /// their fields (vrml::Node::revision) changed since the last call. Cheap when nothing
  /// changed: call it every frame.
  void setBoundNodes(const BoundNodes& bound);

  /// The Inline worlds loaded so far (each once, in load order): the execution model
  /// runs their routes and sensors (runtime::ExecutionModel::addInlineScene).
  const std::vector<std::shared_ptr<const vrml::Scene>>& inlineScenes() const {
    return inlineScenesLoaded_;
  }

  /// The world loaded for `inlineNode` (an Inline of the scene or of a loaded Inline world),
  /// or null when it was not loaded (not met yet, or failed). Loads nothing: for the
  /// Sounds inside Inlines (audio::SoundScene) and X3D IMPORTs (session::WorldRuntimes).
  std::shared_ptr<const vrml::Scene> loadedInline(const vrml::Node& inlineNode) const;

  /// An Inline node the traversal met and what loading it gave: its world (which may
  /// still be streaming in, TraversalOptions::inlineSource), or null when no url could be
  /// loaded.
  struct InlineLoad {
    const vrml::Node* node = nullptr;
    std::shared_ptr<const vrml::Scene> scene;
  };
  /// Every Inline node met so far (drawing or computing bounds loads them), in no
  /// particular order: what session::WorldRuntimes reports to X3D LoadSensors
  /// (runtime::ExecutionModel::setUrlObjectState). Loads nothing.
  std::vector<InlineLoad> inlineLoads() const;

  /// The output events of the collects that reported them (TraversalFrame::reportOutputs)
  /// since the last call, for runtime::ExecutionModel::sendDrawnOutputs: a LOD's
  /// level_changed when the level it shows changed (X3D 4.0 clause 10.4.2; the level
  /// selectLodLevel chose), a GeoLOD's level_changed (25.4.5: 1 within `range` of its
  /// center, else 0) and children (the root nodes of the four children's files once all
  /// have loaded, else its rootNode, else the root nodes of its rootUrl's file) when they
  /// changed. Each node's first report is an event. At most 65,536 wait: past that the
  /// oldest half is dropped (a caller that never takes them).
  vrml::DrawnOutputs takeDrawnOutputs() { return std::exchange(drawnOutputs_, {}); }

  /// How many tessellations collect() and mesh() made (a changed geometry is
  /// tessellated again; an animated Transform is not): for benchmarks and tests.
  std::uint64_t tessellationCount() const { return tessellations_; }

  /// Collects the shapes and lights to draw for a viewer at `viewer` (which selects LOD
  /// levels and orients Billboards) into `frame` (cleared first). Inline files are loaded
  /// the first time they are met; problems become diagnostics.
  void collect(const Camera& viewer, TraversalFrame& frame);
  /// The size of the view in pixels (width, height), for X3D Layout's ScreenGroup and
  /// LayoutGroup units (clause 36); 640x480 until set. The renderer sets it before collect().
  void setViewportSize(int width, int height) {
    viewportPixels_ = glm::vec2(std::max(width, 1), std::max(height, 1));
  }

  /// The tessellation of `geometry`, computed once and cached (per node).
  const vrml::Mesh& mesh(const vrml::Node& geometry);
  /// Frees the cached arrays of `geometry`'s mesh (e.g. after a GPU upload) but keeps its
  /// bounds; a later mesh() call tessellates again.
  void dropMeshArrays(const vrml::Node& geometry);
  /// Bounds of `geometry`'s mesh in its local coordinates.
  const vrml::Bounds& meshBounds(const vrml::Node& geometry);

  /// World bounding box of what is drawn from the bound Viewpoint (the chosen Switch
  /// children and LOD levels, Inlines included), computed once. Exact: a shape whose
  /// transform only scales, translates or swaps axes contributes its local box's 8
  /// corners; any other (rotated, sheared) shape its transformed mesh points, which are
  /// kept for that purpose when dropMeshArrays() drops the rest (or tessellated again).
  const vrml::Bounds& worldBounds();

  /// Problems met while traversing (Inline load failures and their own diagnostics,
  /// tessellation warnings), each reported once.
  const vrml::Diagnostics& diagnostics() const { return diagnostics_; }
  /// Adds a diagnostic unless an identical one (same place and message) was reported.
  void report(vrml::Severity severity, const vrml::SourceLocation& where,
              const std::string& message);

 private:
  glm::vec2 viewportPixels_{640.0f, 480.0f};
  /// A loaded Inline world, shared by every Inline node naming the same resolved URL.
  struct InlineScene {
    std::string url;                           // resolved; the base for URLs inside it
    std::shared_ptr<const vrml::Scene> scene;  // null when loading failed
  };
  struct Walk;
  struct CachedMesh {
    vrml::Mesh mesh;
    bool arraysDropped = false;
    bool rotatedUse = false;                 // worldBounds() needed its points
    std::vector<glm::vec3> boundsPositions;  // the positions kept by dropMeshArrays()
    std::uint64_t revision = 0;              // vrml::revisionWithFields of the geometry
    float nurbsScale = 1.0f;                 // the NurbsSet tessellationScale it was made at
  };
  /// NurbsSets met (X3D 4.0 27.4.6): each NURBS surface of their `geometry` to the set,
  /// whose tessellationScale its mesh is made at (traversal_meshes.cpp).
  std::unordered_map<const vrml::Node*, const vrml::Node*> nurbsSets_;
  /// A NurbsSet met in the scene graph: its surfaces take its tessellationScale.
  void noteNurbsSet(const vrml::Node& set);
  /// The tessellationScale of the NurbsSet that holds `geometry` (>= 0), 1 for none.
  float nurbsScaleOf(const vrml::Node& geometry) const;
  void findBindables();
  const InlineScene* inlineScene(const vrml::Node& inlineNode, const std::string& baseUrl);
  CachedMesh& cachedMesh(const vrml::Node& geometry);
  /// The geometry node that stands for ParticleSystem `system`'s particles drawn as its
  /// geometryType (not GEOMETRY) seen with `localToEye` (the modelview), its mesh made
  /// (particles/particle_mesh.hpp) and put in the tessellation cache; null when no
  /// simulation runs it (scene/src/traversal_particles.cpp).
  const vrml::Node* particleGeometry(const vrml::Node& system,
                                     const particles::ParticleSimulation& simulation,
                                     const glm::mat4& localToEye);
  /// X3D 4.0's X3DBoundedObject.bboxDisplay (clause 10.3.1), as X_ITE draws it: the
  /// Shape (no appearance: unlit white lines) and IndexedLineSet standing for the 12 edges
  /// of `box` (the bounded node's box in its children's coordinates), cached per node, its
  /// Coordinate rewritten when the box changes (scene/src/traversal_bbox.cpp); none for a
  /// box that is empty or not finite.
  struct BoxOutline {
    const vrml::Node* shape = nullptr;
    const vrml::Node* geometry = nullptr;
  };
  BoxOutline boxOutline(const vrml::Node& bounded, const vrml::Bounds& box);
  /// The box of bounded node `n` in its children's coordinates (`inner`: those to world):
  /// its bboxCenter and bboxSize when given (no component of the size -1), else the box
  /// of the meshes of `shapes` (the shapes its traversal added) seen from there.
  vrml::Bounds boundedBox(const vrml::Node& n, std::span<const ShapeInstance> shapes,
                          const glm::mat4& inner);
  /// The groupIds (>= 0) of the OutlineGroups of `scene` that have children, computed
  /// once per scene (every node reachable from its root nodes).
  const std::unordered_set<std::int32_t>& filledGroups(const vrml::Scene& scene);

  std::shared_ptr<const vrml::Scene> scene_;
  TraversalOptions options_;
  std::string mainUrl_;  // the scene's url made absolute when it is a local path
  std::vector<ViewpointInfo> viewpoints_;
  NavigationSettings navigation_;
  BackgroundSettings background_;
  FogSettings fog_;
  std::unordered_map<const vrml::Node*, CachedMesh> meshes_;
  std::unordered_map<const vrml::Scene*, std::unordered_set<std::int32_t>> filledGroups_;
  std::map<std::string, std::shared_ptr<InlineScene>> inlinesByUrl_;
  std::unordered_map<const vrml::Node*, std::shared_ptr<InlineScene>> inlinesByNode_;
  /// The url field each node's entry was resolved from: a url changed since (a Script
  /// routing to set_url, clause 6.25) resolves the node again.
  std::unordered_map<const vrml::Node*, std::vector<std::string>> inlineUrlsByNode_;
  std::vector<std::shared_ptr<const vrml::Scene>> inlineScenesLoaded_;
  std::size_t boundViewpoint_ = 0;
  std::optional<BoundNodes> runtimeBound_;  // set: the execution model decides
  ParticleSource particleSource_;
  /// Per ParticleSystem: the node its mesh is cached under and what that mesh was made of.
  struct ParticleDraw {
    vrml::NodePtr geometry;
    std::uint64_t simulationRevision = ~std::uint64_t{0};
    glm::mat3 eyeToLocal{0.0f};
    int type = -1;
  };
  vrml::NodeMap<ParticleDraw> particleDraws_;
  /// Per node with bboxDisplay TRUE: its outline's nodes and the box they were made of.
  struct BoxDraw {
    vrml::NodePtr shape, geometry, coord;
    vrml::Bounds box;
  };
  vrml::NodeMap<BoxDraw> boxDraws_;
  /// Per GeoLOD: Inline nodes of its rootUrl and child1Url ... child4Url (what the
  /// Inline loading reads), made when first met.
  vrml::NodeMap<std::array<vrml::NodePtr, 5>> geoLodInlines_;
  /// What each LOD and GeoLOD showed at the last report (traversal_levels.cpp), and the
  /// events not taken yet.
  struct ShownLevel {
    int level = -1;
    std::vector<const vrml::Node*> nodes;  // a GeoLOD's children output
  };
  vrml::NodeMap<ShownLevel> shownLevels_;
  vrml::DrawnOutputs drawnOutputs_;
  /// Notes that LOD or GeoLOD `n` shows `level` (and, for a GeoLOD, the nodes of the lists
  /// `shown` points to, in order; null: no children output): events into drawnOutputs_
  /// for what changed. The lists are compared in place; a children event copies them.
  void noteShownLevel(const vrml::Node& n, int level,
                      std::span<const std::vector<vrml::NodePtr>* const> shown);
  void noteShownLevel(const vrml::Node& n, int level, const std::vector<vrml::NodePtr>* shown);
  /// GeoLOD `n`'s Inline standing for url field `k` (0: rootUrl, 1..4: childKUrl).
  const vrml::Node& geoLodInline(const vrml::Node& n, int k);
  std::uint64_t boundRevision_ = 0;
  std::uint64_t tessellations_ = 0;
  vrml::Bounds worldBounds_;
  bool haveWorldBounds_ = false;
  vrml::Diagnostics diagnostics_;
  std::set<std::string> reported_;
  TraversalFrame scratch_;
  std::vector<std::uint32_t> scopeScratch_;       // reused by collect()
  std::int32_t firstGlobalEnvironment_ = -1;      // collect(): the first global EnvironmentLight
  std::vector<glm::vec4> clipScratch_;            // collect(): the ClipPlanes in scope
  std::vector<const std::string*> chainScratch_;  // reused by collect()
};

// ---- Node maths, exposed for tests ----

/// Transform matrices (6.52) and SFRotation matrices: vrml/transform.hpp.
using vrml::rotationMatrix;
using vrml::transformMatrix;

/// The LOD level (clause 6.26) for a viewer at `distance` metres from the LOD's center:
/// level 0 below range[0], level i when range[i-1] <= distance < range[i], the last level
/// beyond; clamped to levelCount - 1. An empty range selects level 0. Returns -1 when
/// levelCount is 0.
int selectLodLevel(const std::vector<float>& range, float distance, std::size_t levelCount);

/// The rotation a Billboard (clause 6.6) applies to its children, in its own coordinate
/// system: `viewer` is the viewer's position there and `viewerUp` its up vector. A
/// non-zero `axisOfRotation` turns the local Z axis towards the viewer around that axis;
/// a zero axis aligns local Z with the direction to the viewer and local Y with viewerUp.
/// Identity when the viewer lies on the axis.
glm::mat4 billboardRotation(const glm::vec3& axisOfRotation, const glm::vec3& viewer,
                            const glm::vec3& viewerUp);

/// The texture-coordinate matrix of a TextureTransform (clause 6.49):
/// Tc' = -C x S x R x C x T x Tc, as a 3x3 homogeneous 2D matrix. Also X3D's
/// TextureTransform3D (the same product in 3D), TextureTransformMatrix3D (its `matrix`,
/// written row by row for row vectors: the translation in its last row) and MultiTextureTransform
/// (its first transform), all applied to (s, t, 0, 1) and kept in 2D (X3D 4.0
/// clauses 33.4.8, 33.4.9, 18.4.5).
glm::mat3 textureTransformMatrix(const vrml::Node& textureTransform);

/// The same transforms as 4x4 matrices acting on 3D texture coordinates (s, t, r, 1), for
/// X3D's Texturing3D (clause 33): TextureTransform3D's -C x S x R x C x T product,
/// TextureTransformMatrix3D's matrix, a 2D TextureTransform acting on (s, t) only, and
/// MultiTextureTransform's first transform.
glm::mat4 textureTransformMatrix3D(const vrml::Node& textureTransform);

}  // namespace gs::scene
