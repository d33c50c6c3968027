// Acoustic surfaces on the direct path (X3D 4.0 clause 12.4.1 AcousticProperties).
#include "audio/acoustics.hpp"

#include "geometry/intersect.hpp"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace gs::audio {

namespace {

/// Crossings closer than this along the segment (a fraction of its length) are one: the
/// triangles that share the edge or corner the path goes through.
constexpr float kSameCrossing = 1e-5f;

}  // namespace

bool acousticSurfaceOf(const vrml::Node& shape, const glm::mat4& world, AcousticSurface& out) {
  using vrml::FieldType;
  const vrml::NodePtr geometry = shape.sfnode("geometry");
  const vrml::NodePtr appearance = shape.sfnode("appearance");
  if (!geometry || !appearance) return false;
  const vrml::NodePtr acoustics = appearance->sfnode("acousticProperties");
  if (!acoustics || acoustics->typeId() != vrml::NodeTypeId::AcousticProperties) return false;
  if (!acoustics->get<FieldType::SFBool>("enabled", true)) return false;
  const float refraction = acoustics->get<FieldType::SFFloat>("refraction", 0.0f);
  out.geometry = geometry.get();
  out.world = world;
  out.refraction = std::isnan(refraction) ? 0.0f : std::clamp(refraction, 0.0f, 1.0f);
  return true;
}

void AcousticOcclusion::setSurfaces(std::vector<AcousticSurface> surfaces) {
  surfaces_ = std::move(surfaces);
  std::unordered_set<const vrml::Node*> met;
  for (const AcousticSurface& s : surfaces_) {
    met.insert(s.geometry);
    const std::uint64_t revision = vrml::revisionWithFields(*s.geometry);
    auto [it, added] = meshes_.try_emplace(s.geometry);
    if (added || it->second.first != revision)
      it->second = {revision, vrml::tessellate(*s.geometry)};
  }
  std::erase_if(meshes_, [&](const auto& m) { return !met.contains(m.first); });
}

float AcousticOcclusion::transmission(const glm::vec3& from, const glm::vec3& to) const {
  float kept = 1.0f;
  std::vector<float> crossings;  // t of each triangle met between the two points
  for (const AcousticSurface& s : surfaces_) {
    const auto it = meshes_.find(s.geometry);
    if (it == meshes_.end()) continue;
    const vrml::Mesh& mesh = it->second.second;
    if (mesh.primitive != vrml::Primitive::triangles || mesh.indices.size() < 3) continue;
    // The segment in the geometry's coordinates: t in (0, 1) between the two points.
    const glm::mat4 toLocal = glm::inverse(s.world);
    const glm::vec3 a(toLocal * glm::vec4(from, 1.0f));
    const glm::vec3 d = glm::vec3(toLocal * glm::vec4(to, 1.0f)) - a;
    if (!vrml::lineMeetsBox(a, d, mesh.bounds, 0.0f, 1.0f)) continue;
    crossings.clear();
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const std::uint32_t i0 = mesh.indices[i], i1 = mesh.indices[i + 1], i2 = mesh.indices[i + 2];
      if (std::max({i0, i1, i2}) >= mesh.positions.size()) continue;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      if (vrml::lineTriangle(a, d, mesh.positions[i0], mesh.positions[i1], mesh.positions[i2], t, u,
                             v) &&
          t > 0.0f && t < 1.0f)
        crossings.push_back(t);
    }
    // A path through an edge or corner meets every triangle there at one place: one crossing.
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t i = 0; i < crossings.size(); ++i)
      if (i == 0 || crossings[i] - crossings[i - 1] > kSameCrossing) kept *= s.refraction;
    if (kept == 0.0f) return 0.0f;
  }
  return kept;
}

}  // namespace gs::audio
