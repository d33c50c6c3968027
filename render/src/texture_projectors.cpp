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

void ShapeProjectors::add(const scene::TextureProjectorInstance& p, const GpuTexture& t,
                          const glm::mat4& view) {
  if (count >= kMaxTextureProjectors || t.components == 0 || t.id == 0) return;
  const auto i = static_cast<std::size_t>(count++);
  // NDC to [0, 1]: s, t and the depth p (X_ITE's bias matrix).
  glm::mat4 bias(0.5f);
  bias[3] = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  matrix[i] = bias * scene::textureProjection(p, t.width, t.height) *
              glm::inverse(view * p.projectorToWorld);
  location[i] = glm::vec3(view * p.projectorToWorld[3]);
  color[i] = p.color;
  intensity[i] = p.intensity;
  // A near or far distance given clips there; without one nothing is clipped on that side.
  depthRange[i] = {p.nearDistance < 0.0f ? 0.0f : -1.0f, p.farDistance < 0.0f ? 1.0f : 2.0f};
  texture[i] = t.id;
}

void uploadProjectors(const ProjectorUniformLocations& u, const ShapeProjectors& s) {
  if (u.count < 0) return;
  glUniform1i(u.count, s.count);
  if (s.count == 0) return;
  glUniformMatrix4fv(u.matrix, s.count, GL_FALSE, glm::value_ptr(s.matrix[0]));
  glUniform3fv(u.location, s.count, glm::value_ptr(s.location[0]));
  glUniform3fv(u.color, s.count, glm::value_ptr(s.color[0]));
  glUniform1fv(u.intensity, s.count, s.intensity.data());
  glUniform2fv(u.depthRange, s.count, glm::value_ptr(s.depthRange[0]));
  for (int i = 0; i < s.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    glUniform1i(u.texture[k], kFirstProjectorUnit + i);
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kFirstProjectorUnit + i));
    glBindTexture(GL_TEXTURE_2D, s.texture[k]);
  }
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace gs::render::detail
