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
#include "render/splat_sort.hpp"
#include "splat_cpu.hpp"
#include "splat_glsl.hpp"
#include "splat_points.hpp"

namespace gs::render {

namespace {

// The geometry path's vertex shader after the shared model (splat_glsl.hpp).
const char* const kSplatVertexBody = R"glsl(
uniform mat4 u_model;
out vec3 g_center;  // model coordinates
out vec3 g_tangent;
out vec3 g_bitangent;
out float g_spread;
out float g_peak;
out vec3 g_color;

void main() {
  vec4 c = splatRgba();
  vec3 n = a_normal;
  float spread;
  float peak;
  splatProfile(a_positionMagnitude.w, c.a, spread, peak);
  g_peak = clamp(peak, 0.0, 1.0);
  g_spread = spread;
  vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  g_tangent = normalize(cross(helper, n));
  g_bitangent = cross(n, g_tangent);
  g_center = a_positionMagnitude.xyz;
  g_color = splatLit(n, c.rgb);
}
)glsl";

// Expands each point into the square patch of its splat.
const char* const kSplatGeometryShader = R"glsl(#version 330 core
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
uniform mat4 u_modelViewProjection;
in vec3 g_center[];
in vec3 g_tangent[];
in vec3 g_bitangent[];
in float g_spread[];
in float g_peak[];
in vec3 g_color[];
out vec2 v_local;  // patch coordinates in units of the Gaussian's spread
flat out vec3 v_color;
flat out float v_peak;

void main() {
  if (!(g_peak[0] > 0.0) || !(g_spread[0] > 0.0)) return;
  for (int i = 0; i < 4; ++i) {
    vec2 corner = vec2((i & 1) == 0 ? -3.0 : 3.0, (i & 2) == 0 ? -3.0 : 3.0);
    vec3 p = g_center[0] + (corner.x * g_tangent[0] + corner.y * g_bitangent[0]) * g_spread[0];
    gl_Position = u_modelViewProjection * vec4(p, 1.0);
    v_local = corner;
    v_color = g_color[0];
    v_peak = g_peak[0];
    EmitVertex();
  }
  EndPrimitive();
}
)glsl";

const char* const kSplatFragmentShader = R"glsl(#version 330 core
in vec2 v_local;
flat in vec3 v_color;
flat in float v_peak;
out vec4 o_color;
void main() {
  float r2 = dot(v_local, v_local);
  if (r2 > 9.0) discard;
  float alpha = v_peak * exp(-0.5 * r2);
  o_color = vec4(v_color * alpha, alpha);  // premultiplied
}
)glsl";

// Composites the front-to-back layer (premultiplied) over the framebuffer.
const char* const kLayerVertexShader = R"glsl(#version 330 core
out vec2 v_uv;
void main() {
  vec2 p = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
  v_uv = p * 0.5 + 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

const char* const kLayerFragmentShader = R"glsl(#version 330 core
in vec2 v_uv;
uniform sampler2D u_layer;
out vec4 o_color;
void main() { o_color = texture(u_layer, v_uv); }
)glsl";

constexpr int kMaxSplatLights = 8;

/// Uniform locations of one splat program (-1 for those it lacks).
struct SplatUniforms {
  GLint modelView, projection, modelViewProjection, normalMatrix, surface, sigma, opacityScale,
      voxelSize, magnitudeMax, ambient, lightCount, lightDirection, lightColor, viewportSize,
      viewport, rayScale, clipRange, depthMap;
  void locate(GLuint program) {
    const auto at = [program](const char* name) { return detail::uniform(program, name); };
    modelView = at("u_modelView");
    projection = at("u_projection");
    modelViewProjection = at("u_modelViewProjection");
    normalMatrix = at("u_normalMatrix");
    surface = at("u_surface");
    sigma = at("u_sigma");
    opacityScale = at("u_opacityScale");
    voxelSize = at("u_voxelSize");
    magnitudeMax = at("u_magnitudeMax");
    ambient = at("u_ambient");
    lightCount = at("u_lightCount");
    lightDirection = at("u_lightDirection");
    lightColor = at("u_lightColor");
    viewportSize = at("u_viewportSize");
    viewport = at("u_viewport");
    rayScale = at("u_rayScale");
    clipRange = at("u_clipRange");
    depthMap = at("u_depthMap");
  }
};

/// The scene's depth of the current viewport (window depths, rows bottom to top), as the
/// GL paths' depth test sees it; empty when there is no depth buffer to read.
std::span<const float> readSceneDepth(std::vector<float>& depth, const GLint viewport[4]) {
  const std::size_t pixels =
      static_cast<std::size_t>(viewport[2]) * static_cast<std::size_t>(viewport[3]);
  GLint drawFramebuffer = 0, readFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
  if (readFramebuffer != drawFramebuffer)
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
  depth.resize(pixels);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(viewport[0], viewport[1], viewport[2], viewport[3], GL_DEPTH_COMPONENT, GL_FLOAT,
               depth.data());
  std::span<const float> result;
  if (glGetError() == GL_NO_ERROR) result = depth;
  if (readFramebuffer != drawFramebuffer)
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer));
  return result;
}

}  // namespace

const char* splatPathName(SplatPath path) {
  switch (path) {
    case SplatPath::points:
      return "points";
    case SplatPath::geometry:
      return "geometry";
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
             : SplatPath::geometry;
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
  GLuint program = 0, pointsProgram = 0, layerProgram = 0;
  GLuint vao = 0, orderBuffer = 0, vectorBuffer = 0;
  GLuint layerFbo = 0, layerTexture = 0;
  int layerWidth = 0, layerHeight = 0;
  SplatUniforms u{}, pu{};  // of program, pointsProgram
  float maxPointSize = 1.0f;
  const qnv::DecodedVector* uploadedData = nullptr;
  std::size_t uploadedSize = 0;
  std::size_t bufferCapacity = 0;  // vectors the GL buffer holds
  std::uint64_t uploadedRevision = 0;
  std::size_t orderCapacity = 0;
  // The last depth order: of which set, count and view, which direction, whether it is in
  // orderBuffer.
  struct SortKey {
    const void* data = nullptr;  // the set's vectors or its Gaussian cloud
    std::size_t size = 0;
    std::uint64_t revision = 0;
    std::size_t count = 0;
    glm::mat4 view{0.0f};
    bool frontToBack = false;
    bool operator==(const SortKey&) const = default;
  } sorted;
  bool orderOnGpu = false;
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  // Whether the last view checked fits the points path (pointsFit), and that view.
  bool pointsFit = false;
  glm::mat4 fitView{0.0f}, fitProjection{0.0f};
  std::size_t fitCount = 0;
  int fitWidth = 0, fitHeight = 0;
  SplatStyle fitStyle;
  // The cpu path: its rasterizer, image, the scene's depth, the texture and an empty VAO.
  SplatPath automaticPath = SplatPath::geometry;  // what `automatic` means here
  detail::CpuSplatRasterizer rasterizer;
  detail::CpuGaussianRasterizer gaussianRasterizer;
  detail::GaussianGlPass gaussianPass;
  std::vector<std::uint32_t> backToFront;  // the GL path's order of Gaussians
  // The last cut of a level-of-detail tree: of which tree, view, budget and height.
  splats::GaussianCloud cutCloud;
  const void* cutSet = nullptr;
  glm::mat4 cutView{0.0f};
  std::size_t cutBudget = 0;
  int cutHeight = 0;
  std::uint64_t cutRevision = 0;
  std::vector<std::uint8_t> pixels;
  std::vector<float> depth;
  GLuint cpuTexture = 0, emptyVao = 0;
  int cpuWidth = 0, cpuHeight = 0;

  void create() {
    automaticPath = automaticSplatPath(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    program = detail::buildProgram("splat", detail::splatVertexShader(kSplatVertexBody).c_str(),
                                   kSplatFragmentShader, kSplatGeometryShader);
    pointsProgram = detail::buildProgram(
        "splat points", detail::splatVertexShader(detail::kSplatPointsVertexBody).c_str(),
        detail::kSplatPointsFragmentShader);
    layerProgram = detail::buildProgram("splat layer", kLayerVertexShader, kLayerFragmentShader);
    u.locate(program);
    pu.locate(pointsProgram);
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    maxPointSize = range[1];
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &orderBuffer);
    glGenBuffers(1, &vectorBuffer);
    // One point per vector (attributes straight from qnv::DecodedVector), drawn in depth
    // order through an index buffer; the geometry shader makes the patch.
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vectorBuffer);
    constexpr GLsizei kStride = sizeof(qnv::DecodedVector);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, kStride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kStride,
                          reinterpret_cast<const void*>(offsetof(qnv::DecodedVector, normal)));
    glEnableVertexAttribArray(2);
    glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, kStride,
                           reinterpret_cast<const void*>(offsetof(qnv::DecodedVector, rgba)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, orderBuffer);  // recorded in the VAO
    glBindVertexArray(0);
  }

  void destroy() {
    glDeleteProgram(program);
    glDeleteProgram(pointsProgram);
    glDeleteProgram(layerProgram);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &orderBuffer);
    glDeleteBuffers(1, &vectorBuffer);
    glDeleteFramebuffers(1, &layerFbo);
    glDeleteTextures(1, &layerTexture);
    glDeleteTextures(1, &cpuTexture);
    glDeleteVertexArrays(1, &emptyVao);
    gaussianPass.release();
  }

  void upload(const SplatSet& set) {
    const qnv::DecodedVector* data = set.vectors.data();
    const std::size_t size = set.vectors.size();
    if (uploadedData == data && uploadedSize == size && uploadedRevision == set.revision) return;
    constexpr std::size_t kBytes = sizeof(qnv::DecodedVector);
    glBindBuffer(GL_ARRAY_BUFFER, vectorBuffer);
    if (uploadedData == data && size > uploadedSize && size <= bufferCapacity &&
        uploadedRevision == set.revision) {
      // A growing set (SplatSet): only the new tail goes to the GPU.
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(uploadedSize * kBytes),
                      static_cast<GLsizeiptr>((size - uploadedSize) * kBytes), data + uploadedSize);
    } else {
      bufferCapacity = std::max(size, set.vectors.capacity());
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bufferCapacity * kBytes), nullptr,
                   GL_STATIC_DRAW);
      glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(size * kBytes), data);
    }
    uploadedData = data;
    uploadedSize = size;
    uploadedRevision = set.revision;
  }

  void ensureLayer(int width, int height) {
    if (layerFbo != 0 && width == layerWidth && height == layerHeight) return;
    if (layerFbo == 0) {
      glGenFramebuffers(1, &layerFbo);
      glGenTextures(1, &layerTexture);
    }
    glBindTexture(GL_TEXTURE_2D, layerTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, layerFbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, layerTexture, 0);
    layerWidth = width;
    layerHeight = height;
  }
};

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
  Gpu& g = *gpu_;
  if (set.gaussians) {
    drawGaussians(set, count, model, camera, aspect, blend, style != nullptr ? *style : set.style);
    return;
  }
  const SplatPath path = path_ == SplatPath::automatic ? g.automaticPath : path_;
  const bool cpu = path == SplatPath::cpu;
  if (!cpu) g.upload(set);

  // Depth order of the first `count` vectors, redone only when the set or the view
  // changed. The cpu path always composites front to back.
  const glm::mat4 view = scene::viewMatrix(camera);
  const glm::mat4 modelView = view * model;
  const bool frontToBack = cpu || blend == SplatBlend::frontToBack;
  const Gpu::SortKey key{set.vectors.data(), set.vectors.size(), set.revision, count,
                         modelView,          frontToBack};
  if (g.sorted != key) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::span<const qnv::DecodedVector> first(set.vectors.data(), count);
    if (frontToBack)
      g.sorter.sortFrontToBack(first, modelView, g.order);
    else
      g.sorter.sortBackToFront(first, modelView, g.order);
    statistics_.sortSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    statistics_.sorted = true;
    g.sorted = key;
    g.orderOnGpu = false;
  }
  if (!cpu && !g.orderOnGpu) {
    glBindVertexArray(g.vao);
    const auto bytes = static_cast<GLsizeiptr>(count * sizeof(std::uint32_t));
    if (g.orderCapacity < count) {
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytes, g.order.data(), GL_STREAM_DRAW);
      g.orderCapacity = count;
    } else {
      glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, bytes, g.order.data());
    }
    glBindVertexArray(0);
    g.orderOnGpu = true;
  }

  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLint previousFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFramebuffer);

  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  const SplatStyle& s = style != nullptr ? *style : set.style;
  if (cpu) {
    drawCpu(set, count, model, modelView, camera, projection, lights, blend, s);
    return;
  }
  // The points path when this view allows it (checked again only when the view changed).
  bool points = false;
  if (path == SplatPath::points) {
    if (g.fitCount != count || g.fitView != modelView || g.fitProjection != projection ||
        g.fitWidth != viewport[2] || g.fitHeight != viewport[3] ||
        std::memcmp(&g.fitStyle, &s, sizeof s) != 0) {
      detail::PointView pv;
      pv.modelView = modelView;
      pv.scaleX = projection[0][0];
      pv.scaleY = projection[1][1];
      pv.width = viewport[2];
      pv.height = viewport[3];
      pv.nearClip = std::max(camera.nearClip, 1e-6f);
      pv.maxPointSize = g.maxPointSize;
      g.pointsFit = detail::pointsFit({set.vectors.data(), count}, s, pv);
      g.fitCount = count;
      g.fitView = modelView;
      g.fitProjection = projection;
      g.fitWidth = viewport[2];
      g.fitHeight = viewport[3];
      g.fitStyle = s;
    }
    points = g.pointsFit;
  }
  statistics_.path = points ? SplatPath::points : SplatPath::geometry;
  const SplatUniforms& u = points ? g.pu : g.u;
  glUseProgram(points ? g.pointsProgram : g.program);
  if (points) {
    glUniformMatrix4fv(u.modelView, 1, GL_FALSE, &modelView[0][0]);
    glUniformMatrix4fv(u.projection, 1, GL_FALSE, &projection[0][0]);
    glUniform2f(u.viewportSize, static_cast<float>(viewport[2]), static_cast<float>(viewport[3]));
    // Where the pass draws: the layer (from its origin) or the framebuffer's viewport.
    const bool layer = blend == SplatBlend::frontToBack;
    glUniform4f(u.viewport, layer ? 0.0f : static_cast<float>(viewport[0]),
                layer ? 0.0f : static_cast<float>(viewport[1]), static_cast<float>(viewport[2]),
                static_cast<float>(viewport[3]));
    glUniform2f(u.rayScale, 1.0f / projection[0][0], 1.0f / projection[1][1]);
    const float nearClip = std::max(camera.nearClip, 1e-6f);
    glUniform2f(u.clipRange, nearClip, std::max(camera.farClip, nearClip * 1.001f));
    glUniform2f(u.depthMap, projection[2][2], projection[3][2]);
    glEnable(GL_PROGRAM_POINT_SIZE);
  } else {
    const glm::mat4 modelViewProjection = projection * modelView;
    glUniformMatrix4fv(u.modelViewProjection, 1, GL_FALSE, &modelViewProjection[0][0]);
  }
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
  glUniformMatrix3fv(u.normalMatrix, 1, GL_FALSE, &normalMatrix[0][0]);
  glUniform1i(u.surface, s.kind == qnv::StreamKind::surface ? 1 : 0);
  glUniform1f(u.sigma, s.sigma);
  glUniform1f(u.opacityScale, s.opacityScale);
  glUniform1f(u.voxelSize, s.voxelSize);
  glUniform1f(u.magnitudeMax, s.magnitudeMax);
  glUniform1f(u.ambient, s.ambient);
  const int lightCount = static_cast<int>(std::min<std::size_t>(lights.size(), kMaxSplatLights));
  glm::vec3 directions[kMaxSplatLights], colors[kMaxSplatLights];
  for (int i = 0; i < lightCount; ++i) {
    directions[i] = lights[static_cast<std::size_t>(i)].direction;
    colors[i] = lights[static_cast<std::size_t>(i)].color;
  }
  glUniform1i(u.lightCount, lightCount);
  if (lightCount > 0) {
    glUniform3fv(u.lightDirection, lightCount, &directions[0][0]);
    glUniform3fv(u.lightColor, lightCount, &colors[0][0]);
  }

  glEnable(GL_BLEND);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  if (blend == SplatBlend::frontToBack) {
    // Accumulate under a cleared layer, then put the layer over the framebuffer. The layer
    // has no depth buffer: in this mode splats are not hidden by polygons.
    g.ensureLayer(viewport[2], viewport[3]);
    glBindFramebuffer(GL_FRAMEBUFFER, g.layerFbo);
    glViewport(0, 0, viewport[2], viewport[3]);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glBlendFunc(GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  } else {
    glEnable(GL_DEPTH_TEST);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  glBindVertexArray(g.vao);
  glDrawElements(GL_POINTS, static_cast<GLsizei>(count), GL_UNSIGNED_INT, nullptr);
  if (points) glDisable(GL_PROGRAM_POINT_SIZE);
  if (blend == SplatBlend::frontToBack) {
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previousFramebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glUseProgram(g.layerProgram);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, g.layerTexture);
    glUniform1i(detail::uniform(g.layerProgram, "u_layer"), 0);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  }
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  statistics_.splats = count;
}

void SplatRenderer::drawCpu(const SplatSet& set, std::size_t count, const glm::mat4& model,
                            const glm::mat4& modelView, const scene::Camera& camera,
                            const glm::mat4& projection, std::span<const SplatLight> lights,
                            SplatBlend blend, const SplatStyle& style) {
  Gpu& g = *gpu_;
  statistics_.path = SplatPath::cpu;
  statistics_.splats = count;
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = viewport[2], height = viewport[3];
  if (width <= 0 || height <= 0) return;

  // The scene's depth, as the GL paths' depth test sees it (the front-to-back GL layer
  // has no depth test: neither has this path in that mode).
  std::span<const float> depth;
  if (blend == SplatBlend::backToFront) depth = readSceneDepth(g.depth, viewport);

  detail::CpuSplatView v;
  v.modelView = modelView;
  v.projection = projection;
  v.normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
  v.width = width;
  v.height = height;
  v.nearClip = std::max(camera.nearClip, 1e-6f);
  v.farClip = std::max(camera.farClip, v.nearClip * 1.001f);
  g.rasterizer.draw({set.vectors.data(), count}, g.order, style, lights, v, depth, g.pixels);
  drawImage(width, height);
}

void SplatRenderer::drawGaussians(const SplatSet& set, std::size_t count, const glm::mat4& model,
                                  const scene::Camera& camera, float aspect, SplatBlend blend,
                                  const SplatStyle& style) {
  Gpu& g = *gpu_;
  const glm::mat4 modelView = scene::viewMatrix(camera) * model;
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = viewport[2], height = viewport[3];
  if (width <= 0 || height <= 0) return;
  const glm::vec3 eye(glm::inverse(modelView) * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // What this view draws: a prefix of the cloud, or the cut of its level-of-detail tree
  // (nodes below one pixel merged) under the same budget, chosen again when the view moves.
  const splats::GaussianCloud* drawn = set.gaussians.get();
  std::uint64_t revision = set.revision;
  if (set.lodTree) {
    if (g.cutSet != set.lodTree.get() || g.cutView != projection * modelView ||
        g.cutBudget != count || g.cutHeight != height) {
      const splats::CutView view = splats::cutViewFromViewProjection(
          projection * modelView, eye, 0.5f * static_cast<float>(height) * projection[1][1]);
      const splats::LodCut cut = splats::selectCut(*set.lodTree, view, count);
      splats::assembleCut(*set.lodTree, *set.gaussians, cut, g.cutCloud);
      g.cutSet = set.lodTree.get();
      g.cutView = projection * modelView;
      g.cutBudget = count;
      g.cutHeight = height;
      ++g.cutRevision;
    }
    drawn = &g.cutCloud;
    revision = g.cutRevision;
    count = g.cutCloud.size();
  }
  const splats::GaussianCloud& cloud = *drawn;
  const Gpu::SortKey key{&cloud, cloud.size(), revision, count, modelView, true};
  if (g.sorted != key) {
    const auto t0 = std::chrono::steady_clock::now();
    g.sorter.sortFrontToBack(std::span<const glm::vec3>(cloud.positions.data(), count), modelView,
                             g.order);
    statistics_.sortSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    statistics_.sorted = true;
    g.sorted = key;
    g.orderOnGpu = false;
  }
  statistics_.splats = count;
  const SplatPath path = path_ == SplatPath::automatic ? g.automaticPath : path_;
  if (path != SplatPath::cpu) {
    // The GL path (one program for `geometry` and `points`), back to front.
    statistics_.path = SplatPath::geometry;
    g.backToFront.assign(g.order.rbegin(), g.order.rend());
    g.gaussianPass.draw(cloud, g.backToFront, modelView, projection, eye, viewport,
                        std::max(camera.nearClip, 1e-6f), style.opacityScale, revision);
    return;
  }
  statistics_.path = SplatPath::cpu;
  std::span<const float> depth;
  if (blend == SplatBlend::backToFront) depth = readSceneDepth(g.depth, viewport);
  detail::CpuGaussianView v;
  v.modelView = modelView;
  v.projection = projection;
  v.eye = eye;
  v.width = width;
  v.height = height;
  v.nearClip = std::max(camera.nearClip, 1e-6f);
  v.farClip = std::max(camera.farClip, v.nearClip * 1.001f);
  v.opacityScale = style.opacityScale;
  g.gaussianRasterizer.draw(cloud, g.order, v, depth, g.pixels, revision);
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
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE,
                    g.pixels.data());
  }
  glUseProgram(g.layerProgram);
  glUniform1i(detail::uniform(g.layerProgram, "u_layer"), 0);
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
}

}  // namespace gs::render
