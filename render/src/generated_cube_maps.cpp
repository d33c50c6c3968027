#include "generated_cube_maps.hpp"

#include "scene/node_access.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>

namespace gs::render::detail {

const GpuTexture* GeneratedCubeMaps::texture(const vrml::Node& node) {
  Entry& e = entries_[&node];
  if (e.texture.id != 0) return &e.texture;
  e.size = std::clamp(scene::sfInt(node, "size", 128), 1, kMaxSize);
  glGenTextures(1, &e.texture.id);
  glBindTexture(GL_TEXTURE_CUBE_MAP, e.texture.id);
  for (int f = 0; f < 6; ++f)
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f), 0, GL_RGBA8, e.size,
                 e.size, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  // Black until drawn (the faces' texels are undefined until then).
  const std::vector<std::uint8_t> black(static_cast<std::size_t>(e.size) * e.size * 4, 0);
  for (int f = 0; f < 6; ++f)
    glTexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f), 0, 0, 0, e.size,
                    e.size, GL_RGBA, GL_UNSIGNED_BYTE, black.data());
  glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  e.texture.components = 3;
  e.texture.cube = true;
  return &e.texture;
}

bool GeneratedCubeMaps::due(const vrml::Node& node) const {
  const std::string& update = scene::sfString(node, "update");
  if (update == "ALWAYS") return true;
  if (update != "NEXT_FRAME_ONLY") return false;
  const auto it = entries_.find(&node);
  return it == entries_.end() || !it->second.drawn ||
         it->second.drawnRevision != vrml::revisionWithFields(node);
}

int GeneratedCubeMaps::bindFace(const vrml::Node& node, int face) {
  texture(node);
  Entry& e = entries_[&node];
  if (e.framebuffer == 0) {
    glGenFramebuffers(1, &e.framebuffer);
    glGenRenderbuffers(1, &e.depth);
    glBindRenderbuffer(GL_RENDERBUFFER, e.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, e.size, e.size);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, e.framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                         GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(face), e.texture.id,
                         0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, e.depth);
  return e.size;
}

void GeneratedCubeMaps::finish(const vrml::Node& node) {
  Entry& e = entries_[&node];
  glBindTexture(GL_TEXTURE_CUBE_MAP, e.texture.id);
  glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  e.drawn = true;
  e.drawnRevision = vrml::revisionWithFields(node);
}

void GeneratedCubeMaps::release() {
  for (auto& [node, e] : entries_) {
    if (e.texture.id != 0) glDeleteTextures(1, &e.texture.id);
    if (e.framebuffer != 0) glDeleteFramebuffers(1, &e.framebuffer);
    if (e.depth != 0) glDeleteRenderbuffers(1, &e.depth);
  }
  entries_.clear();
}

scene::Camera GeneratedCubeMaps::faceCamera(glm::vec3 position, int face, float nearClip,
                                            float farClip) {
  // GL's cube map faces (OpenGL 4.5 core, 8.13): the direction each looks along and its
  // up, which runs towards the face's t = 0 (the layout of table 8.19).
  static const std::array<std::pair<glm::vec3, glm::vec3>, 6> kFaces = {{
      {{1, 0, 0}, {0, -1, 0}},
      {{-1, 0, 0}, {0, -1, 0}},
      {{0, 1, 0}, {0, 0, 1}},
      {{0, -1, 0}, {0, 0, -1}},
      {{0, 0, 1}, {0, -1, 0}},
      {{0, 0, -1}, {0, -1, 0}},
  }};
  const auto& [look, up] = kFaces[static_cast<std::size_t>(face)];
  scene::Camera c;
  c.position = position;
  c.orientation = glm::quatLookAtRH(look, up);  // -Z onto `look`, +Y onto `up`
  c.fieldOfView = glm::radians(90.0f);
  c.nearClip = nearClip;
  c.farClip = farClip;
  return c;
}

}  // namespace gs::render::detail
