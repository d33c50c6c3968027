#include "render/splat_renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "gl_program.hpp"
#include "render/splat_sort.hpp"

namespace gs::render {

namespace {

// The splat model of splat_model.hpp in GLSL: keep the two in step.
const char* const kSplatVertexShader = R"glsl(#version 330 core
layout(location = 0) in uint a_index;
uniform samplerBuffer u_vectors;  // two RGBA32F texels per qnv::DecodedVector
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normalMatrix;
uniform int u_surface;
uniform float u_sigma;
uniform float u_opacityScale;
uniform float u_voxelSize;
uniform float u_magnitudeMax;
uniform float u_ambient;
uniform int u_lightCount;
uniform vec3 u_lightDirection[8];
uniform vec3 u_lightColor[8];
out vec2 v_local;  // patch coordinates in units of the Gaussian's spread
flat out vec3 v_color;
flat out float v_peak;

void main() {
  int i = int(a_index) * 2;
  vec4 a = texelFetch(u_vectors, i);
  vec4 b = texelFetch(u_vectors, i + 1);
  uint rgba = floatBitsToUint(b.w);
  vec4 c = vec4(float(rgba & 255u), float((rgba >> 8) & 255u), float((rgba >> 16) & 255u),
                float(rgba >> 24)) / 255.0;
  float magnitude = a.w;
  vec3 n = b.xyz;
  float spread;
  float peak;
  if (u_surface == 1) {
    float radius = sqrt(max(magnitude, 0.0) / 3.14159265);
    spread = 2.0 * u_sigma * radius;
    peak = spread > 0.0 ? u_opacityScale * magnitude / (2.0 * 3.14159265 * spread * spread) : 0.0;
    peak *= c.a;
  } else {
    spread = 2.0 * u_sigma * u_voxelSize;
    peak = u_opacityScale * c.a * sqrt(clamp(magnitude / u_magnitudeMax, 0.0, 1.0));
  }
  peak = clamp(peak, 0.0, 1.0);
  vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = normalize(cross(helper, n));
  vec3 bt = cross(n, t);
  vec2 corner = vec2((gl_VertexID & 1) == 0 ? -3.0 : 3.0, (gl_VertexID & 2) == 0 ? -3.0 : 3.0);
  v_local = corner;
  vec3 p = a.xyz + (corner.x * t + corner.y * bt) * spread;
  gl_Position = u_projection * u_view * u_model * vec4(p, 1.0);
  vec3 wn = normalize(u_normalMatrix * n);
  vec3 light = vec3(u_ambient);
  for (int k = 0; k < u_lightCount; ++k)
    light += abs(dot(wn, u_lightDirection[k])) * u_lightColor[k];
  v_color = min(c.rgb * light, vec3(1.0));
  v_peak = peak;
  if (!(peak > 0.0) || !(spread > 0.0)) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled
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

}  // namespace

void SplatSet::computeBounds() {
  bounds = vrml::Bounds{};
  for (const qnv::DecodedVector& v : vectors) bounds.extend(v.position);
}

struct SplatRenderer::Gpu {
  GLuint program = 0, layerProgram = 0;
  GLuint vao = 0, orderBuffer = 0, vectorBuffer = 0, vectorTexture = 0;
  GLuint layerFbo = 0, layerTexture = 0;
  int layerWidth = 0, layerHeight = 0;
  struct {
    GLint vectors, model, view, projection, normalMatrix, surface, sigma, opacityScale, voxelSize,
        magnitudeMax, ambient, lightCount, lightDirection, lightColor;
  } u{};
  const qnv::DecodedVector* uploadedData = nullptr;
  std::size_t uploadedSize = 0;
  std::size_t orderCapacity = 0;
  glm::mat4 sortedView{0.0f};
  std::size_t sortedCount = 0;
  SplatBlend sortedBlend = SplatBlend::backToFront;
  DepthSorter sorter;
  std::vector<std::uint32_t> order;

  void create() {
    program = detail::buildProgram("splat", kSplatVertexShader, kSplatFragmentShader);
    layerProgram = detail::buildProgram("splat layer", kLayerVertexShader, kLayerFragmentShader);
    u.vectors = detail::uniform(program, "u_vectors");
    u.model = detail::uniform(program, "u_model");
    u.view = detail::uniform(program, "u_view");
    u.projection = detail::uniform(program, "u_projection");
    u.normalMatrix = detail::uniform(program, "u_normalMatrix");
    u.surface = detail::uniform(program, "u_surface");
    u.sigma = detail::uniform(program, "u_sigma");
    u.opacityScale = detail::uniform(program, "u_opacityScale");
    u.voxelSize = detail::uniform(program, "u_voxelSize");
    u.magnitudeMax = detail::uniform(program, "u_magnitudeMax");
    u.ambient = detail::uniform(program, "u_ambient");
    u.lightCount = detail::uniform(program, "u_lightCount");
    u.lightDirection = detail::uniform(program, "u_lightDirection");
    u.lightColor = detail::uniform(program, "u_lightColor");
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &orderBuffer);
    glGenBuffers(1, &vectorBuffer);
    glGenTextures(1, &vectorTexture);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, orderBuffer);
    glEnableVertexAttribArray(0);
    glVertexAttribIPointer(0, 1, GL_UNSIGNED_INT, 0, nullptr);
    glVertexAttribDivisor(0, 1);
    glBindVertexArray(0);
  }

  void destroy() {
    glDeleteProgram(program);
    glDeleteProgram(layerProgram);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &orderBuffer);
    glDeleteBuffers(1, &vectorBuffer);
    glDeleteTextures(1, &vectorTexture);
    glDeleteFramebuffers(1, &layerFbo);
    glDeleteTextures(1, &layerTexture);
  }

  void upload(const SplatSet& set) {
    if (uploadedData == set.vectors.data() && uploadedSize == set.vectors.size()) return;
    glBindBuffer(GL_TEXTURE_BUFFER, vectorBuffer);
    glBufferData(GL_TEXTURE_BUFFER,
                 static_cast<GLsizeiptr>(set.vectors.size() * sizeof(qnv::DecodedVector)),
                 set.vectors.data(), GL_STATIC_DRAW);
    glBindTexture(GL_TEXTURE_BUFFER, vectorTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, vectorBuffer);
    uploadedData = set.vectors.data();
    uploadedSize = set.vectors.size();
    sortedCount = 0;  // force a sort
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

SplatRenderer::SplatRenderer() = default;

SplatRenderer::~SplatRenderer() {
  release();
}

void SplatRenderer::release() {
  if (gpu_) gpu_->destroy();
  gpu_.reset();
}

void SplatRenderer::draw(const SplatSet& set, std::size_t count, const glm::mat4& model,
                         const Camera& camera, float aspect, std::span<const SplatLight> lights,
                         SplatBlend blend) {
  statistics_ = {};
  count = std::min(count, set.vectors.size());
  if (count == 0) return;
  if (!gpu_) {
    gpu_ = std::make_unique<Gpu>();
    gpu_->create();
  }
  Gpu& g = *gpu_;
  g.upload(set);

  // Depth order of the first `count` vectors, redone only when the view moved.
  const glm::mat4 view = viewMatrix(camera);
  const glm::mat4 modelView = view * model;
  if (g.sortedCount != count || g.sortedView != modelView || g.sortedBlend != blend) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::span<const qnv::DecodedVector> first(set.vectors.data(), count);
    if (blend == SplatBlend::backToFront)
      g.sorter.sortBackToFront(first, modelView, g.order);
    else
      g.sorter.sortFrontToBack(first, modelView, g.order);
    statistics_.sortSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    statistics_.sorted = true;
    glBindBuffer(GL_ARRAY_BUFFER, g.orderBuffer);
    const auto bytes = static_cast<GLsizeiptr>(count * sizeof(std::uint32_t));
    if (g.orderCapacity < count) {
      glBufferData(GL_ARRAY_BUFFER, bytes, g.order.data(), GL_STREAM_DRAW);
      g.orderCapacity = count;
    } else {
      glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, g.order.data());
    }
    g.sortedCount = count;
    g.sortedView = modelView;
    g.sortedBlend = blend;
  }

  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLint previousFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFramebuffer);

  glUseProgram(g.program);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, g.vectorTexture);
  glUniform1i(g.u.vectors, 0);
  glUniformMatrix4fv(g.u.model, 1, GL_FALSE, &model[0][0]);
  glUniformMatrix4fv(g.u.view, 1, GL_FALSE, &view[0][0]);
  const glm::mat4 projection = projectionMatrix(camera, aspect);
  glUniformMatrix4fv(g.u.projection, 1, GL_FALSE, &projection[0][0]);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
  glUniformMatrix3fv(g.u.normalMatrix, 1, GL_FALSE, &normalMatrix[0][0]);
  const SplatStyle& s = set.style;
  glUniform1i(g.u.surface, s.kind == qnv::StreamKind::surface ? 1 : 0);
  glUniform1f(g.u.sigma, s.sigma);
  glUniform1f(g.u.opacityScale, s.opacityScale);
  glUniform1f(g.u.voxelSize, s.voxelSize);
  glUniform1f(g.u.magnitudeMax, s.magnitudeMax);
  glUniform1f(g.u.ambient, s.ambient);
  const int lightCount = static_cast<int>(std::min<std::size_t>(lights.size(), kMaxSplatLights));
  glm::vec3 directions[kMaxSplatLights], colors[kMaxSplatLights];
  for (int i = 0; i < lightCount; ++i) {
    directions[i] = lights[static_cast<std::size_t>(i)].direction;
    colors[i] = lights[static_cast<std::size_t>(i)].color;
  }
  glUniform1i(g.u.lightCount, lightCount);
  if (lightCount > 0) {
    glUniform3fv(g.u.lightDirection, lightCount, &directions[0][0]);
    glUniform3fv(g.u.lightColor, lightCount, &colors[0][0]);
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
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count));
  if (blend == SplatBlend::frontToBack) {
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previousFramebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glUseProgram(g.layerProgram);
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

}  // namespace gs::render
