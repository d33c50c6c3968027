#include "render/splat_renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "gaussian_cpu.hpp"
#include "gaussian_gl.hpp"
#include "gl_program.hpp"
#include "render/context.hpp"
#include "render/splat_sort.hpp"
#include "splat_layer_gl.hpp"

namespace gs::render {

namespace {

/// The scene's depth under `rect` of the current viewport (window depths, rows bottom to
/// top), as the GL paths' depth test sees it; empty when there is no depth buffer to read.
std::span<const float> readSceneDepth(std::vector<float>& depth, const GLint viewport[4],
                                      const detail::PixelRect& rect) {
  const std::size_t pixels =
      static_cast<std::size_t>(rect.width()) * static_cast<std::size_t>(rect.height());
  GLint drawFramebuffer = 0, readFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
  if (readFramebuffer != drawFramebuffer)
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
  depth.resize(pixels);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  readFramebufferPixels(viewport[0] + rect.x0, viewport[1] + rect.y0, rect.width(), rect.height(),
                        GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  std::span<const float> result;
  if (glGetError() == GL_NO_ERROR) result = depth;
  if (readFramebuffer != drawFramebuffer)
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer));
  return result;
}

/// What the cpu path reads of the scene's depth: under back-to-front blending (splats in a
/// scene) the depth buffer under the pixels the splats reach; front to back, none.
detail::SceneDepthReader sceneDepthReader(SplatBlend blend, std::vector<float>& depth,
                                          const GLint viewport[4]) {
  if (blend != SplatBlend::backToFront) return {};
  return [&depth, viewport](const detail::PixelRect& rect) {
    return readSceneDepth(depth, viewport, rect);
  };
}

/// The path drawn with clip planes set: the gpu path sorts on the GPU, where the clipped
/// order is not; the geometry path draws the same splats from the CPU's order.
SplatPath clipResolved(SplatPath path, const std::vector<glm::vec4>& planes) {
  return path == SplatPath::gpu && !planes.empty() ? SplatPath::geometry : path;
}

glm::vec3 centreOf(const glm::vec3& p) {
  return p;
}

glm::vec3 centreOf(const qnv::DecodedVector& v) {
  return v.position;
}

/// The cpu path's view of a viewport of width x height pixels: the clip range that
/// projectionMatrix really uses, and `fog`.
detail::CpuGaussianView cpuView(const glm::mat4& modelView, const glm::mat4& projection,
                                const scene::Camera& camera, int width, int height,
                                const SplatFog& fog) {
  detail::CpuGaussianView v;
  v.fog = fog;
  v.modelView = modelView;
  v.projection = projection;
  v.width = width;
  v.height = height;
  v.nearClip = std::max(camera.nearClip, 1e-6f);
  v.farClip = std::max(camera.farClip, v.nearClip * 1.001f);
  return v;
}

}  // namespace

const char* splatPathName(SplatPath path) {
  switch (path) {
    case SplatPath::points:
      return "points";
    case SplatPath::geometry:
      return "geometry";
    case SplatPath::gpu:
      return "gpu";
    case SplatPath::cpu:
      return "cpu";
    case SplatPath::automatic:
      break;
  }
  return "auto";
}

bool parseSplatPath(const char* text, SplatPath& path) {
  const std::string_view t = text != nullptr ? text : "";
  if (t == "points")
    path = SplatPath::points;
  else if (t == "geometry")
    path = SplatPath::geometry;
  else if (t == "gpu")
    path = SplatPath::gpu;
  else if (t == "cpu")
    path = SplatPath::cpu;
  else if (t == "auto")
    path = SplatPath::automatic;
  else
    return false;
  return true;
}

SplatPath automaticSplatPath(const char* glRenderer) {
  const std::string_view r = glRenderer != nullptr ? glRenderer : "";
  return r.find("llvmpipe") != std::string_view::npos ||
                 r.find("softpipe") != std::string_view::npos
             ? SplatPath::cpu
             : SplatPath::gpu;
}

SplatViewRequests::Request::~Request() {
  if (auto registry = registry_.lock()) registry->views_.erase(id_);
}

void SplatViewRequests::Request::update(const SplatView& view) {
  if (auto registry = registry_.lock()) registry->views_[id_] = view;
}

std::unique_ptr<SplatViewRequests::Request> SplatViewRequests::request() {
  return std::unique_ptr<Request>(new Request(weak_from_this(), next_++));
}

void SplatSet::computeBounds() {
  bounds = vrml::Bounds{};
  for (const qnv::DecodedVector& v : vectors) bounds.extend(v.position);
  if (gaussians)
    for (const glm::vec3& p : gaussians->positions) bounds.extend(p);
}

struct SplatRenderer::Gpu {
  GLuint layerProgram = 0;
  // The last depth order: of which set, count and view.
  struct SortKey {
    const void* data = nullptr;  // the set's vectors or its Gaussian cloud
    std::size_t size = 0;
    std::uint64_t revision = 0;
    std::size_t count = 0;
    glm::mat4 view{0.0f};
    bool operator==(const SortKey&) const = default;
  } sorted;
  DepthSorter sorter;
  std::vector<std::uint32_t> order;               // front to back
  SplatPath automaticPath = SplatPath::geometry;  // what `automatic` means here
  bool gpuSort = false;                           // whether GpuDepthSort runs here

  /// The path a setting draws with here: `automatic` resolved, `points` as `geometry`,
  /// `gpu` as `geometry` without compute shaders.
  SplatPath resolve(SplatPath setting) const {
    const SplatPath p = setting == SplatPath::automatic ? automaticPath : setting;
    if (p == SplatPath::points) return SplatPath::geometry;
    if (p == SplatPath::gpu && !gpuSort) return SplatPath::geometry;
    return p;
  }
  // The two ways of drawing the one splat model.
  detail::CpuGaussianRasterizer rasterizer;
  detail::GaussianGlPass gaussianPass;
  std::vector<std::uint32_t> backToFront;  // the GL path's order
  // The last cut of a level-of-detail tree: of which tree, view, budget and height.
  splats::GaussianCloud cutCloud;
  const void* cutSet = nullptr;
  glm::mat4 cutView{0.0f};
  std::size_t cutBudget = 0;
  int cutHeight = 0;
  SplatPath cutPath = SplatPath::automatic;  // the path the cut was made for
  std::size_t cutSourceSize = 0;             // ... the source's size and revision then
  std::uint64_t cutSourceRevision = 0;
  std::uint64_t cutRevision = 0;
  // The tree's every node as one cloud (LodTree::merged, then the source's splats), for
  // the paths that draw a cut by index: of which tree, cloud, revision and source size.
  // (The source may have grown past the splats the tree was built over: a progressive
  // stream's prefix tree. Its new splats are appended, nothing else is copied again.)
  splats::GaussianCloud treeCloud;
  const void* treeOf = nullptr;
  const void* treeCloudOf = nullptr;
  std::uint64_t treeSourceRevision = 0;
  std::size_t treeSourceSize = 0;
  std::uint64_t treeRevision = 0;
  std::vector<std::uint32_t> cutIndices;  // into treeCloud (ascending for the cpu path)
  std::vector<glm::vec3> cutPositions;    // their centres, for the cpu path's depth sort

  /// Makes treeCloud for `set` (a SplatSet with a tree) unless it is made already; appends
  /// the source's new splats when only they changed.
  void holdTree(const SplatSet& set) {
    const splats::GaussianCloud& source = *set.gaussians;
    const bool same = treeOf == set.lodTree.get() && treeCloudOf == set.gaussians.get() &&
                      treeSourceRevision == set.revision;
    if (same && treeSourceSize == source.size()) return;
    if (same && treeSourceSize < source.size()) {
      treeCloud.appendRange(source, treeSourceSize, source.size());
    } else {
      const splats::GaussianCloud& merged = set.lodTree->merged;
      treeCloud = merged;
      treeCloud.reserve(merged.size() + source.size());
      treeCloud.appendRange(source, 0, source.size());
    }
    treeOf = set.lodTree.get();
    treeCloudOf = set.gaussians.get();
    treeSourceRevision = set.revision;
    treeSourceSize = source.size();
    ++treeRevision;
  }
  // The cpu path: its image, the scene's depth, the texture and an empty VAO.
  std::vector<std::uint8_t> pixels;
  std::vector<float> depth;
  GLuint cpuTexture = 0, emptyVao = 0;
  int cpuWidth = 0, cpuHeight = 0;

  void create() {
    automaticPath = automaticSplatPath(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    gpuSort = detail::GaussianGlPass::gpuSortAvailable();
    layerProgram = detail::buildLayerProgram();
  }

  void destroy() {
    glDeleteProgram(layerProgram);
    glDeleteTextures(1, &cpuTexture);
    glDeleteVertexArrays(1, &emptyVao);
    gaussianPass.release();
  }

  /// The front-to-back order of `positions` seen through `modelView`, sorted again only
  /// when the key changed; true when it sorted.
  template <typename Positions>
  bool sort(const SortKey& key, const Positions& positions, const glm::mat4& modelView) {
    if (sorted == key) return false;
    sorter.sortFrontToBack(positions, modelView, order);
    sorted = key;
    return true;
  }
};

template <typename Positions>
const std::vector<std::uint32_t>& SplatRenderer::clippedOrder(
    const std::vector<std::uint32_t>& order, const Positions& positions, const glm::mat4& model) {
  if (clipPlanes_.empty()) return order;
  // Each plane in local coordinates: (a, b, c, d) . (model p, 1) = (transpose(model) plane) . p.
  std::vector<glm::vec4> local(clipPlanes_.size());
  for (std::size_t k = 0; k < clipPlanes_.size(); ++k)
    local[k] = glm::transpose(model) * clipPlanes_[k];
  clipped_.clear();
  for (const std::uint32_t place : order) {
    const glm::vec4 p(centreOf(positions[place]), 1.0f);
    bool kept = true;
    for (const glm::vec4& plane : local) kept = kept && glm::dot(plane, p) >= 0.0f;
    if (kept) clipped_.push_back(place);
  }
  return clipped_;
}

SplatRenderer::SplatRenderer() : path_(SplatPath::automatic) {}

SplatRenderer::~SplatRenderer() {
  release();
}

void SplatRenderer::release() {
  if (gpu_) gpu_->destroy();
  gpu_.reset();
}

void SplatRenderer::draw(const SplatSet& set, std::size_t count, const glm::mat4& model,
                         const scene::Camera& camera, float aspect,
                         std::span<const SplatLight> lights, SplatBlend blend,
                         const SplatStyle* style) {
  statistics_ = {};
  count = std::min(count, set.size());
  if (count == 0) return;
  if (!gpu_) {
    gpu_ = std::make_unique<Gpu>();
    gpu_->create();
  }
  if (set.gaussians) {
    drawGaussians(set, count, model, camera, aspect, blend, style != nullptr ? *style : set.style);
    return;
  }
  Gpu& g = *gpu_;
  g.gaussianPass.setFog(fog_);
  const SplatStyle& s = style != nullptr ? *style : set.style;
  const glm::mat4 modelView = scene::viewMatrix(camera) * model;
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = viewport[2], height = viewport[3];
  if (width <= 0 || height <= 0) return;
  statistics_.splats = count;
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
  const float nearClip = std::max(camera.nearClip, 1e-6f);
  const SplatPath path = clipResolved(g.resolve(path_), clipPlanes_);
  statistics_.path = path;
  if (path == SplatPath::gpu) {
    // The GL path, its order sorted on the GPU.
    g.gaussianPass.drawVectors({set.vectors.data(), set.vectors.size()}, set.revision, {}, count, s,
                               lights, normalMatrix, modelView, projection, viewport, nearClip);
    return;
  }
  // The depth order of the first `count` vectors, front to back, redone only when the set
  // or the view changed.
  const auto t0 = std::chrono::steady_clock::now();
  const Gpu::SortKey key{set.vectors.data(), set.vectors.size(), set.revision, count, modelView};
  if (g.sort(key, std::span<const qnv::DecodedVector>(set.vectors.data(), count), modelView)) {
    statistics_.sortSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    statistics_.sorted = true;
  }
  const std::vector<std::uint32_t>& order =
      clippedOrder(g.order, std::span<const qnv::DecodedVector>(set.vectors.data(), count), model);
  if (path != SplatPath::cpu) {
    // The GL path, back to front.
    g.backToFront.assign(order.rbegin(), order.rend());
    g.gaussianPass.drawVectors({set.vectors.data(), set.vectors.size()}, set.revision,
                               g.backToFront, count, s, lights, normalMatrix, modelView, projection,
                               viewport, nearClip);
    return;
  }
  // The scene's depth, as the GL path's depth test sees it (front to back: none).
  g.rasterizer.drawVectors({set.vectors.data(), count}, order, s, lights, normalMatrix,
                           cpuView(modelView, projection, camera, width, height, fog_),
                           sceneDepthReader(blend, g.depth, viewport), g.pixels);
  drawImage(width, height);
}

void SplatRenderer::drawGaussians(const SplatSet& set, std::size_t count, const glm::mat4& model,
                                  const scene::Camera& camera, float aspect, SplatBlend blend,
                                  const SplatStyle& style) {
  Gpu& g = *gpu_;
  g.gaussianPass.setFog(fog_);
  const glm::mat4 modelView = scene::viewMatrix(camera) * model;
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = viewport[2], height = viewport[3];
  if (width <= 0 || height <= 0) return;
  const glm::vec3 eye(glm::inverse(modelView) * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // What this view draws: a prefix of the cloud, or the cut of its level-of-detail tree
  // (nodes below one pixel merged) under the same budget, chosen again when the view moves.
  // The gpu and cpu paths draw the cut by index from one cloud of the tree's every node,
  // made once (nothing copied or sent again as the view moves but the cut's indices); the
  // geometry path draws the cut assembled into a cloud of its own.
  const splats::GaussianCloud* drawn = set.gaussians.get();
  std::uint64_t revision = set.revision;
  std::span<const std::uint32_t> subset;  // a cut by index: its splats in the tree cloud
  std::span<const glm::vec3> positions;   // the centres the depth sort orders
  const void* sortData = nullptr;         // the sort's key: what and which revision
  std::uint64_t sortRevision = 0;
  const SplatPath path = clipResolved(g.resolve(path_), clipPlanes_);
  statistics_.path = path;
  // (A tree over more splats than the cloud holds is not this cloud's: never drawn.)
  if (set.lodTree && set.lodTree->splatCount <= set.gaussians->size()) {
    const bool byIndex = path != SplatPath::geometry;
    const splats::GaussianCloud& source = *set.gaussians;
    if (g.cutSet != set.lodTree.get() || g.cutView != projection * modelView ||
        g.cutBudget != count || g.cutHeight != height || g.cutPath != path ||
        g.cutSourceSize != source.size() || g.cutSourceRevision != set.revision) {
      const splats::CutView view = splats::cutViewFromViewProjection(
          projection * modelView, eye, 0.5f * static_cast<float>(height) * projection[1][1]);
      const splats::LodCut cut = splats::selectCut(*set.lodTree, view, count);
      // A prefix tree (a stream still arriving): the splats after its prefix are drawn
      // whole with the cut, until a tree over them is attached; as a prefix is, only
      // those the view's budget reaches (index below `count`).
      const std::size_t covered = std::min(set.lodTree->splatCount, source.size());
      const std::size_t tailEnd = std::max(covered, std::min(source.size(), count));
      if (byIndex) {
        g.holdTree(set);
        g.cutIndices.assign(cut.merged.begin(), cut.merged.end());
        const auto first = static_cast<std::uint32_t>(set.lodTree->merged.size());
        for (const std::uint32_t i : cut.originals) g.cutIndices.push_back(first + i);
        for (std::size_t i = covered; i < tailEnd; ++i)
          g.cutIndices.push_back(first + static_cast<std::uint32_t>(i));
        if (path == SplatPath::cpu) {
          // Ascending, so that the set-up reads the cloud in sequence; the centres for the
          // depth sort. (The GPU sorts the indices as they come.)
          std::sort(g.cutIndices.begin(), g.cutIndices.end());
          g.cutPositions.resize(g.cutIndices.size());
          for (std::size_t k = 0; k < g.cutIndices.size(); ++k)
            g.cutPositions[k] = g.treeCloud.positions[g.cutIndices[k]];
        }
      } else {
        splats::assembleCut(*set.lodTree, source, cut, g.cutCloud);
        g.cutCloud.appendRange(source, covered, tailEnd);
      }
      g.cutSet = set.lodTree.get();
      g.cutSourceSize = source.size();
      g.cutSourceRevision = set.revision;
      g.cutView = projection * modelView;
      g.cutBudget = count;
      g.cutHeight = height;
      g.cutPath = path;
      ++g.cutRevision;
    }
    if (byIndex) {
      // The cut by index: the tree cloud, its cut's indices, their centres for the sort.
      drawn = &g.treeCloud;
      revision = g.treeRevision;
      subset = g.cutIndices;
      positions = g.cutPositions;
      sortData = g.cutPositions.data();
      sortRevision = g.cutRevision;
      count = g.cutIndices.size();
    } else {
      drawn = &g.cutCloud;
      revision = g.cutRevision;
      count = g.cutCloud.size();
    }
  }
  const splats::GaussianCloud& cloud = *drawn;
  if (subset.empty()) {
    positions = std::span<const glm::vec3>(cloud.positions.data(), count);
    sortData = &cloud;
    sortRevision = revision;
  }
  statistics_.splats = count;
  if (path == SplatPath::gpu) {
    g.gaussianPass.drawGpuSorted(cloud, count, modelView, projection, eye, viewport,
                                 std::max(camera.nearClip, 1e-6f), style.opacityScale, revision,
                                 subset, g.cutRevision);
    return;
  }
  // (With a subset, the order holds places in it: the cpu path reads it so.)
  const auto t0 = std::chrono::steady_clock::now();
  const Gpu::SortKey key{sortData, subset.empty() ? cloud.size() : subset.size(), sortRevision,
                         count, modelView};
  if (g.sort(key, positions, modelView)) {
    statistics_.sortSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    statistics_.sorted = true;
  }
  const std::vector<std::uint32_t>& order = clippedOrder(g.order, positions, model);
  if (path != SplatPath::cpu) {
    // The GL path, back to front.
    g.backToFront.assign(order.rbegin(), order.rend());
    g.gaussianPass.draw(cloud, g.backToFront, modelView, projection, eye, viewport,
                        std::max(camera.nearClip, 1e-6f), style.opacityScale, revision);
    return;
  }
  detail::CpuGaussianView v = cpuView(modelView, projection, camera, width, height, fog_);
  v.eye = eye;
  v.opacityScale = style.opacityScale;
  g.rasterizer.draw(cloud, order, v, sceneDepthReader(blend, g.depth, viewport), g.pixels, revision,
                    subset);
  drawImage(width, height);
}

void SplatRenderer::drawImage(int width, int height) {
  Gpu& g = *gpu_;
  // The premultiplied image over the framebuffer: one quad, texel per pixel.
  glActiveTexture(GL_TEXTURE0);
  if (g.cpuTexture == 0) {
    glGenTextures(1, &g.cpuTexture);
    glGenVertexArrays(1, &g.emptyVao);
  }
  // Only the tiles some splat reached (a far cut covers few): the rest of the image is
  // transparent black, which composites to nothing.
  const detail::CpuGaussianRasterizer::PixelRect r = g.rasterizer.touched();
  if (r.empty()) return;
  glBindTexture(GL_TEXTURE_2D, g.cpuTexture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (width != g.cpuWidth || height != g.cpuHeight) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 g.pixels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    g.cpuWidth = width;
    g.cpuHeight = height;
  } else {
    glPixelStorei(GL_UNPACK_ROW_LENGTH, width);
    glTexSubImage2D(GL_TEXTURE_2D, 0, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0, GL_RGBA,
                    GL_UNSIGNED_BYTE,
                    g.pixels.data() + (static_cast<std::size_t>(r.y0) * width + r.x0) * 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  }
  // The quad drawn within that rectangle (inside any scissor box already set).
  GLint viewport[4], box[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const GLboolean scissored = glIsEnabled(GL_SCISSOR_TEST);
  glGetIntegerv(GL_SCISSOR_BOX, box);
  GLint x0 = viewport[0] + r.x0, y0 = viewport[1] + r.y0;
  GLint x1 = viewport[0] + r.x1, y1 = viewport[1] + r.y1;
  if (scissored) {
    x0 = std::max(x0, box[0]);
    y0 = std::max(y0, box[1]);
    x1 = std::min(x1, box[0] + box[2]);
    y1 = std::min(y1, box[1] + box[3]);
  }
  if (x0 >= x1 || y0 >= y1) return;
  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, y0, x1 - x0, y1 - y0);
  glUseProgram(g.layerProgram);
  glUniform1i(detail::uniform(g.layerProgram, "u_layer"), 0);
  glUniform2i(detail::uniform(g.layerProgram, "u_origin"), viewport[0], viewport[1]);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(g.emptyVao);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glScissor(box[0], box[1], box[2], box[3]);
  if (!scissored) glDisable(GL_SCISSOR_TEST);
}

}  // namespace gs::render
