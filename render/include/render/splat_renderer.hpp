// The splat pass (Nagasawa, "Beyond VRML", sections 3.1 and 3.5) over the one splat model
// (splats/gaussian.hpp, docs/splats.md): a 3D Gaussian splatting scene's anisotropic
// Gaussians, and every decoded QNV vector as the flat-disc Gaussian across its normal with
// the paper's opacity profile (render/splat_model.hpp, vectorGaussian), shaded flat by the
// lights; each projected by EWA and composited in view-depth order as equation (1) says.
// OpenGL 3.3 core; the same code draws into a window or an OSMesa framebuffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/geometry.hpp"
#include "qnv/decoder.hpp"
#include "render/splat_model.hpp"
#include "scene/camera.hpp"
#include "splats/gaussian.hpp"
#include "splats/lod_tree.hpp"

namespace gs::render {

/// How one viewport drew a view-dependent set (a QNV tileset): its camera (world
/// coordinates), the node's placement (set coordinates to world), viewport aspect and
/// height (pixels), and the vectors its level of detail asked for.
struct SplatView {
  scene::Camera camera;
  glm::mat4 model{1.0f};
  float aspect = 1.0f;
  int heightPixels = 0;
  std::uint64_t vectors = 0;
};

/// The views that ask a view-dependent set for vectors (docs/tilesets.md, "Views"): each
/// scene renderer that draws the set holds one Request and updates it every frame it
/// draws; destroying the Request releases it, so a closed viewport stops choosing and
/// fetching bricks. The tileset loader reads views(). Drawing thread only.
class SplatViewRequests : public std::enable_shared_from_this<SplatViewRequests> {
 public:
  /// One viewport's request; releases itself when destroyed (also after the registry).
  class Request {
   public:
    ~Request();
    Request(const Request&) = delete;
    Request& operator=(const Request&) = delete;
    /// Records how the viewport drew the set this frame.
    void update(const SplatView& view);

   private:
    friend class SplatViewRequests;
    Request(std::weak_ptr<SplatViewRequests> registry, std::uint64_t id)
        : registry_(std::move(registry)), id_(id) {}
    std::weak_ptr<SplatViewRequests> registry_;
    std::uint64_t id_;
  };
  /// A new request (no view until its first update()). The registry must be owned by a
  /// shared_ptr (SplatSet::viewRequests is).
  std::unique_ptr<Request> request();
  /// The last view of every live request that was updated, keyed by request (in the order
  /// the requests were made).
  const std::map<std::uint64_t, SplatView>& views() const { return views_; }

 private:
  std::map<std::uint64_t, SplatView> views_;
  std::uint64_t next_ = 1;
};

/// One stream's vectors, ready to draw: in stream order (largest first), so the first N
/// are the level of detail N. Positions and normals are in the coordinates of the node
/// that shows them (world coordinates for a .qnv opened directly).
/// A set may grow while its stream arrives (progressive loading): vectors are only
/// appended (or placed past the end), never changed once present, so a renderer uploads
/// only the new tail.
struct SplatSet {
  std::vector<qnv::DecodedVector> vectors;
  SplatStyle style;
  vrml::Bounds bounds;  // of the positions, grown by the largest splat extent
  /// Vectors in the whole stream while it is still arriving (the header's count); 0 when
  /// `vectors` is all of it. Levels of detail are fractions of total().
  std::uint64_t expectedVectors = 0;
  /// The longest prefix any view asked to draw so far (set while drawing); a progressive
  /// loader fetches up to it (HTTP range requests).
  mutable std::uint64_t wantedVectors = 0;
  /// Bumped whenever vectors already present change (a late packet filling a gap): the
  /// renderer then uploads the whole set again instead of only the new tail.
  std::uint64_t revision = 0;
  /// Whether the vectors depend on the view (a QNV tileset, session/tileset_stream.hpp):
  /// then every scene renderer that draws the set registers a request in viewRequests
  /// and updates it with how it drew it; the loader chooses the bricks from those views.
  bool viewDependent = false;
  using View = SplatView;
  /// The views that ask for the set's vectors (shared: renderers hold requests on it).
  std::shared_ptr<SplatViewRequests> viewRequests = std::make_shared<SplatViewRequests>();
  /// A 3D Gaussian splatting scene (splats/gaussian.hpp; docs/splats.md) instead of QNV
  /// vectors: when set, `vectors` is empty and the set draws these Gaussians, in their
  /// importance order (splats::sortByImportance), so the first N are the level of detail N.
  std::shared_ptr<const splats::GaussianCloud> gaussians;
  /// The level-of-detail tree of merged Gaussians over `gaussians` (splats/lod_tree.hpp;
  /// docs/splats-lod.md), or null: with it, each view draws the cut of the tree whose
  /// nodes project below one pixel, under the view's budget (the level of detail's share
  /// of the splats), instead of a prefix. A progressive stream's tree may cover only the
  /// first LodTree::splatCount splats (the prefix that had arrived): the splats after them
  /// that the view's budget reaches (index below it, as a prefix) are then drawn whole
  /// beside the cut until a tree over them replaces it. A tree over
  /// more splats than `gaussians` holds is ignored.
  std::shared_ptr<const splats::LodTree> lodTree;
  /// A QNV tileset's merged levels (docs/tilesets.md, "Merged levels"), or null: the merged
  /// Gaussians of the nodes the views draw merged, a set of `gaussians` drawn whole, before
  /// (behind) this set's vectors, each depth-tested at its centre.
  std::shared_ptr<const SplatSet> merged;
  /// Why the set's source could not be read after the set was handed out (a Gaussian
  /// splatting scene read in the background, session/src/gaussian_scene_load.hpp:
  /// "garden.spz: unsupported SPZ version 9"); empty otherwise. The renderer reports it
  /// as the node's error, as it reports a url that could not be loaded at once.
  std::string loadError;
  /// Vectors of the whole stream: expectedVectors, or the vectors (or Gaussians) present.
  std::uint64_t total() const {
    if (expectedVectors > 0) return expectedVectors;
    return gaussians ? gaussians->size() : vectors.size();
  }
  /// Splats present: vectors.size(), or the Gaussians' count.
  std::size_t size() const { return gaussians ? gaussians->size() : vectors.size(); }
  /// Bounds of the positions of `vectors` (or of the Gaussians' centres); call after
  /// filling them.
  void computeBounds();
};

/// Whether the scene's depth hides splats. backToFront: each splat is depth-tested at its
/// centre against the framebuffer's depth (the GL path blends it over the framebuffer, C =
/// a c + (1 - a) C, farthest first; the cpu path composites front to back and reads the
/// depth back). frontToBack: nothing hides the splats (the GL path still blends back to
/// front, with an empty depth buffer's result; the cpu path composites front to back,
/// C += T a c, T *= 1 - a). Both give the same image up to 8-bit rounding.
enum class SplatBlend { backToFront, frontToBack };

/// How the pass turns splats into pixels. Both draw the same model (the picture agrees with
/// the CPU reference of equation (1), splat_reference.hpp); they differ in speed
/// (docs/rendering.md, bench_splats).
enum class SplatPath {
  /// The GL path (src/gaussian_gl.hpp): one instanced quad per Gaussian, projected in the
  /// vertex shader, back to front in the CPU's radix-sort order. `points` is an older name
  /// of it (until 2026-11 a point-sprite path for QNV vectors); statistics report
  /// `geometry`.
  points,
  /// The GL path, as `points`.
  geometry,
  /// The GL path with its depth order sorted on the GPU (src/gpu_sort.hpp: a radix sort in
  /// OpenGL 4.3 compute shaders; the order never comes back to the CPU). Where the context
  /// lacks compute shaders it draws as `geometry` (SplatStatistics::path says which ran).
  gpu,
  /// A multi-threaded CPU rasterizer (src/gaussian_cpu.hpp) composites the splats front to
  /// back into a premultiplied RGBA8 image, depth-tested against the framebuffer's depth
  /// (under backToFront: read once per draw, under the tiles the splats reach), then
  /// drawn as one textured quad over those tiles. The fastest path where GL itself runs
  /// on the CPU (llvmpipe, softpipe).
  cpu,
  /// `cpu` when the GL renderer (GL_RENDERER) is llvmpipe or softpipe, else `gpu` (or
  /// `geometry` without compute shaders); resolved at the first draw. Only a setting:
  /// SplatStatistics::path is never automatic.
  automatic,
};

/// "points", "geometry", "gpu", "cpu" or "auto"; parseSplatPath returns false for any other
/// text.
const char* splatPathName(SplatPath path);
bool parseSplatPath(const char* text, SplatPath& path);
/// What `automatic` means for a GL_RENDERER string: `cpu` when it contains "llvmpipe" or
/// "softpipe", else `gpu` (a null string: `gpu`); SplatRenderer draws `gpu` as `geometry`
/// where compute shaders are missing.
SplatPath automaticSplatPath(const char* glRenderer);

/// What the last draw() did.
struct SplatStatistics {
  std::size_t splats = 0;                // vectors drawn
  bool sorted = false;                   // whether the view moved and the depth sort ran
  double sortSeconds = 0.0;              // CPU time of that sort
  SplatPath path = SplatPath::geometry;  // the path that drew (cpu, geometry or gpu)
};

/// GPU resources for drawing splat sets. Create, draw and destroy with the same context
/// current. Keeps the last uploaded set (compared by address and size) and the last
/// depth order, re-sorting only when the view or the count changed; no allocation per
/// frame once a set and a count have been drawn.
class SplatRenderer {
 public:
  SplatRenderer();
  ~SplatRenderer();
  SplatRenderer(const SplatRenderer&) = delete;
  SplatRenderer& operator=(const SplatRenderer&) = delete;

  /// Draws the first `count` vectors of `set` (clamped to its size), placed by `model`
  /// (local to world), seen by `camera` in a viewport of aspect width / height, lit by
  /// `lights` (world directions; at most 8 are used). Depth-tested against what is in the
  /// framebuffer under `blend` = backToFront, without writing depth (the cpu path reads
  /// that depth back with glReadPixels; frontToBack reads none: a world without opaque
  /// shapes, render/src/scene_splats.hpp). The viewport must already be set. `style`
  /// (may be null) replaces set.style (a QNV node's mode and opacityScale). Throws
  /// std::runtime_error when a shader fails to compile.
  void draw(const SplatSet& set, std::size_t count, const glm::mat4& model,
            const scene::Camera& camera, float aspect, std::span<const SplatLight> lights,
            SplatBlend blend = SplatBlend::backToFront, const SplatStyle* style = nullptr);

  const SplatStatistics& statistics() const { return statistics_; }
  /// The path draw() tries (`automatic` at construction, setPath() changes it;
  /// SceneRendererOptions::splatPath for a SceneRenderer's splats).
  void setPath(SplatPath path) { path_ = path; }
  SplatPath path() const { return path_; }
  /// The ClipPlanes in scope of what the next draw() calls draw (X3D 4.0 clause 11.4.1;
  /// world coordinates, (a, b, c, d) keeping a x + b y + c z + d >= 0; at most 8 used;
  /// empty: none). A splat whose centre a plane removes is not drawn, as crop boxes of
  /// splat editors cut by centre. The gpu path, which sorts on the GPU, gives way to the
  /// geometry path while planes are set.
  /// The fog the splats of the next draw() calls go through (a shape's fragments' fog, by
  /// each splat's centre; SplatFog's default: none).
  void setFog(const SplatFog& fog) { fog_ = fog; }
  void setClipPlanes(std::span<const glm::vec4> planes) {
    clipPlanes_.assign(planes.begin(), planes.begin() + std::min<std::ptrdiff_t>(planes.size(), 8));
  }
  /// Frees every GL object (context current).
  void release();

 private:
  /// draw() for a set of Gaussians: a prefix or its tree's cut, front-to-back order, then
  /// the CPU rasterizer (src/gaussian_cpu.hpp) or the GL pass (src/gaussian_gl.hpp).
  void drawGaussians(const SplatSet& set, std::size_t count, const glm::mat4& model,
                     const scene::Camera& camera, float aspect, SplatBlend blend,
                     const SplatStyle& style);
  /// Puts the premultiplied RGBA8 image of the cpu path over the framebuffer's viewport.
  void drawImage(int width, int height);

  /// The front-to-back order `order` (places in `positions`, local centres placed by
  /// `model`) without the splats clipPlanes_ remove: `order` itself when none are set.
  template <typename Positions>
  const std::vector<std::uint32_t>& clippedOrder(const std::vector<std::uint32_t>& order,
                                                 const Positions& positions,
                                                 const glm::mat4& model);

  struct Gpu;
  std::unique_ptr<Gpu> gpu_;
  SplatStatistics statistics_;
  SplatPath path_;
  std::vector<glm::vec4> clipPlanes_;
  SplatFog fog_;
  std::vector<std::uint32_t> clipped_;  // clippedOrder's result
};

}  // namespace gs::render
