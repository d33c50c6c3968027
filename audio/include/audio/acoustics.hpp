// Sound through the world's surfaces: X3D 4.0's AcousticProperties (ISO/IEC 19775-1:2023
// clause 12.4.1, Appearance.acousticProperties) on the direct path from a sound to the
// listener. A Shape whose Appearance holds an enabled AcousticProperties is an acoustic
// surface; each time the straight segment from a sound's location to the listener crosses
// one of its triangles, the sound keeps the `refraction` fraction of its intensity (the
// part that passes into the surface and on, the clause's refraction coefficient); the
// rest is absorbed or reflected away (absorption, specular, diffuse), and reflections are
// not traced. Shapes without AcousticProperties let sound through, as in X_ITE 15, which
// reads the node without using it (docs/media.md, "Acoustic surfaces").
#pragma once

#include "geometry/geometry.hpp"
#include "vrml/node.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs::audio {

/// A Shape met in the scene graph whose Appearance has an enabled AcousticProperties.
struct AcousticSurface {
  const vrml::Node* geometry = nullptr;  // the Shape's geometry node
  glm::mat4 world{1.0f};                 // geometry coordinates to world coordinates
  float refraction = 0.0f;               // the intensity fraction one crossing keeps, 0..1
};

/// The acoustic surface of `shape` (a Shape node) under `world`, when its Appearance holds
/// an AcousticProperties whose `enabled` is TRUE and it has a geometry; else false.
/// `refraction` is clamped to [0, 1] (NaN: 0).
bool acousticSurfaceOf(const vrml::Node& shape, const glm::mat4& world, AcousticSurface& out);

/// The surfaces of one frame and their tessellations (made again only when a geometry's
/// revisionWithFields changes).
class AcousticOcclusion {
 public:
  /// The surfaces of this frame, replacing the last frame's; their geometry nodes must
  /// stay alive until the next call. Tessellations of geometry no longer met are dropped.
  void setSurfaces(std::vector<AcousticSurface> surfaces);
  /// The fraction (0..1) of a sound's intensity that reaches `to` from `from` (world
  /// coordinates, metres) along the straight segment between them: the product of
  /// `refraction` over every crossing of a surface strictly between the two points (either
  /// face; the triangles met at one place, an edge or corner, are one crossing; 1 with no
  /// surface in the way). Points, lines and empty geometry are crossed nowhere. Time:
  /// linear in the triangles of the surfaces whose bounds the segment meets.
  float transmission(const glm::vec3& from, const glm::vec3& to) const;
  /// The surfaces set by the last setSurfaces().
  std::size_t surfaceCount() const { return surfaces_.size(); }

 private:
  std::vector<AcousticSurface> surfaces_;
  std::unordered_map<const vrml::Node*, std::pair<std::uint64_t, vrml::Mesh>> meshes_;
};

}  // namespace gs::audio
