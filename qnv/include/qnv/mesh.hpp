// A triangle mesh as the surface encoder consumes it (paper section 2.1: one vector per
// triangle). The readers of formats/ (PLY, OBJ, glTF) produce it; scene::worldTriangles
// builds it from VRML worlds.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace gs::qnv {

/// RGBA, 8 bits per channel, 0..255, not premultiplied.
using Rgba8 = glm::u8vec4;

/// Indexed triangles in one coordinate frame (world units; metres for VRML worlds).
/// Invariants that readers guarantee: indices.size() % 3 == 0 and every index is below
/// positions.size(); vertexColors is empty or has positions.size() entries;
/// faceColors is empty or has indices.size() / 3 entries. A triangle's colour is its
/// face colour, else the mean of its vertex colours, else baseColor.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;   // three per triangle, counter-clockwise front
  std::vector<Rgba8> vertexColors;      // optional, per vertex
  std::vector<Rgba8> faceColors;        // optional, per triangle
  Rgba8 baseColor{204, 204, 204, 255};  // VRML97 Material default diffuse 0.8

  std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace gs::qnv
