// Private to render/: X3D Texture projection (X3D 4.0 clause 42) in the surface programs:
// the GLSL both programs share and the uniforms of the projectors that reach a shape.
#pragma once

#include "gpu_resources.hpp"
#include "scene/traversal.hpp"

#include <glad/gl.h>
#include <glm/glm.hpp>

#include <array>

namespace gs::render::detail {

/// Projectors a shape takes at most (X_ITE's count): the global ones of its layer first,
/// then its scoped ones, in traversal order.
inline constexpr int kMaxTextureProjectors = 4;
/// The texture units of projectors 0..3.
inline constexpr GLint kFirstProjectorUnit = 12;

/// The shared GLSL: uniforms and `vec3 projectedColor(vec3 position, vec3 normal, bool
/// linear)`, the factor the colour before lighting is multiplied by: for each projector
/// whose frustum holds the eye-space `position` on the side of the surface (normal, eye
/// space, already turned to the viewer's side) facing it, mix(1, T.rgb color, T.a
/// intensity), T the texel (decoded from sRGB when `linear`), as X_ITE 15 does.
#define GS_TEXTURE_PROJECTOR_GLSL                                                               \
  "const int kMaxProjectors = 4;\n"                                                             \
  "uniform int u_projectorCount;\n"                                                             \
  "uniform mat4 u_projectorMatrix[kMaxProjectors];  // eye -> (s, t, p, q)\n"                   \
  "uniform vec3 u_projectorLocation[kMaxProjectors];  // eye coordinates\n"                     \
  "uniform vec3 u_projectorColor[kMaxProjectors];\n"                                            \
  "uniform float u_projectorIntensity[kMaxProjectors];\n"                                       \
  "uniform vec2 u_projectorDepthRange[kMaxProjectors];  // p clamped to it\n"                   \
  "uniform sampler2D u_projectorTexture0;\n"                                                    \
  "uniform sampler2D u_projectorTexture1;\n"                                                    \
  "uniform sampler2D u_projectorTexture2;\n"                                                    \
  "uniform sampler2D u_projectorTexture3;\n"                                                    \
  "vec3 projectedColor(vec3 position, vec3 normal, bool linear) {\n"                            \
  "  vec3 factor = vec3(1.0);\n"                                                                \
  "  for (int i = 0; i < kMaxProjectors; ++i) {\n"                                              \
  "    if (i >= u_projectorCount) break;\n"                                                     \
  "    vec4 c = u_projectorMatrix[i] * vec4(position, 1.0);\n"                                  \
  "    vec3 stp = c.xyz / c.w;\n"                                                               \
  "    stp.z = clamp(stp.z, u_projectorDepthRange[i].x, u_projectorDepthRange[i].y);\n"         \
  "    if (any(greaterThan(abs(stp - 0.5), vec3(0.5)))) continue;\n"                            \
  "    if (dot(normal, u_projectorLocation[i] - position) < 0.0) continue;\n"                   \
  "    vec4 t = i == 0 ? texture(u_projectorTexture0, stp.xy)\n"                                \
  "           : i == 1 ? texture(u_projectorTexture1, stp.xy)\n"                                \
  "           : i == 2 ? texture(u_projectorTexture2, stp.xy)\n"                                \
  "                    : texture(u_projectorTexture3, stp.xy);\n"                               \
  "    if (linear) t.rgb = pow(t.rgb, vec3(2.2));\n"                                            \
  "    factor *= mix(vec3(1.0), t.rgb * u_projectorColor[i], t.a * u_projectorIntensity[i]);\n" \
  "  }\n"                                                                                       \
  "  return factor;\n"                                                                          \
  "}\n"

/// Uniform locations of the projector GLSL in one program.
struct ProjectorUniformLocations {
  GLint count = -1, matrix = -1, location = -1, color = -1, intensity = -1, depthRange = -1;
  std::array<GLint, kMaxTextureProjectors> texture{-1, -1, -1, -1};
  void find(GLuint program);
};

/// One projector in eye coordinates, made once per frame (eyeProjector); texture 0: it
/// projects nothing (its texture has not loaded or could not be).
struct EyeProjector {
  glm::mat4 matrix{1.0f};    // eye -> texture (s, t, p, q)
  glm::vec3 location{0.0f};  // eye coordinates
  glm::vec3 color{1.0f};
  float intensity = 0.0f;
  glm::vec2 depthRange{0.0f, 1.0f};  // the projected depth p is clamped to it
  GLuint texture = 0;
  std::uint32_t layer = 0;  // scene::TextureProjectorInstance::layer
};

/// Projector `p` whose texture is `t`, for a view `view` (world to eye).
EyeProjector eyeProjector(const scene::TextureProjectorInstance& p, const GpuTexture& t,
                          const glm::mat4& view);

/// The projectors of one shape, ready to upload.
struct ShapeProjectors {
  int count = 0;
  std::array<const EyeProjector*, kMaxTextureProjectors> projector{};
  /// Adds `p` unless it projects nothing or kMaxTextureProjectors are in already.
  void add(const EyeProjector& p) {
    if (count < kMaxTextureProjectors && p.texture != 0)
      projector[static_cast<std::size_t>(count++)] = &p;
  }
};

/// Sets the uniforms of `s` in the program in use and binds its textures (units
/// kFirstProjectorUnit...); leaves GL_TEXTURE0 active.
void uploadProjectors(const ProjectorUniformLocations& u, const ShapeProjectors& s);

}  // namespace gs::render::detail
