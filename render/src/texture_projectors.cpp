// X3D Texture projection (X3D 4.0 clause 42) in the surface programs (texture_projectors.hpp).
#include "texture_projectors.hpp"

#include "gl_program.hpp"

#include <glm/gtc/type_ptr.hpp>

namespace gs::render::detail {

void ProjectorUniformLocations::find(GLuint p) {
  count = glGetUniformLocation(p, "u_projectorCount");
  matrix = glGetUniformLocation(p, "u_projectorMatrix");
  location = glGetUniformLocation(p, "u_projectorLocation");
  color = glGetUniformLocation(p, "u_projectorColor");
  intensity = glGetUniformLocation(p, "u_projectorIntensity");
  depthRange = glGetUniformLocation(p, "u_projectorDepthRange");
  static constexpr std::array<const char*, kMaxTextureProjectors> kTextures = {
      "u_projectorTexture0", "u_projectorTexture1", "u_projectorTexture2", "u_projectorTexture3"};
  for (std::size_t i = 0; i < kTextures.size(); ++i)
    texture[i] = glGetUniformLocation(p, kTextures[i]);
}

EyeProjector eyeProjector(const scene::TextureProjectorInstance& p, const GpuTexture& t,
                          const glm::mat4& view) {
  EyeProjector e;
  e.layer = p.layer;
  if (t.components == 0 || t.id == 0) return e;
  // NDC to [0, 1]: s, t and the depth p (X_ITE's bias matrix).
  glm::mat4 bias(0.5f);
  bias[3] = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  e.matrix = bias * scene::textureProjection(p, t.width, t.height) *
             glm::inverse(view * p.projectorToWorld);
  e.location = glm::vec3(view * p.projectorToWorld[3]);
  e.color = p.color;
  e.intensity = p.intensity;
  // A near or far distance given clips there; without one nothing is clipped on that side.
  e.depthRange = {p.nearDistance < 0.0f ? 0.0f : -1.0f, p.farDistance < 0.0f ? 1.0f : 2.0f};
  e.texture = t.id;
  return e;
}

void uploadProjectors(const ProjectorUniformLocations& u, const ShapeProjectors& s) {
  if (u.count < 0) return;
  glUniform1i(u.count, s.count);
  if (s.count == 0) return;
  std::array<glm::mat4, kMaxTextureProjectors> matrix{};
  std::array<glm::vec3, kMaxTextureProjectors> location{}, color{};
  std::array<float, kMaxTextureProjectors> intensity{};
  std::array<glm::vec2, kMaxTextureProjectors> depthRange{};
  for (int i = 0; i < s.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const EyeProjector& p = *s.projector[k];
    matrix[k] = p.matrix;
    location[k] = p.location;
    color[k] = p.color;
    intensity[k] = p.intensity;
    depthRange[k] = p.depthRange;
    glUniform1i(u.texture[k], kFirstProjectorUnit + i);
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kFirstProjectorUnit + i));
    glBindTexture(GL_TEXTURE_2D, p.texture);
  }
  glActiveTexture(GL_TEXTURE0);
  glUniformMatrix4fv(u.matrix, s.count, GL_FALSE, glm::value_ptr(matrix[0]));
  glUniform3fv(u.location, s.count, glm::value_ptr(location[0]));
  glUniform3fv(u.color, s.count, glm::value_ptr(color[0]));
  glUniform1fv(u.intensity, s.count, intensity.data());
  glUniform2fv(u.depthRange, s.count, glm::value_ptr(depthRange[0]));
}

}  // namespace gs::render::detail
