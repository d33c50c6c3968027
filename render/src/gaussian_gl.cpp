// The GL path of 3D Gaussians (see gaussian_gl.hpp).
#include "gaussian_gl.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl_program.hpp"

namespace gs::render::detail {

namespace {

const char* const kGaussianVertexShader = R"glsl(#version 330 core
layout(location = 0) in uint a_index;  // per instance: the Gaussian
uniform samplerBuffer u_splats;        // 3 texels each: centre + opacity, covariance
uniform samplerBuffer u_colors;        // RGBA8: this view's colour
uniform mat4 u_modelView;
uniform mat4 u_projection;
uniform vec2 u_focal;     // fx, fy, pixels
uniform vec2 u_viewport;  // width, height, pixels
uniform float u_near;
uniform float u_opacityScale;
uniform float u_minAlpha;      // fragments below it are not drawn (1/255; vectors 0.5/255)
uniform float u_keepIntegral;  // 1: the peak keeps the integrated opacity (QNV vectors)
uniform int u_fogType;         // render::SplatFog
uniform vec3 u_fogColor;
uniform float u_fogVisibilityRange;
uniform vec4 u_fogPlane;
out vec2 v_offset;  // pixels from the centre, y up
flat out vec3 v_conic;
flat out vec4 v_color;
flat out float v_minAlpha;  // u_minAlpha scaled as the peak (QNV vectors)

void main() {
  int i = int(a_index);
  vec4 t0 = texelFetch(u_splats, 3 * i);
  vec4 t1 = texelFetch(u_splats, 3 * i + 1);
  vec4 t2 = texelFetch(u_splats, 3 * i + 2);
  vec4 eye = u_modelView * vec4(t0.xyz, 1.0);
  float depth = -eye.z;
  gl_Position = vec4(0.0, 0.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
  float opacity = min(t0.w * u_opacityScale, 1.0);
  if (!(depth >= u_near) || !(opacity >= u_minAlpha)) return;
  mat3 sigma = mat3(t1.x, t1.y, t1.z, t1.y, t1.w, t2.x, t1.z, t2.x, t2.y);
  mat3 w = mat3(u_modelView);
  w[0].z = -w[0].z; w[1].z = -w[1].z; w[2].z = -w[2].z;  // eye z forward
  vec2 limit = 1.3 * 0.5 * u_viewport / u_focal;
  vec2 t = clamp(eye.xy / depth, -limit, limit) * depth;
  vec3 j0 = vec3(u_focal.x / depth, 0.0, -u_focal.x * t.x / (depth * depth));
  vec3 j1 = vec3(0.0, u_focal.y / depth, -u_focal.y * t.y / (depth * depth));
  mat3 cov = w * sigma * transpose(w);
  float a = dot(j0, cov * j0) + 0.3;
  float b = dot(j0, cov * j1);
  float c = dot(j1, cov * j1) + 0.3;
  float det = a * c - b * b;
  if (!(det > 0.0)) return;
  float keep = sqrt(clamp(((a - 0.3) * (c - 0.3) - b * b) / det, 0.0, 1.0));
  keep = mix(1.0, keep, u_keepIntegral);
  opacity *= keep;
  if (!(opacity > 0.0)) return;
  float mid = 0.5 * (a + c);
  float radius = ceil(3.0 * sqrt(mid + sqrt(max(0.1, mid * mid - det))));
  vec2 corner = vec2((gl_VertexID & 1) == 0 ? -radius : radius,
                     (gl_VertexID & 2) == 0 ? -radius : radius);
  vec4 clip = u_projection * eye;
  gl_Position = clip + vec4(corner * 2.0 / u_viewport * clip.w, 0.0, 0.0);
  v_offset = corner;
  v_conic = vec3(c, -b, a) / det;
  v_color = vec4(texelFetch(u_colors, i).rgb, opacity);
  if (u_fogType != 0 && u_fogVisibilityRange > 0.0) {  // render::fogged
    float d = u_fogPlane != vec4(0.0) ? dot(u_fogPlane, eye) : length(eye.xyz);
    float r = u_fogVisibilityRange;
    float f = d < r ? (u_fogType == 1 ? (r - d) / r : exp(-d / (r - d))) : 0.0;
    v_color.rgb = mix(u_fogColor, v_color.rgb, clamp(f, 0.0, 1.0));
  }
  v_minAlpha = u_minAlpha * keep;
}
)glsl";

const char* const kGaussianFragmentShader = R"glsl(#version 330 core
in vec2 v_offset;
flat in vec3 v_conic;
flat in vec4 v_color;
flat in float v_minAlpha;
out vec4 o_color;
void main() {
  float power = -0.5 * (v_conic.x * v_offset.x * v_offset.x + v_conic.z * v_offset.y * v_offset.y)
                - v_conic.y * v_offset.x * v_offset.y;
  if (power > 0.0) discard;
  float alpha = min(0.99, v_color.a * exp(power));
  if (alpha < v_minAlpha) discard;
  o_color = vec4(v_color.rgb * alpha, alpha);  // premultiplied
}
)glsl";

}  // namespace

void GaussianGlPass::create() {
  if (program_ != 0) return;
  program_ = buildProgram("gaussian splats", kGaussianVertexShader, kGaussianFragmentShader);
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &orderBuffer_);
  glGenBuffers(1, &splatBuffer_);
  glGenBuffers(1, &colorBuffer_);
  glGenBuffers(1, &subsetBuffer_);
  glGenTextures(1, &splatTexture_);
  glGenTextures(1, &colorTexture_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, orderBuffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribIPointer(0, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
  glVertexAttribDivisor(0, 1);
  glBindVertexArray(0);
}

namespace {

/// Puts `bytes` (the whole array) into `buffer` from byte `from` on: only the tail
/// [from, size) when the buffer's store (`capacity` bytes) already holds it, else a new
/// store of at least twice the old capacity with everything. Rebinds `texture` to it.
void uploadTail(GLuint buffer, GLuint texture, GLenum format, const void* bytes, std::size_t size,
                std::size_t from, std::size_t& capacity, GLenum usage) {
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  if (from > 0 && from <= size && size <= capacity) {
    glBufferSubData(GL_TEXTURE_BUFFER, static_cast<GLintptr>(from),
                    static_cast<GLsizeiptr>(size - from), static_cast<const char*>(bytes) + from);
  } else {
    capacity = std::max(size, from > 0 ? 2 * capacity : size);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(capacity), nullptr, usage);
    glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(size), bytes);
  }
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, format, buffer);
}

}  // namespace

void GaussianGlPass::uploadSplats(std::size_t from) {
  uploadTail(splatBuffer_, splatTexture_, GL_RGBA32F, staging_.data(),
             staging_.size() * sizeof(float), from * 12 * sizeof(float), splatCapacity_,
             GL_STATIC_DRAW);
}

void GaussianGlPass::uploadColors(std::size_t from) {
  uploadTail(colorBuffer_, colorTexture_, GL_RGBA8, colors_.data(), colors_.size(), from * 4,
             colorCapacity_, GL_STREAM_DRAW);
}

namespace {

/// Splat i's three texels: centre and opacity, then the covariance's six entries.
void writeTexels(float* t, const glm::vec3& position, float opacity, const glm::mat3& s) {
  t[0] = position.x;
  t[1] = position.y;
  t[2] = position.z;
  t[3] = opacity;
  t[4] = s[0][0];
  t[5] = s[1][0];
  t[6] = s[2][0];
  t[7] = s[1][1];
  t[8] = s[2][1];
  t[9] = s[2][2];
  t[10] = t[11] = 0.0f;
}

void writeColor(std::uint8_t* out, const glm::vec3& c) {
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<std::uint8_t>(std::clamp(c[k], 0.0f, 1.0f) * 255.0f + 0.5f);
  out[3] = 255;
}

}  // namespace

void GaussianGlPass::uploadCloud(const splats::GaussianCloud& cloud, const glm::vec3& eye,
                                 std::uint64_t revision, bool gpuColors) {
  create();
  const std::size_t n = cloud.size();
  if (uploaded_ != &cloud || uploadedSize_ != n || uploadedRevision_ != revision) {
    shOnGpu_ = false;
    staging_.resize(n * 12);
    for (std::size_t i = 0; i < n; ++i)
      writeTexels(&staging_[i * 12], cloud.positions[i], cloud.opacities[i],
                  splats::covariance(cloud.scales[i], cloud.rotations[i]));
    uploadSplats(0);
    uploaded_ = &cloud;
    uploadedSize_ = n;
    uploadedRevision_ = revision;
    colorKey_.clear();
  }
  // This view's colours: SH along the ray from the camera (once when the cloud has none),
  // on the GPU when asked (the gpu path: nothing per splat on the CPU as the view moves).
  const bool viewDependent = cloud.shDegree > 0;
  if (viewDependent && gpuColors && n > 0) {
    if (!shOnGpu_) {
      shColors_.upload(cloud);
      shOnGpu_ = true;
      colorKey_.clear();
    }
    if (colorKey_.empty() || !(colorEye_ == eye)) {
      if (colorCapacity_ < n * 4) {
        colorCapacity_ = n * 4;
        glBindBuffer(GL_TEXTURE_BUFFER, colorBuffer_);
        glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(colorCapacity_), nullptr,
                     GL_STREAM_DRAW);
        glBindTexture(GL_TEXTURE_BUFFER, colorTexture_);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA8, colorBuffer_);
      }
      shColors_.evaluate(splatTexture_, colorBuffer_, n, eye);
      colorEye_ = eye;
      colorKey_.assign(1, 1.0f);  // 1: made on the GPU
    }
    return;
  }
  if (colorKey_.empty() || colorKey_[0] != 0.0f || (viewDependent && !(colorEye_ == eye))) {
    colors_.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3 toward = cloud.positions[i] - eye;
      const float length = glm::length(toward);
      writeColor(&colors_[i * 4],
                 splats::shColor(cloud, i,
                                 length > 0.0f ? toward / length : glm::vec3(0.0f, 0.0f, -1.0f)));
    }
    uploadColors(0);
    colorEye_ = eye;
    colorKey_.assign(1, 0.0f);
  }
}

void GaussianGlPass::draw(const splats::GaussianCloud& cloud, std::span<const std::uint32_t> order,
                          const glm::mat4& modelView, const glm::mat4& projection,
                          const glm::vec3& eye, const int viewport[4], float nearClip,
                          float opacityScale, std::uint64_t revision) {
  uploadCloud(cloud, eye, revision, false);
  drawUploaded(order, order.size(), modelView, projection, viewport, nearClip, opacityScale,
               1.0f / 255.0f, false);
}

void GaussianGlPass::drawGpuSorted(const splats::GaussianCloud& cloud, std::size_t count,
                                   const glm::mat4& modelView, const glm::mat4& projection,
                                   const glm::vec3& eye, const int viewport[4], float nearClip,
                                   float opacityScale, std::uint64_t revision,
                                   std::span<const std::uint32_t> subset,
                                   std::uint64_t subsetRevision) {
  uploadCloud(cloud, eye, revision, GpuDepthSort::available());
  if (subset.empty()) {
    drawUploaded({}, std::min(count, cloud.size()), modelView, projection, viewport, nearClip,
                 opacityScale, 1.0f / 255.0f, false);
    return;
  }
  // A cut: its indices sent when it changed (a few bytes a splat), the cloud kept.
  if (subsetSent_ != subset.data() || subsetSize_ != subset.size() ||
      subsetRevision_ != subsetRevision) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, subsetBuffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER,
                 static_cast<GLsizeiptr>(subset.size() * sizeof(std::uint32_t)), subset.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    subsetSent_ = subset.data();
    subsetSize_ = subset.size();
    subsetRevision_ = subsetRevision;
  }
  drawUploaded({}, subset.size(), modelView, projection, viewport, nearClip, opacityScale,
               1.0f / 255.0f, false, subsetBuffer_);
}

void GaussianGlPass::drawVectors(std::span<const qnv::DecodedVector> vectors,
                                 std::uint64_t revision, std::span<const std::uint32_t> order,
                                 std::size_t count, const SplatStyle& style,
                                 std::span<const SplatLight> lights, const glm::mat3& normalMatrix,
                                 const glm::mat4& modelView, const glm::mat4& projection,
                                 const int viewport[4], float nearClip) {
  create();
  const std::size_t n = vectors.size();
  // A set that grew (a progressive stream: vectors are only appended, SplatSet) sends only
  // its new tail; anything else is uploaded whole.
  const bool same = uploaded_ == vectors.data() && uploadedRevision_ == revision &&
                    std::memcmp(&uploadedStyle_, &style, sizeof style) == 0 && n >= uploadedSize_;
  if (!same || n != uploadedSize_) {
    const std::size_t from = same ? uploadedSize_ : 0;
    staging_.resize(n * 12);
    for (std::size_t i = from; i < n; ++i) {
      VectorGaussian g;
      if (!vectorGaussian(vectors[i], style, g)) g = {};  // opacity 0: not drawn
      writeTexels(&staging_[i * 12], g.position, g.opacity, g.covariance);
    }
    uploadSplats(from);
    uploaded_ = vectors.data();
    uploadedSize_ = n;
    uploadedRevision_ = revision;
    uploadedStyle_ = style;
    if (!same) colorKey_.clear();
  }
  // The flat shading of every vector, again when the lights or the placement change; only
  // the new tail's when the set grew under the same lights.
  std::vector<float>& key = nextColorKey_;  // kept: no allocation per frame
  key.clear();
  key.push_back(style.ambient);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) key.push_back(normalMatrix[c][r]);
  const std::size_t lightCount = std::min<std::size_t>(lights.size(), 8);
  for (std::size_t i = 0; i < lightCount; ++i)
    for (int k = 0; k < 3; ++k) {
      key.push_back(lights[i].direction[k]);
      key.push_back(lights[i].color[k]);
    }
  if (key != colorKey_ || coloredSize_ != n) {
    const std::size_t from = key == colorKey_ && coloredSize_ < n ? coloredSize_ : 0;
    colors_.resize(n * 4);
    for (std::size_t i = from; i < n; ++i) {
      const qnv::DecodedVector& v = vectors[i];
      const float length = glm::length(normalMatrix * v.normal);
      const glm::vec3 world = length > 0.0f ? normalMatrix * v.normal / length : glm::vec3(0.0f);
      writeColor(&colors_[i * 4], shadeSplat(world, glm::vec3(unpackRgba(v.rgba)),
                                             lights.first(lightCount), style.ambient));
    }
    uploadColors(from);
    colorKey_.swap(key);
    coloredSize_ = n;
  }
  drawUploaded(order, order.empty() ? count : order.size(), modelView, projection, viewport,
               nearClip, 1.0f, splats::kVisiblePeak, true);
}

void GaussianGlPass::drawUploaded(std::span<const std::uint32_t> order, std::size_t count,
                                  const glm::mat4& modelView, const glm::mat4& projection,
                                  const int viewport[4], float nearClip, float opacityScale,
                                  float minAlpha, bool keepIntegral, GLuint subset) {
  if (count == 0) return;
  GLuint orderBuffer = orderBuffer_;
  if (order.empty()) {
    gpuSort_.sort(splatTexture_, count, modelView, subset);
    orderBuffer = gpuSort_.order();
  } else {
    glBindBuffer(GL_ARRAY_BUFFER, orderBuffer_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(order.size() * sizeof(std::uint32_t)),
                 order.data(), GL_STREAM_DRAW);
  }
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, orderBuffer);
  glVertexAttribIPointer(0, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
  glBindVertexArray(0);

  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, splatTexture_);
  glUniform1i(uniform(program_, "u_splats"), 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, colorTexture_);
  glUniform1i(uniform(program_, "u_colors"), 1);
  glActiveTexture(GL_TEXTURE0);
  glUniformMatrix4fv(uniform(program_, "u_modelView"), 1, GL_FALSE, &modelView[0][0]);
  glUniformMatrix4fv(uniform(program_, "u_projection"), 1, GL_FALSE, &projection[0][0]);
  const float w = static_cast<float>(viewport[2]), h = static_cast<float>(viewport[3]);
  glUniform2f(uniform(program_, "u_focal"), projection[0][0] * w * 0.5f,
              projection[1][1] * h * 0.5f);
  glUniform2f(uniform(program_, "u_viewport"), w, h);
  glUniform1f(uniform(program_, "u_near"), nearClip);
  glUniform1f(uniform(program_, "u_opacityScale"), opacityScale);
  glUniform1f(uniform(program_, "u_minAlpha"), minAlpha);
  glUniform1f(uniform(program_, "u_keepIntegral"), keepIntegral ? 1.0f : 0.0f);
  glUniform1i(uniform(program_, "u_fogType"), fog_.type);
  glUniform3fv(uniform(program_, "u_fogColor"), 1, &fog_.color[0]);
  glUniform1f(uniform(program_, "u_fogVisibilityRange"), fog_.visibilityRange);
  glUniform4fv(uniform(program_, "u_fogPlane"), 1, &fog_.eyePlane[0]);
  // Into the float layer (the scene's depth copied in), composited over the framebuffer
  // once; straight into the framebuffer where the layer cannot take the scene's depth.
  const bool layered = layer_.begin(viewport);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count));
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  if (layered) layer_.end();
}

void GaussianGlPass::release() {
  if (program_ == 0) return;
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &vao_);
  GLuint buffers[] = {orderBuffer_, splatBuffer_, colorBuffer_, subsetBuffer_};
  glDeleteBuffers(4, buffers);
  subsetSent_ = nullptr;
  subsetSize_ = 0;
  GLuint textures[] = {splatTexture_, colorTexture_};
  glDeleteTextures(2, textures);
  program_ = 0;
  uploaded_ = nullptr;
  colorKey_.clear();
  splatCapacity_ = colorCapacity_ = coloredSize_ = 0;
  gpuSort_.release();
  shColors_.release();
  layer_.release();
  shOnGpu_ = false;
}

}  // namespace gs::render::detail
