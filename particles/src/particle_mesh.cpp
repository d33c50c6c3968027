#include "particles/particle_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gs::particles {

using vrml::FieldType;

glm::vec4 rampColor(const std::vector<float>& keys, const std::vector<glm::vec4>& colors, float f) {
  if (keys.empty() || colors.empty()) return glm::vec4(1.0f);
  const auto color = [&](std::size_t k) { return colors[k % colors.size()]; };
  if (keys.size() == 1 || f <= keys.front()) return color(0);
  if (f >= keys.back()) return color(keys.size() - 1);
  const auto i =
      static_cast<std::size_t>(std::upper_bound(keys.begin(), keys.end(), f) - keys.begin());
  const float span = keys[i] - keys[i - 1];
  const float w = span > 0.0f ? std::clamp((f - keys[i - 1]) / span, 0.0f, 1.0f) : 1.0f;
  return glm::mix(color(i - 1), color(i), w);
}

std::vector<glm::vec4> rampColors(const vrml::Node& system) {
  std::vector<glm::vec4> out;
  const vrml::NodePtr& node = system.sfnode("color");
  if (!node || node->unresolved) return out;
  const vrml::FieldValue* c = node->field("color");
  if (c == nullptr) return out;
  if (c->type() == FieldType::MFColor) {
    for (const glm::vec3& rgb : c->get<FieldType::MFColor>()) out.emplace_back(rgb, 1.0f);
  } else if (c->type() == FieldType::MFColorRGBA) {
    out = c->get<FieldType::MFColorRGBA>();
  }
  return out;
}

std::size_t rampTexCoordSet(const std::vector<float>& keys, float f) {
  if (keys.size() < 2 || f <= keys.front()) return 0;
  if (f >= keys.back()) return keys.size() - 2;
  return static_cast<std::size_t>(std::upper_bound(keys.begin(), keys.end(), f) - keys.begin()) - 1;
}

namespace {

const std::vector<float>& mfFloat(const vrml::Node& n, vrml::FieldName name) {
  static const std::vector<float> kNone;
  const vrml::FieldValue* f = n.field(name);
  return f && f->type() == FieldType::MFFloat ? f->get<FieldType::MFFloat>() : kNone;
}

const std::vector<glm::vec2>& rampTexCoords(const vrml::Node& system) {
  static const std::vector<glm::vec2> kNone;
  const vrml::NodePtr& node = system.sfnode("texCoord");
  if (!node || node->unresolved) return kNone;
  const vrml::FieldValue* p = node->field("point");
  return p && p->type() == FieldType::MFVec2f ? p->get<FieldType::MFVec2f>() : kNone;
}

}  // namespace

vrml::Mesh particleMesh(const vrml::Node& system, GeometryType type,
                        const std::vector<Particle>& particles, const glm::mat3& eyeToLocal) {
  vrml::Mesh mesh;
  const glm::vec2 size = system.get<FieldType::SFVec2f>("particleSize", glm::vec2(0.02f));
  const std::vector<float>& colorKeys = mfFloat(system, "colorKey");
  const std::vector<glm::vec4> colors =
      colorKeys.empty() ? std::vector<glm::vec4>{} : rampColors(system);
  const bool colored = !colorKeys.empty() && !colors.empty();
  const std::vector<float>& texKeys = mfFloat(system, "texCoordKey");
  const std::vector<glm::vec2>& texPoints = rampTexCoords(system);
  const bool texRamp = !texKeys.empty() && !texPoints.empty();

  std::size_t visible = 0;
  for (const Particle& p : particles) visible += p.visible ? 1 : 0;
  std::size_t perParticle = 1;
  switch (type) {
    case GeometryType::point:
      mesh.primitive = vrml::Primitive::points;
      break;
    case GeometryType::line:
      mesh.primitive = vrml::Primitive::lines;
      perParticle = 2;
      break;
    default:
      perParticle = 4;
      break;
  }
  mesh.solid = type != GeometryType::point && type != GeometryType::line;
  mesh.positions.reserve(visible * perParticle);
  if (colored) mesh.colors.reserve(visible * perParticle);
  if (perParticle == 4) {
    mesh.normals.reserve(visible * 4);
    mesh.texCoords.reserve(visible * 4);
    mesh.indices.reserve(visible * 6);
  } else {
    mesh.indices.reserve(visible * perParticle);
  }

  // The rectangle's axes: local X and Y (QUAD, TRIANGLE) or the viewer's (SPRITE).
  glm::vec3 xAxis{1, 0, 0}, yAxis{0, 1, 0}, normal{0, 0, 1};
  if (type == GeometryType::sprite) {
    const glm::vec3 z = glm::normalize(eyeToLocal[2]);
    const glm::vec3 x = glm::normalize(glm::cross(eyeToLocal[1], z));
    if (std::isfinite(x.x + x.y + x.z) && std::isfinite(z.x + z.y + z.z)) {
      xAxis = x;
      yAxis = glm::normalize(glm::cross(z, x));
      normal = z;
    }
  }
  static constexpr std::array<glm::vec2, 4> kCorners{glm::vec2{-0.5f, -0.5f},
                                                     glm::vec2{0.5f, -0.5f}, glm::vec2{0.5f, 0.5f},
                                                     glm::vec2{-0.5f, 0.5f}};
  static constexpr std::array<glm::vec2, 4> kWhole{glm::vec2{0, 0}, glm::vec2{1, 0},
                                                   glm::vec2{1, 1}, glm::vec2{0, 1}};

  for (const Particle& p : particles) {
    if (!p.visible) continue;
    const float f = p.ageFraction();
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    if (type == GeometryType::point) {
      mesh.positions.push_back(p.position);
      mesh.indices.push_back(base);
    } else if (type == GeometryType::line) {
      const float speed = glm::length(p.velocity);
      const glm::vec3 d = speed > 0.0f ? p.velocity / speed : glm::vec3(0, 0, 1);
      mesh.positions.push_back(p.position - d * (size.y * 0.5f));
      mesh.positions.push_back(p.position + d * (size.y * 0.5f));
      mesh.indices.push_back(base);
      mesh.indices.push_back(base + 1);
    } else {
      const std::size_t set = texRamp ? rampTexCoordSet(texKeys, f) : 0;
      for (std::size_t k = 0; k < 4; ++k) {
        mesh.positions.push_back(p.position + xAxis * (kCorners[k].x * size.x) +
                                 yAxis * (kCorners[k].y * size.y));
        mesh.normals.push_back(normal);
        const std::size_t t = set * 4 + k;
        mesh.texCoords.push_back(texRamp ? texPoints[t % texPoints.size()] : kWhole[k]);
      }
      for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    }
    if (colored) {
      const glm::vec4 c = rampColor(colorKeys, colors, f);
      mesh.colors.insert(mesh.colors.end(), mesh.positions.size() - base, c);
    }
  }
  for (const glm::vec3& v : mesh.positions) mesh.bounds.extend(v);
  return mesh;
}

}  // namespace gs::particles
