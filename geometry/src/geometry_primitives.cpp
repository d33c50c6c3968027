// The solid primitives: Box (6.4), Cone (6.11), Cylinder (6.15), Sphere (6.43), centred
// on the origin, kRoundSegments around the Y axis. Curved surfaces get smooth normals,
// flat faces and caps flat ones; texture coordinates follow each node's clause. X3D's
// `solid` field (X3D 4.0 clause 13, Geometry3D) is honoured; VRML97 nodes are always solid.
//
// Around the Y axis, angle a (0..2pi) is the point (-sin a, 0, -cos a): it starts at the
// back (-Z) and turns counterclockwise seen from above (+Y), and s = a / 2pi, as the spec
// asks of the side textures of Cone, Cylinder and Sphere (seam in the X=0 plane, -Z half).
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

namespace gs::vrml::geometry_detail {

namespace {

constexpr int kSegments = kRoundSegments;
constexpr int kSphereRings = kRoundSegments / 2;  // latitude bands of the Sphere

/// Unit direction at angle index k of n (0 = -Z, counterclockwise seen from +Y).
glm::vec3 around(double k, int n) {
  const double a = 2.0 * std::numbers::pi * k / n;
  return {static_cast<float>(-std::sin(a)), 0.0f, static_cast<float>(-std::cos(a))};
}

/// X3D's `solid` field of the primitives (X3D 4.0 clause 13; default TRUE; VRML97 has none).
bool solidField(const Node& node) {
  return node.get<FieldType::SFBool>("solid", true);
}

/// Reads a size or radius that the spec requires to be > 0: negative or non-finite
/// values are reported and give false; zero gives false silently (nothing to draw).
bool positive(float v, const char* name, ProblemLog& log) {
  if (std::isfinite(v) && v >= 0.0f) return v > 0.0f;
  log.add(std::string(name) + " must be > 0, got " + std::to_string(v) + "; not drawn");
  return false;
}

/// Appends a flat disc cap at height y with normal +Y (up) or -Y, as a fan of kSegments
/// triangles around a centre vertex. Texture: a circle cut from the texture square, right
/// side up when the cap is turned to face +Z (top: tilted towards +Z, bottom: towards -Z).
void disc(MeshBuilder& b, float radius, float y, bool up) {
  const glm::vec3 n(0.0f, up ? 1.0f : -1.0f, 0.0f);
  const std::uint32_t centre = b.push({{0.0f, y, 0.0f}, n, {}, {0.5f, 0.5f}});
  std::uint32_t rim[kSegments + 1];
  for (int k = 0; k <= kSegments; ++k) {
    const glm::vec3 d = around(k % kSegments, kSegments);
    const glm::vec2 tc(0.5f + 0.5f * d.x, up ? 0.5f - 0.5f * d.z : 0.5f + 0.5f * d.z);
    rim[k] = k < kSegments ? b.push({d * radius + glm::vec3(0.0f, y, 0.0f), n, {}, tc}) : rim[0];
  }
  for (int k = 0; k < kSegments; ++k) {
    if (up)
      b.triangle(centre, rim[k], rim[k + 1]);  // counterclockwise seen from above
    else
      b.triangle(centre, rim[k + 1], rim[k]);
  }
}

}  // namespace

Mesh tessellateBox(const Node& node, ProblemLog& log) {
  const glm::vec3 size = node.get<FieldType::SFVec3f>("size", glm::vec3(2.0f));
  if (!positive(size.x, "size.x", log) || !positive(size.y, "size.y", log) ||
      !positive(size.z, "size.z", log))
    return {};
  const glm::vec3 h = size * 0.5f;
  // Per face: outward normal, and the directions of increasing s and t on it, with
  // s x t = normal. Each face's texture is right side up seen from outside; the top with
  // -Z towards the top of the image, the bottom with +Z (clause 6.4).
  struct Face {
    glm::vec3 n, s, t;
  };
  static constexpr Face kFaces[6] = {
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},    // front
      {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},  // back
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},   // right
      {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},   // left
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},   // top
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},   // bottom
  };
  // castle-engine's Box.ccw extension (X3D worlds only, docs/x3d.md): FALSE turns the
  // faces inside out, normals inward and triangles wound the other way; the texture
  // coordinates stay as they are.
  const bool outward = node.get<FieldType::SFBool>("ccw", true);
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve(24, 36);
  for (const Face& f : kFaces) {
    std::uint32_t v[4];
    const glm::vec3 normal = outward ? f.n : -f.n;
    for (int c = 0; c < 4; ++c) {
      const float ss = (c == 1 || c == 2) ? 1.0f : 0.0f, tt = (c >= 2) ? 1.0f : 0.0f;
      const glm::vec3 p = (f.n + f.s * (2.0f * ss - 1.0f) + f.t * (2.0f * tt - 1.0f)) * h;
      v[c] = b.push({p, normal, {}, {ss, tt}});
    }
    if (outward) {
      b.triangle(v[0], v[1], v[2]);
      b.triangle(v[0], v[2], v[3]);
    } else {
      b.triangle(v[0], v[2], v[1]);
      b.triangle(v[0], v[3], v[2]);
    }
  }
  return b.finish(solidField(node));
}

Mesh tessellateCylinder(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("radius", 1.0f);
  const float height = node.get<FieldType::SFFloat>("height", 2.0f);
  if (!positive(r, "radius", log) || !positive(height, "height", log)) return {};
  const float y = height * 0.5f;
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve(4 * (kSegments + 2), 12 * kSegments);
  if (node.get<FieldType::SFBool>("side", true)) {
    // Texture wraps counterclockwise from the back; t = 0 at the bottom, 1 at the top.
    std::uint32_t lower[kSegments + 1], upper[kSegments + 1];
    for (int k = 0; k <= kSegments; ++k) {
      const glm::vec3 d = around(k % kSegments, kSegments);
      const float s = static_cast<float>(k) / kSegments;
      lower[k] = b.push({d * r - glm::vec3(0.0f, y, 0.0f), d, {}, {s, 0.0f}});
      upper[k] = b.push({d * r + glm::vec3(0.0f, y, 0.0f), d, {}, {s, 1.0f}});
    }
    for (int k = 0; k < kSegments; ++k) {
      b.triangle(lower[k], lower[k + 1], upper[k + 1]);
      b.triangle(lower[k], upper[k + 1], upper[k]);
    }
  }
  if (node.get<FieldType::SFBool>("top", true)) disc(b, r, y, true);
  if (node.get<FieldType::SFBool>("bottom", true)) disc(b, r, -y, false);
  return b.finish(solidField(node));
}

Mesh tessellateCone(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("bottomRadius", 1.0f);
  const float height = node.get<FieldType::SFFloat>("height", 2.0f);
  if (!positive(r, "bottomRadius", log) || !positive(height, "height", log)) return {};
  const float y = height * 0.5f;
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve((kConeStacks + 1) * (kSegments + 1) + 1, 6 * kSegments * (kConeStacks + 1));
  if (node.get<FieldType::SFBool>("side", true)) {
    // Smooth side normal at angle a: perpendicular to the slant line, outward and up.
    auto sideNormal = [&](double k) {
      const glm::vec3 d = around(k, kSegments);
      return glm::normalize(d * height + glm::vec3(0.0f, r, 0.0f));
    };
    // kConeStacks rings up the side, each vertex with the normal of its angle alone, so
    // the normal varies smoothly around the cone (castle-model-viewer also uses stacks);
    // only the top stack meets the apex, with one apex vertex per slice carrying the
    // normal and s of the slice's middle.
    std::uint32_t ring[kSegments + 1], next[kSegments + 1];
    for (int j = 0; j < kConeStacks; ++j) {
      const float f = static_cast<float>(j) / kConeStacks;
      for (int k = 0; k <= kSegments; ++k) {
        const glm::vec3 d = around(k % kSegments, kSegments);
        next[k] = b.push({d * (r * (1.0f - f)) + glm::vec3(0.0f, -y + height * f, 0.0f),
                          sideNormal(k % kSegments),
                          {},
                          {static_cast<float>(k) / kSegments, f}});
      }
      if (j > 0)
        for (int k = 0; k < kSegments; ++k) {
          b.triangle(ring[k], ring[k + 1], next[k + 1]);
          b.triangle(ring[k], next[k + 1], next[k]);
        }
      std::copy(std::begin(next), std::end(next), std::begin(ring));
    }
    for (int k = 0; k < kSegments; ++k) {
      const float s = (static_cast<float>(k) + 0.5f) / kSegments;
      const std::uint32_t apex = b.push({{0.0f, y, 0.0f}, sideNormal(k + 0.5), {}, {s, 1.0f}});
      b.triangle(ring[k], ring[k + 1], apex);
    }
  }
  if (node.get<FieldType::SFBool>("bottom", true)) disc(b, r, -y, false);
  return b.finish(solidField(node));
}

Mesh tessellateSphere(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("radius", 1.0f);
  if (!positive(r, "radius", log)) return {};
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve((kSegments + 1) * (kSphereRings + 1), 6 * kSegments * kSphereRings);
  // Ring j is at polar angle pi * j / rings from +Y; t = 1 at the top, 0 at the bottom.
  // Each pole is one vertex per segment (s at the segment's middle), the other rings have
  // kSegments + 1 vertices so that the seam at the back has s = 0 and s = 1.
  std::vector<std::uint32_t> prev(kSegments + 1), cur(kSegments + 1);
  for (int j = 0; j <= kSphereRings; ++j) {
    const double polar = std::numbers::pi * j / kSphereRings;
    const float ringY = static_cast<float>(std::cos(polar));
    const float ringR = static_cast<float>(std::sin(polar));
    const float t = 1.0f - static_cast<float>(j) / kSphereRings;
    const bool pole = (j == 0 || j == kSphereRings);
    for (int k = 0; k <= kSegments; ++k) {
      if (pole && k == kSegments) break;
      const double at = pole ? k + 0.5 : k;
      const glm::vec3 n = pole ? glm::vec3(0.0f, ringY, 0.0f)
                               : around(at, kSegments) * ringR + glm::vec3(0, ringY, 0);
      cur[k] = b.push({n * r, n, {}, {static_cast<float>(at / kSegments), t}});
    }
    if (j > 0) {
      for (int k = 0; k < kSegments; ++k) {  // prev = ring above, cur = ring below
        if (j == 1)
          b.triangle(cur[k], cur[k + 1], prev[k]);
        else if (j == kSphereRings)
          b.triangle(cur[k], prev[k + 1], prev[k]);
        else {
          b.triangle(cur[k], cur[k + 1], prev[k + 1]);
          b.triangle(cur[k], prev[k + 1], prev[k]);
        }
      }
    }
    std::swap(prev, cur);
  }
  return b.finish(solidField(node));
}

}  // namespace gs::vrml::geometry_detail
