// Draws one VRML97 scene with OpenGL 3.3 core: Background, opaque shapes, then
// transparent shapes sorted back to front, lit per fragment by the VRML97 lighting model
// (clause 4.14) with textures, fog, scoped DirectionalLights, PointLights, SpotLights
// and the headlight. The same code draws into a window or an off-screen framebuffer.
#pragma once

#include "render/browser_options.hpp"
#include "render/splat_renderer.hpp"
#include "render/splat_source.hpp"
#include "scene/camera.hpp"

#include <glm/gtc/quaternion.hpp>
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace gs::render {

/// The front view of a volume (issue 42, friction 9): a CT stack opened looking down its
/// slice axis showed CThead from above, where 3D Slicer's anterior view shows the face.
/// For a stack laid out as CThead is (rows from the face, row 0, to the back of the head;
/// slices from the top of the head down) the camera looks along +Y with -Z up: a turn of
/// pi about (0, 1, -1) / sqrt 2.
inline glm::quat volumeFrontOrientation() {
  return glm::quat(0.0f, 0.0f, 0.70710678f, -0.70710678f);
}

class MoviePlayers;

namespace detail {
class SceneSplats;
}

/// MovieTexture (6.28): the seconds into `movie`'s clip to show now, from the execution
/// model (runtime::ExecutionModel::mediaTime); empty: the first frame.
using MediaClock = std::function<std::optional<double>(const vrml::Node& movie)>;

struct SceneRendererOptions {
  /// Reads ImageTexture, MovieTexture and Background panorama urls in the background
  /// (base::FetchMode::background: a texture still on its way is drawn untextured, without
  /// a diagnostic, and asked for again at a later draw), and is the traversal's fetcher
  /// when traversal.fetcher is null. Not owned; must outlive the renderer. Null: local
  /// files and data: URLs only.
  base::Fetcher* fetcher = nullptr;
  scene::TraversalOptions traversal;
  /// Diameter of PointSet points in pixels; 0: the world's default, 1 pixel for X3D worlds
  /// (X_ITE 15's, the reference for X3D) and 2 for VRML97 worlds.
  float pointSize = 0.0f;
  /// Loads the vectors of QuantizedNormalVectors urls. Empty: local .qnv files.
  SplatLoader splatLoader;
  /// Level of detail: the fraction of every QNV stream drawn (times the node's own
  /// fraction or count), 0..1. traversal.mode = RenderMode::splats draws the polygon
  /// world as splats.
  double lod = 1.0;
  /// How the splat pass turns vectors into pixels (`--splat-path`; docs/rendering.md).
  SplatPath splatPath = SplatPath::automatic;
  /// MovieTexture players (render/movie_players.hpp) shared with the other renderers
  /// given the same registry: renderers of one world then decode each movie once. Null: a
  /// registry of this renderer's own.
  std::shared_ptr<MoviePlayers> movies;
  /// Draw Phong shapes with shader variants specialized to what each uses (lights, texture,
  /// fog, colours), compiled a few per frame from the second frame on; false: always the
  /// one generic program (the same pixels, more work per pixel). docs/rendering.md.
  bool shaderVariants = true;
  /// `--texture-quality`: the filter of textures without TextureProperties.
  TextureQuality textureQuality = TextureQuality::high;
  /// `--shading`: where a Material shape's texture enters the lighting.
  ShadingOption shading = ShadingOption::phong;
};

/// What the last draw() did.
struct DrawStatistics {
  std::size_t shapes = 0;          // Shape nodes drawn (instances)
  std::size_t triangles = 0;       // triangles submitted
  std::size_t transparent = 0;     // shapes drawn in the blended pass
  std::size_t splats = 0;          // QNV vectors drawn
  std::size_t shaderVariants = 0;  // specialized surface programs built so far
  /// New MovieTexture frames drawn since the renderer was made (each movie frame once,
  /// however often it is drawn): docs/media.md's "frames shown".
  std::uint64_t movieFrames = 0;
  /// Of those, the frames this renderer copied into a movie's texture itself; renderers
  /// sharing SceneRendererOptions::movies share the texture, so one copies, the others not.
  std::uint64_t movieUploads = 0;
};

/// Holds the GPU resources of one scene. CPU work (traversal, viewpoints, bounds) needs
/// no OpenGL context; draw() needs the context current in which all draws of this
/// renderer happen, and the GL objects are created on the first draw. Destroy the
/// renderer (or call releaseGpuResources()) while that context is still current.
class SceneRenderer {
 public:
  /// Finds the bindable nodes and viewpoints; loads nothing else yet.
  explicit SceneRenderer(std::shared_ptr<const vrml::Scene> scene,
                         SceneRendererOptions options = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// Draws the scene seen by `camera` into the rectangle (x, y, width, height) of the
  /// current framebuffer (pixels, lower-left origin as glViewport): the Background fills
  /// the rectangle and its depth is cleared; pixels outside it are untouched. Throws
  /// std::runtime_error when a shader fails to compile (a broken driver). Problems with
  /// the content (missing textures or Inlines) are diagnostics, never exceptions.
  void draw(const scene::Camera& camera, int x, int y, int width, int height);

  /// Every Viewpoint of the main file, depth-first (for a viewpoint menu).
  const std::vector<scene::ViewpointInfo>& viewpoints() const { return traversal_.viewpoints(); }
  /// Camera of the bound (first) Viewpoint or the VRML97 default, with clip planes from
  /// NavigationInfo and the scene bounds (SceneTraversal::viewpointCamera).
  scene::Camera boundViewpointCamera() { return traversal_.boundViewpointCamera(); }
  /// The camera to start with in a viewport of aspect width / height: the bound
  /// Viewpoint's when the file has one; otherwise the VRML97 default orientation and field
  /// of view moved back to show the whole scene (the default position 0 0 10 often shows
  /// nothing useful): for a glTF asset where castle-model-viewer puts it
  /// (scene::wholeSceneCamera), for other worlds just far enough (scene::fitCamera).
  scene::Camera initialCamera(float aspect);
  /// Camera of viewpoints()[index] with clip planes as boundViewpointCamera().
  scene::Camera viewpointCamera(std::size_t index) { return traversal_.viewpointCamera(index); }
  /// World bounding box of the scene as drawn from the bound Viewpoint (loads Inlines,
  /// tessellates all geometry and loads QNV streams the first time).
  const vrml::Bounds& bounds();
  /// The scene, an Inline scene or a QNV set grew (progressive loading, see
  /// SceneTraversal): bindable nodes are found again and the bounds recomputed on the
  /// next bounds(); tessellations and GPU meshes already made are kept.
  void sceneChanged();
  /// At most `vectors` QNV vectors drawn per frame in all (0: no budget): every stream's
  /// level of detail is lowered by the same factor to fit (SceneRendererOptions::lod stays
  /// the upper bound).
  void setVectorBudget(std::uint64_t vectors);
  /// Changes the level of detail of every QNV stream (SceneRendererOptions::lod).
  void setLod(double lod);
  /// The view a world without a Viewpoint starts in: VRML97's default (looking down -Z,
  /// +Y up), or, when everything it shows is QNV volumes, the anatomical front view
  /// (volumeFrontOrientation). Loads the scene's QNV nodes (bounds()).
  glm::quat defaultOrientation();
  /// A camera looking along `direction`'s view direction that frames the whole scene in a
  /// viewport of aspect width / height (fitCamera on bounds()).
  scene::Camera fitToScene(float aspect, const scene::Camera& direction) {
    return scene::fitCamera(bounds(), aspect, direction);
  }
  /// The bound NavigationInfo (type, headlight, speed, avatarSize, visibilityLimit).
  const scene::NavigationSettings& navigation() const { return traversal_.navigation(); }

  /// Whether the headlight is on; starts as NavigationInfo.headlight.
  bool headlight() const { return headlight_; }
  void setHeadlight(bool on) {
    headlight_ = on;
    headlightSet_ = true;
  }

  /// The browser option Shading (browser_options.hpp) from the next draw() on: the
  /// command line's `--shading` at first, then what a Script of the world sets with
  /// Browser.setBrowserOption("Shading", ...) (session::WorldView::draw).
  ShadingOption shading() const { return options_.shading; }
  void setShading(ShadingOption shading) { options_.shading = shading; }

  /// Where MovieTextures take their media time from (docs/media.md). `waitForFrames`:
  /// draw() waits for the frame of that time (--snapshot: the same pixels every run);
  /// otherwise it shows the newest frame decoded so far and never waits (the window).
  void setMediaClock(MediaClock clock, bool waitForFrames);
  /// The durations of the MovieTextures whose movies opened (seconds; -1: unreadable)
  /// since the last call, for runtime::ExecutionModel::setMediaDuration.
  std::vector<std::pair<const vrml::Node*, double>> takeMediaDurations();
  /// The ImageTextures and ImageTexture3Ds (X3DUrlObject textures) whose loading ended
  /// since the last call: true when the image was read, false when no url could be. For
  /// X3D LoadSensors (runtime::ExecutionModel::setUrlObjectState). A texture loads when
  /// first drawn.
  std::vector<std::pair<const vrml::Node*, bool>> takeUrlObjectLoads();
  /// The output events drawing computed since the last call (vrml/drawn_output.hpp), for
  /// runtime::ExecutionModel::sendDrawnOutputs: the levels LODs and GeoLODs show
  /// (scene::SceneTraversal::takeDrawnOutputs), then the shaders' isValid and isSelected
  /// (X3D 4.0 clause 31.3.1: TRUE for the shader an Appearance draws with, isValid FALSE
  /// for one that does not compile or link), then the TextureProjectors' aspectRatio
  /// (42.4.1: the texture's width over height, once it loaded), each in the order it
  /// changed.
  vrml::DrawnOutputs takeDrawnOutputs();

  /// Counts of the last draw().
  const DrawStatistics& statistics() const { return statistics_; }
  /// Triangles drawn by the last draw().
  std::size_t trianglesDrawn() const { return statistics_.triangles; }

  /// Problems met while loading Inlines and textures or tessellating, each once.
  const vrml::Diagnostics& diagnostics() const { return traversal_.diagnostics(); }
  /// The CPU traversal (for tests and tools).
  scene::SceneTraversal& traversal() { return traversal_; }

  /// Frees every GL object (the renderer's context must be current); the next draw()
  /// creates them again.
  void releaseGpuResources();

 private:
  struct Gpu;
  SceneRendererOptions options_;
  scene::SceneTraversal traversal_;
  std::unique_ptr<Gpu> gpu_;
  std::unique_ptr<detail::SceneSplats> splats_;
  vrml::Bounds bounds_;
  bool haveBounds_ = false;
  bool headlight_ = true;
  bool headlightSet_ = false;  // setHeadlight() was called: NavigationInfo no longer decides
  DrawStatistics statistics_;
  // GeneratedCubeMapTexture (detail/generated_cube_maps.hpp): whether a shape has shown one
  // (then each draw first draws the due ones' faces), whether a face is being drawn now,
  // and the geometry of the shape whose cube map it is (not drawn into it).
  bool generatedCubeMaps_ = false;
  bool generatingFace_ = false;
  const vrml::Node* faceExcludes_ = nullptr;
  /// Draws the faces of the due GeneratedCubeMapTextures of the shapes `camera` would
  /// draw, each from its shape's origin in the world, the shape itself left out.
  void generateCubeMaps(const scene::Camera& camera);
  /// Sorts the frame's shapes (gpu_->frame) into gpu_->opaque and gpu_->transparent (back
  /// to front along `camera`'s view), uploading meshes and loading textures as they come
  /// (scene_draw_items.cpp).
  void collectDrawItems(const scene::Camera& camera);
};

}  // namespace gs::render
