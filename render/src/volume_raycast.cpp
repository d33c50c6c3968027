// The volume ray caster (volume_raycast.hpp): X_ITE 15's slices as samples along each
// pixel's ray, its style code per sample, composited front to back.
#include "volume_raycast.hpp"

#include "gl_program.hpp"
#include "volume_style_glsl.hpp"

#include "scene/node_access.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace gs::render::detail {

namespace {

/// Slices X_ITE 15 draws at its default TextureQuality (MEDIUM).
constexpr int kVolumeSlices = 400;
/// The first texture unit the ray caster binds (the voxels, then the style's samplers):
/// after the renderer's own (0..7), before the texture projectors' (12..15).
constexpr int kVolumeFirstUnit = 8;

const char* const kVolumeVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_boxModelView;  // the unit box to eye coordinates
uniform mat4 u_projection;
void main() { gl_Position = u_projection * u_boxModelView * vec4(a_position, 1.0); }
)glsl";

// Before the style code: what X_ITE's VolumeStyle.fs gives its styles.
const char* const kVolumePrelude = R"glsl(
#define x3d_DirectionalLight 1
#define x3d_PointLight 2
#define x3d_SpotLight 3
uniform sampler3D x3d_Texture3D[1];
uniform mat3 x3d_TextureNormalMatrix;
// The eye's +z axis in texture coordinates (ProjectionVolumeStyle marches along it; X_ITE
// takes the texture's r axis, right only for a volume that is not turned).
uniform vec3 x3d_TextureViewDirection;
struct x3d_LightSourceParameters {
  int type; vec3 color; float intensity; float ambientIntensity; vec3 attenuation;
  vec3 location; vec3 direction; float radius; float beamWidth; float cutOffAngle;
};
uniform x3d_LightSourceParameters x3d_LightSource[8];
const float M_PI = 3.141592653589793;
const float M_SQRT2 = 1.4142135623730951;
const float M_SQRT1_2 = 0.7071067811865476;
vec3 vertex;  // the sample's eye-space position
)glsl";

// After it: the march. The planes are X_ITE's slices: perpendicular to the eye's z axis
// (u_sliceNormal, in local coordinates), offsets (j / (N - 1) - 0.5) * u_sliceSize from
// the origin, nearest first.
const char* const kVolumeMarch = R"glsl(
uniform mat4 u_modelView;
uniform mat4 u_inverseModelViewProjection;
uniform vec4 u_viewport;  // x, y, width, height (pixels)
uniform vec3 u_dimensions;
uniform vec3 u_sliceNormal;
uniform float u_sliceSize;
uniform int u_slices;
// ClipPlanes in the box's local coordinates (a sample p is kept where dot(plane, (p, 1))
// >= 0); fog as the surface programs have it (eye coordinates).
uniform int u_clipPlaneCount;
uniform vec4 u_clipPlanes[8];
uniform int u_fogType;  // 0 none, 1 LINEAR, 2 EXPONENTIAL
uniform vec3 u_fogColor;
uniform float u_fogVisibilityRange;
uniform vec4 u_fogPlane;  // volumetric fog: the distance is dot(plane, (eye position, 1))
uniform bool u_sceneDepthUsed;  // the opaque scene's depth stops the rays
uniform sampler2D u_sceneDepth;  // window depth (0..1) at each framebuffer pixel
out vec4 fragColor;

bool clippedAway(vec3 p) {
  for (int k = 0; k < u_clipPlaneCount; ++k)
    if (dot(u_clipPlanes[k], vec4(p, 1.0)) < 0.0) return true;
  return false;
}

vec3 fogged(vec3 color, vec3 eye) {
  if (u_fogType == 0 || u_fogVisibilityRange <= 0.0) return color;
  float d = u_fogPlane != vec4(0.0) ? dot(u_fogPlane, vec4(eye, 1.0)) : length(eye);
  float r = u_fogVisibilityRange;
  float f = 0.0;
  if (d < r) f = u_fogType == 1 ? (r - d) / r : exp(-d / (r - d));
  return mix(u_fogColor, color, clamp(f, 0.0, 1.0));
}

void main() {
  vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
  vec4 a = u_inverseModelViewProjection * vec4(ndc, -1.0, 1.0);
  vec4 b = u_inverseModelViewProjection * vec4(ndc, 1.0, 1.0);
  vec3 o = a.xyz / a.w;
  vec3 d = b.xyz / b.w - o;  // near plane to far plane, local coordinates
  // The part of the ray inside the box (slabs), within the near and far planes.
  vec3 halfSize = 0.5 * u_dimensions;
  // (A zero component gets a tiny one: no infinities or NaNs at the box's edges.)
  vec3 inv = 1.0 / mix(d, vec3(1e-20), lessThan(abs(d), vec3(1e-20)));
  vec3 t0 = (-halfSize - o) * inv, t1 = (halfSize - o) * inv;
  vec3 lo = min(t0, t1), hi = max(t0, t1);
  float s0 = max(max(lo.x, lo.y), max(lo.z, 0.0));
  float s1 = min(min(hi.x, hi.y), min(hi.z, 1.0));
  // An opaque surface inside the box (or in front of it, seen from inside) ends the ray.
  if (u_sceneDepthUsed) {
    float z = texelFetch(u_sceneDepth, ivec2(gl_FragCoord.xy), 0).r;
    if (z < 1.0) {
      vec4 c = u_inverseModelViewProjection * vec4(ndc, z * 2.0 - 1.0, 1.0);
      s1 = min(s1, dot(c.xyz / c.w - o, d) / dot(d, d));
    }
  }
  if (!(s0 < s1)) discard;  // missed (or NaN)
  float dn = dot(d, u_sliceNormal);
  if (abs(dn) < 1e-12) discard;
  float n1 = float(u_slices - 1);
  float on = dot(o, u_sliceNormal);
  // Slice offsets at the two ends, in slice index units.
  float j0 = (on + s0 * dn) / u_sliceSize * n1 + 0.5 * n1;
  float j1 = (on + s1 * dn) / u_sliceSize * n1 + 0.5 * n1;
  int jFirst = int(floor(max(j0, j1)));
  int jLast = int(ceil(min(j0, j1)));
  jFirst = min(jFirst, u_slices - 1);
  jLast = max(jLast, 0);
  if (jFirst < jLast) discard;
  vec3 color = vec3(0.0);
  float transmittance = 1.0;
  for (int j = jFirst; j >= jLast; --j) {
    float offset = (float(j) / n1 - 0.5) * u_sliceSize;
    float s = (offset - on) / dn;
    vec3 p = o + s * d;
    vec3 texCoord = p / u_dimensions + 0.5;
    if (any(greaterThan(abs(texCoord - 0.5), vec3(0.5))) || clippedAway(p)) continue;
    vertex = (u_modelView * vec4(p, 1.0)).xyz;
    vec4 c = clamp(getTextureColor(texCoord), 0.0, 1.0);
    c.rgb = fogged(c.rgb, vertex);
    color += transmittance * c.a * c.rgb;
    transmittance *= 1.0 - c.a;
    if (transmittance < 1.0 / 1024.0) break;
  }
  fragColor = vec4(color, 1.0 - transmittance);
}
)glsl";

std::string volumeFragmentSource(const VolumeStyleGlsl& style, int lights) {
  std::string s = "#version 330 core\n";
  s += "#define X3D_NUM_LIGHTS " + std::to_string(lights) + "\n";
  if (lights > 0) s += "#define X3D_LIGHTING\n";
  s += style.defines;
  s += kVolumePrelude;
  s += style.uniforms;
  s += "\nvec4 getTextureColor(in vec3 texCoord) {\n"
       "  vec4 textureColor = texture(x3d_Texture3D[0], texCoord);\n";
  s += style.functions;
  s += "\n  return textureColor;\n}\n";
  s += kVolumeMarch;
  return s;
}

/// The box's triangles: 12, corners of [-0.5, 0.5]^3 (scaled by dimensions in the model
/// matrix), counter-clockwise seen from outside.
std::array<float, 108> unitBox() {
  static const int kFaces[6][4][3] = {
      {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},
      {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}};
  std::array<float, 108> v{};
  std::size_t k = 0;
  for (const auto& f : kFaces)
    for (int i : {0, 1, 2, 0, 2, 3})
      for (int c = 0; c < 3; ++c) v[k++] = static_cast<float>(f[i][c]) - 0.5f;
  return v;
}

void setLight(GLuint program, int i, int type, const glm::vec3& color, float intensity,
              float ambient, const glm::vec3& attenuation, const glm::vec3& location,
              const glm::vec3& direction, float radius, float beamWidth, float cutOffAngle) {
  const std::string base = "x3d_LightSource[" + std::to_string(i) + "].";
  auto at = [&](const char* field) { return uniform(program, (base + field).c_str()); };
  glUniform1i(at("type"), type);
  glUniform3fv(at("color"), 1, glm::value_ptr(color));
  glUniform1f(at("intensity"), intensity);
  glUniform1f(at("ambientIntensity"), ambient);
  glUniform3fv(at("attenuation"), 1, glm::value_ptr(attenuation));
  glUniform3fv(at("location"), 1, glm::value_ptr(location));
  glUniform3fv(at("direction"), 1, glm::value_ptr(direction));
  glUniform1f(at("radius"), radius);
  glUniform1f(at("beamWidth"), beamWidth);
  glUniform1f(at("cutOffAngle"), cutOffAngle);
}

}  // namespace

bool VolumeRaycaster::draw(const vrml::Node& node, const std::string& baseUrl,
                           const glm::mat4& model, const scene::Camera& camera, float aspect,
                           std::span<const scene::LightInstance> lights, bool headlight,
                           const VolumeSurroundings& around, TextureCache& textures,
                           scene::SceneTraversal& traversal, base::Fetcher* fetcher) {
  const vrml::NodePtr& voxels = node.sfnode("voxels");
  if (!voxels || voxels->unresolved) return false;
  const GpuTexture& volume = textures.get(*voxels, baseUrl, traversal, fetcher);
  if (volume.id == 0 || !volume.volume) return false;
  const VolumeStyleGlsl style = volumeStyleGlsl(node);
  // The style's samplers: every texture must be there (a file on its way: next frame).
  std::vector<std::pair<const VolumeStyleSampler*, const GpuTexture*>> bound;
  for (const VolumeStyleSampler& s : style.samplers) {
    if (s.texture == nullptr) continue;
    const GpuTexture& t = textures.get(*s.texture, baseUrl, traversal, fetcher);
    if (t.id == 0) return false;
    bound.emplace_back(&s, &t);
  }
  const int lightCount = std::min<int>(8, static_cast<int>(lights.size()) + (headlight ? 1 : 0));
  const std::string source = volumeFragmentSource(style, lightCount);
  auto [it, added] = programs_.try_emplace(source, 0);
  if (added) {
    try {
      it->second = buildProgram("volume ray caster", kVolumeVertexShader, source.c_str());
    } catch (const std::exception& e) {
      traversal.report(
          vrml::Severity::error, node.location,
          node.typeName() + ": its render style does not compile (" + e.what() + "): not drawn");
    }
  }
  const GLuint program = it->second;
  if (program == 0) return false;
  if (vao_ == 0) {
    const std::array<float, 108> box = unitBox();
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, sizeof(box), box.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  const glm::vec3 dimensions = glm::max(scene::sfVec3(node, "dimensions", glm::vec3(1.0f)), 1e-6f);
  const glm::mat4 view = scene::viewMatrix(camera);
  const glm::mat4 modelView = view * model;
  const glm::mat4 boxModelView = modelView * glm::scale(glm::mat4(1.0f), dimensions);
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  const glm::mat4 inverseMvp = glm::inverse(projection * modelView);
  const glm::mat4 eyeToLocal = glm::inverse(modelView);
  const glm::vec3 sliceNormal = glm::normalize(glm::vec3(eyeToLocal * glm::vec4(0, 0, 1, 0)));
  GLint viewport[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_VIEWPORT, viewport);

  glUseProgram(program);
  glUniformMatrix4fv(uniform(program, "u_modelView"), 1, GL_FALSE, glm::value_ptr(modelView));
  glUniformMatrix4fv(uniform(program, "u_boxModelView"), 1, GL_FALSE, glm::value_ptr(boxModelView));
  glUniformMatrix4fv(uniform(program, "u_projection"), 1, GL_FALSE, glm::value_ptr(projection));
  glUniformMatrix4fv(uniform(program, "u_inverseModelViewProjection"), 1, GL_FALSE,
                     glm::value_ptr(inverseMvp));
  glUniform4f(uniform(program, "u_viewport"), static_cast<float>(viewport[0]),
              static_cast<float>(viewport[1]), static_cast<float>(viewport[2]),
              static_cast<float>(viewport[3]));
  glUniform3fv(uniform(program, "u_dimensions"), 1, glm::value_ptr(dimensions));
  glUniform3fv(uniform(program, "u_sliceNormal"), 1, glm::value_ptr(sliceNormal));
  glUniform1f(uniform(program, "u_sliceSize"), glm::length(dimensions));
  glUniform3fv(uniform(program, "x3d_TextureViewDirection"), 1,
               glm::value_ptr(glm::normalize(sliceNormal / dimensions)));
  glUniform1i(uniform(program, "u_slices"), kVolumeSlices);
  // ClipPlanes to the box's local coordinates (a plane maps by the transpose of the point
  // transform), the fog as a shape's (scene_renderer.cpp).
  std::array<glm::vec4, 8> planes{};
  const std::size_t planeCount = std::min(around.clipPlanes.size(), planes.size());
  for (std::size_t i = 0; i < planeCount; ++i)
    planes[i] = glm::transpose(model) * around.clipPlanes[i];
  glUniform1i(uniform(program, "u_clipPlaneCount"), static_cast<GLint>(planeCount));
  glUniform4fv(uniform(program, "u_clipPlanes[0]"), 8, glm::value_ptr(planes[0]));
  const SplatFog& fog = around.fog;
  glUniform1i(uniform(program, "u_fogType"), fog.type);
  glUniform3fv(uniform(program, "u_fogColor"), 1, glm::value_ptr(fog.color));
  glUniform1f(uniform(program, "u_fogVisibilityRange"), fog.visibilityRange);
  glUniform4fv(uniform(program, "u_fogPlane"), 1, glm::value_ptr(fog.eyePlane));
  // Texture-space gradients to eye space: X_ITE's x3d_TextureNormalMatrix (the inverse of
  // the texture transform's 3x3, position / dimensions) under the normal matrix.
  const glm::mat3 textureNormal = glm::inverseTranspose(glm::mat3(modelView)) *
                                  glm::mat3(glm::scale(glm::mat4(1.0f), 1.0f / dimensions));
  glUniformMatrix3fv(uniform(program, "x3d_TextureNormalMatrix"), 1, GL_FALSE,
                     glm::value_ptr(textureNormal));
  int n = 0;
  if (headlight)
    setLight(program, n++, 1, glm::vec3(1.0f), 1.0f, 0.0f, glm::vec3(1, 0, 0), glm::vec3(0.0f),
             glm::vec3(0, 0, -1), 100.0f, 1.570796f, 0.785398f);
  for (const scene::LightInstance& l : lights) {
    if (n >= lightCount) break;
    const int type = l.type == scene::LightType::directional ? 1
                     : l.type == scene::LightType::point     ? 2
                                                             : 3;
    const glm::vec3 location(view * glm::vec4(l.location, 1.0f));
    const glm::vec3 direction = glm::normalize(glm::vec3(view * glm::vec4(l.direction, 0.0f)));
    setLight(program, n++, type, l.color, l.intensity, l.ambientIntensity, l.attenuation, location,
             direction, l.radius, l.beamWidth, l.cutOffAngle);
  }
  // A lit ShadedVolumeStyle's x3d_LightMatrix (X_ITE's light.matrix: the inverse of the
  // light's model-view 3x3, for its radius test): our lights are in eye space already.
  if (const GLint lightMatrix = uniform(program, "x3d_LightMatrix[0]"); lightMatrix >= 0) {
    std::array<glm::mat3, 8> identities;
    identities.fill(glm::mat3(1.0f));
    glUniformMatrix3fv(lightMatrix, 8, GL_FALSE, glm::value_ptr(identities[0]));
  }
  // Every texture is read through a sampler without mipmaps: the styles sample inside the
  // march's loop, where implicit derivatives (and so the mipmap level) are undefined (a
  // coarse level there lit the box's silhouette). Segment identifiers are nearest.
  if (linearSampler_ == 0) {
    glGenSamplers(1, &linearSampler_);
    glGenSamplers(1, &nearestSampler_);
    for (const auto& [sampler, filter] :
         {std::pair{linearSampler_, GL_LINEAR}, std::pair{nearestSampler_, GL_NEAREST}}) {
      glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, filter);
      glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, filter);
      for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(sampler, wrap, GL_CLAMP_TO_EDGE);
    }
  }
  int unit = kVolumeFirstUnit;
  const int firstUnit = unit;
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_3D, volume.id);
  glBindSampler(static_cast<GLuint>(unit), linearSampler_);
  glUniform1i(uniform(program, "x3d_Texture3D[0]"), unit++);
  for (const auto& [s, t] : bound) {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
    glBindTexture(s->dimensions == 3 ? GL_TEXTURE_3D : GL_TEXTURE_2D, t->id);
    const bool identifiers = s->uniform.rfind("segmentIdentifiers", 0) == 0;
    glBindSampler(static_cast<GLuint>(unit), identifiers ? nearestSampler_ : linearSampler_);
    glUniform1i(uniform(program, s->uniform.c_str()), unit++);
  }
  const bool sceneDepth = copySceneDepth(viewport);
  glUniform1i(uniform(program, "u_sceneDepthUsed"), sceneDepth ? 1 : 0);
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_2D, sceneDepth ? depthTexture_ : 0);
  glBindSampler(static_cast<GLuint>(unit), nearestSampler_);
  glUniform1i(uniform(program, "u_sceneDepth"), unit++);
  glActiveTexture(GL_TEXTURE0);
  // Front faces, depth-tested: what is in front of the box hides it; from inside the box,
  // its back faces without the test.
  const glm::vec3 eyeLocal(eyeToLocal[3]);
  const bool inside = glm::all(glm::lessThanEqual(glm::abs(eyeLocal), 0.5f * dimensions * 1.001f));
  glEnable(GL_CULL_FACE);
  glCullFace(inside ? GL_FRONT : GL_BACK);
  if (inside) glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 36);
  glBindVertexArray(0);
  for (int u = firstUnit; u < unit; ++u) glBindSampler(static_cast<GLuint>(u), 0);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  return true;
}

SplatFog splatFogOf(const scene::FogSettings& fog, const glm::mat4& view) {
  SplatFog f;
  f.type = fog.visibilityRange > 0.0f ? (fog.exponential ? 2 : 1) : 0;
  f.color = fog.color;
  f.visibilityRange = fog.visibilityRange;
  if (fog.volumetric)
    f.eyePlane = glm::transpose(glm::inverse(view)) *
                 glm::vec4(fog.volumetricDirection, -fog.volumetricStart);
  return f;
}

bool VolumeRaycaster::copySceneDepth(const GLint viewport[4]) {
  GLint read = 0, draw = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  // A blit copies depth between equal formats only: the framebuffer's must be 24-bit depth
  // with 8-bit stencil, as this renderer's framebuffers and GLFW's default window are.
  // (Each attachment's type first: asking the size of one that is absent is a GL error.)
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(draw));
  const auto bits = [](GLenum attachment, GLenum size) {
    GLint type = GL_NONE, value = 0;
    glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, attachment,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_NONE)
      glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, attachment, size, &value);
    return value;
  };
  const GLint depthBits =
      bits(draw == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE);
  const GLint stencilBits =
      bits(draw == 0 ? GL_STENCIL : GL_STENCIL_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE);
  const int width = viewport[0] + viewport[2], height = viewport[1] + viewport[3];
  if (depthBits != 24 || stencilBits != 8 || viewport[0] < 0 || viewport[1] < 0 || width <= 0 ||
      height <= 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
    return false;
  }
  if (depthFbo_ == 0) {
    glGenFramebuffers(1, &depthFbo_);
    glGenTextures(1, &depthTexture_);
  }
  if (width != depthWidth_ || height != depthHeight_) {
    glBindTexture(GL_TEXTURE_2D, depthTexture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, width, height, 0, GL_DEPTH_STENCIL,
                 GL_UNSIGNED_INT_24_8, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, depthFbo_);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
                           depthTexture_, 0);
    depthWidth_ = width;
    depthHeight_ = height;
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, depthFbo_);
  const bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  if (complete) {
    // The same rectangle at the same place (a multisampled framebuffer is resolved so);
    // the scissor test would clip it.
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glBlitFramebuffer(viewport[0], viewport[1], width, height, viewport[0], viewport[1], width,
                      height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    if (scissor == GL_TRUE) glEnable(GL_SCISSOR_TEST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
  return complete;
}

void VolumeRaycaster::release() {
  for (auto& [source, program] : programs_)
    if (program != 0) glDeleteProgram(program);
  programs_.clear();
  if (vbo_ != 0) glDeleteBuffers(1, &vbo_);
  if (linearSampler_ != 0) glDeleteSamplers(1, &linearSampler_);
  if (nearestSampler_ != 0) glDeleteSamplers(1, &nearestSampler_);
  linearSampler_ = nearestSampler_ = 0;
  if (depthFbo_ != 0) glDeleteFramebuffers(1, &depthFbo_);
  if (depthTexture_ != 0) glDeleteTextures(1, &depthTexture_);
  depthFbo_ = depthTexture_ = 0;
  depthWidth_ = depthHeight_ = 0;
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  vao_ = vbo_ = 0;
}

}  // namespace gs::render::detail
