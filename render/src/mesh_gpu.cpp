// Uploading tessellated meshes to GPU buffers.
#include "gpu_resources.hpp"

#include <algorithm>

#include <cstdint>

namespace gs::render::detail {

void GpuMesh::upload(const vrml::Mesh& mesh) {
  release();
  const std::size_t n = mesh.positions.size();
  primitive = mesh.primitive;
  solid = mesh.solid;
  bounds = mesh.bounds;
  triangles = mesh.triangleCount();
  hasNormals = mesh.primitive == vrml::Primitive::triangles && mesh.normals.size() == n;
  hasColors = mesh.colors.size() == n && n > 0;
  colorAlpha = hasColors && std::any_of(mesh.colors.begin(), mesh.colors.end(),
                                        [](const glm::vec4& c) { return c.w < 1.0f; });
  hasTexCoords = mesh.texCoords.size() == n && n > 0;
  hasTexCoords1 = hasTexCoords && mesh.texCoords1.size() == n;
  hasFogDepths = mesh.fogDepths.size() == n && n > 0;
  hasTexCoordsStrq = mesh.texCoordsStrq.size() == n && n > 0;
  indexed = !mesh.indices.empty();
  count = static_cast<GLsizei>(indexed ? mesh.indices.size() : n);
  if (!indexed && primitive == vrml::Primitive::triangles) triangles = n / 3;
  bool indicesValid = true;
  for (std::uint32_t i : mesh.indices)
    if (i >= n) {
      indicesValid = false;
      break;
    }
  if (n == 0 || count == 0 || !indicesValid) {
    count = 0;
    triangles = 0;
    return;
  }

  const std::size_t positionBytes = n * sizeof(glm::vec3);
  const std::size_t normalBytes = hasNormals ? n * sizeof(glm::vec3) : 0;
  const std::size_t colorBytes = hasColors ? n * sizeof(glm::vec4) : 0;
  const std::size_t texBytes = hasTexCoords ? n * sizeof(glm::vec2) : 0;
  const std::size_t tex1Bytes = hasTexCoords1 ? n * sizeof(glm::vec2) : 0;
  const std::size_t fogBytes = hasFogDepths ? n * sizeof(float) : 0;
  const std::size_t strqBytes = hasTexCoordsStrq ? n * sizeof(glm::vec4) : 0;
  std::size_t total =
      positionBytes + normalBytes + colorBytes + texBytes + tex1Bytes + fogBytes + strqBytes;
  attributes.clear();
  for (const vrml::VertexAttribute& a : mesh.attributes)
    if (a.components > 0 && a.values.size() == n * static_cast<std::size_t>(a.components)) {
      attributes.push_back({a.name, a.components, total});
      total += a.values.size() * sizeof(float);
    }

  // X_ITE's x3d_TexCoord0 (a vec4 in its custom shaders) reads the texture coordinates
  // the geometry has: (s, t, r, q) of a TextureCoordinate3D/4D, else (s, t, 0, 1).
  const std::size_t texOffset = positionBytes + normalBytes + colorBytes;
  if (hasTexCoordsStrq)
    attributes.push_back({"x3d_TexCoord0", 4, texOffset + texBytes + tex1Bytes + fogBytes});
  else if (hasTexCoords)
    attributes.push_back({"x3d_TexCoord0", 2, texOffset});

  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vertexBuffer);
  glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(total), nullptr, GL_STATIC_DRAW);
  std::size_t offset = 0;
  auto attribute = [&](GLuint location, GLint size, const void* data, std::size_t bytes) {
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                    data);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, 0,
                          reinterpret_cast<const void*>(offset));
    offset += bytes;
  };
  attribute(0, 3, mesh.positions.data(), positionBytes);
  if (hasNormals) attribute(1, 3, mesh.normals.data(), normalBytes);
  if (hasColors) attribute(2, 4, mesh.colors.data(), colorBytes);
  if (hasTexCoords) attribute(3, 2, mesh.texCoords.data(), texBytes);
  if (hasTexCoords1) attribute(4, 2, mesh.texCoords1.data(), tex1Bytes);
  if (hasFogDepths) attribute(5, 1, mesh.fogDepths.data(), fogBytes);
  if (hasTexCoordsStrq) attribute(6, 4, mesh.texCoordsStrq.data(), strqBytes);
  // The user attributes: uploaded here, pointed at by bindAttributes (their locations
  // are the program's).
  std::size_t next = 0;
  for (const vrml::VertexAttribute& a : mesh.attributes)
    if (next < attributes.size() && attributes[next].name == a.name &&
        a.values.size() == n * static_cast<std::size_t>(a.components))
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(attributes[next++].offset),
                      static_cast<GLsizeiptr>(a.values.size() * sizeof(float)), a.values.data());
  if (indexed) {
    glGenBuffers(1, &indexBuffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GpuMesh::draw() const {
  if (count == 0) return;
  // Arrays a mesh lacks read the generic attribute values (not VAO state: set each time).
  if (!hasNormals) glVertexAttrib3f(1, 0.0f, 0.0f, 1.0f);
  if (!hasColors) glVertexAttrib4f(2, 1.0f, 1.0f, 1.0f, 1.0f);
  if (!hasTexCoords) glVertexAttrib2f(3, 0.0f, 0.0f);
  if (!hasTexCoords1) glVertexAttrib2f(4, 0.0f, 0.0f);
  if (!hasFogDepths) glVertexAttrib1f(5, -1.0f);
  if (!hasTexCoordsStrq) glVertexAttrib4f(6, 0.0f, 0.0f, 0.0f, 0.0f);
  const GLenum mode = primitive == vrml::Primitive::triangles ? GL_TRIANGLES
                      : primitive == vrml::Primitive::lines   ? GL_LINES
                                                              : GL_POINTS;
  glBindVertexArray(vao);
  if (indexed)
    glDrawElements(mode, count, GL_UNSIGNED_INT, nullptr);
  else
    glDrawArrays(mode, 0, count);
  glBindVertexArray(0);
}

void GpuMesh::bindAttributes(const std::vector<ProgramAttribute>& wanted) const {
  if (count == 0 || wanted.empty()) return;
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
  for (const ProgramAttribute& w : wanted) {
    const auto it = std::find_if(attributes.begin(), attributes.end(),
                                 [&](const Attribute& a) { return a.name == w.name; });
    const bool vector = w.columns == 1 && it != attributes.end() && it->components <= 4;
    const bool matrix =
        w.columns > 1 && it != attributes.end() && it->components == w.columns * w.rows;
    for (int c = 0; c < w.columns; ++c) {
      const GLuint location = w.location + static_cast<GLuint>(c);
      if (!vector && !matrix) {
        glDisableVertexAttribArray(location);
        glVertexAttrib4f(location, 0.0f, 0.0f, 0.0f, 1.0f);
        continue;
      }
      const GLint size = vector ? it->components : w.rows;
      const std::size_t offset = it->offset + static_cast<std::size_t>(c * w.rows) * sizeof(float);
      glEnableVertexAttribArray(location);
      glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE,
                            static_cast<GLsizei>(it->components * sizeof(float)),
                            reinterpret_cast<const void*>(offset));
    }
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GpuMesh::release() {
  if (vao != 0) glDeleteVertexArrays(1, &vao);
  if (vertexBuffer != 0) glDeleteBuffers(1, &vertexBuffer);
  if (indexBuffer != 0) glDeleteBuffers(1, &indexBuffer);
  vao = vertexBuffer = indexBuffer = 0;
  count = 0;
  attributes.clear();
}

}  // namespace gs::render::detail
