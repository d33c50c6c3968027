#include "triangles.hpp"

#include "geometry/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs::particles {

glm::vec3 Random::unitVectorInCone(const glm::vec3& axis, float angle) {
  // X_ITE's getRandomNormalWithAngle: cos(polar angle) uniform in [cos angle, 1] around +Z,
  // then the rotation taking +Z onto the axis.
  const float theta = uniform(-3.14159265f, 3.14159265f);
  const float c = uniform(std::cos(angle), 1.0f);
  const float r = std::sqrt(std::max(0.0f, 1.0f - c * c));
  const glm::vec3 v{std::sin(theta) * r, std::cos(theta) * r, c};
  const float length = glm::length(axis);
  if (!(length > 0.0f)) return v;
  const glm::vec3 z = axis / length;
  if (z.z < -0.999999f) return {-v.x, v.y, -v.z};  // 180 degrees about Y
  // Rodrigues' rotation of +Z onto z: axis (+Z x z), cos = z.z.
  const glm::vec3 k{-z.y, z.x, 0.0f};
  const float cosA = z.z;
  return v * cosA + glm::cross(k, v) + k * (glm::dot(k, v) / (1.0f + cosA));
}

bool Triangles::assign(const vrml::Mesh& mesh, float normalScale, std::size_t maxTriangles) {
  triangles_.clear();
  const std::size_t count =
      mesh.primitive == vrml::Primitive::triangles ? mesh.indices.size() / 3 : 0;
  if (count > maxTriangles) {
    build();
    return false;
  }
  triangles_.reserve(count);
  for (std::size_t t = 0; t < count; ++t) {
    Triangle tri;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = mesh.indices[t * 3 + static_cast<std::size_t>(k)];
      if (i >= mesh.positions.size()) {
        ok = false;
        break;
      }
      tri.p[k] = mesh.positions[i];
      tri.n[k] = (i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f)) * normalScale;
    }
    if (!ok) continue;
    if (mesh.normals.empty()) {  // the face normal
      const glm::vec3 f = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
      const float l = glm::length(f);
      for (glm::vec3& n : tri.n) n = l > 0.0f ? f / l * normalScale : glm::vec3(0.0f);
    }
    triangles_.push_back(tri);
  }
  build();
  return true;
}

void Triangles::append(const Triangles& other) {
  triangles_.insert(triangles_.end(), other.triangles_.begin(), other.triangles_.end());
  build();
}

void Triangles::build() {
  cumulativeArea_.resize(triangles_.size());
  float sum = 0.0f;
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    const float area = 0.5f * glm::length(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
    sum += std::isfinite(area) ? area : 0.0f;
    cumulativeArea_[i] = sum;
  }
  nodes_.clear();
  if (!triangles_.empty()) buildNode(0, static_cast<std::uint32_t>(triangles_.size()), 0);
}

std::uint32_t Triangles::buildNode(std::uint32_t first, std::uint32_t count, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  for (std::uint32_t i = first; i < first + count; ++i)
    for (const glm::vec3& p : triangles_[i].p) node.box.extend(p);
  if (count <= 4 || depth >= 40) {
    node.first = first;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  // Median split along the longest axis of the box (by triangle centroid).
  const glm::vec3 extent = node.box.size();
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const auto begin = triangles_.begin() + first;
  const auto middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [axis](const Triangle& a, const Triangle& b) {
    return a.p[0][axis] + a.p[1][axis] + a.p[2][axis] < b.p[0][axis] + b.p[1][axis] + b.p[2][axis];
  });
  node.left = buildNode(first, count / 2, depth + 1);
  node.right = buildNode(first + count / 2, count - count / 2, depth + 1);
  nodes_[index] = node;
  return index;
}

bool Triangles::sample(Random& random, glm::vec3& point, glm::vec3& normal) const {
  if (triangles_.empty() || !(cumulativeArea_.back() > 0.0f)) return false;
  const float f = random.uniform() * cumulativeArea_.back();
  auto it = std::upper_bound(cumulativeArea_.begin(), cumulativeArea_.end(), f);
  if (it == cumulativeArea_.end()) --it;
  const Triangle& t = triangles_[static_cast<std::size_t>(it - cumulativeArea_.begin())];
  float u = random.uniform(), v = random.uniform();
  if (u + v > 1.0f) {
    u = 1.0f - u;
    v = 1.0f - v;
  }
  const float w = 1.0f - u - v;
  point = v * t.p[0] + w * t.p[1] + u * t.p[2];
  const glm::vec3 n = v * t.n[0] + w * t.n[1] + u * t.n[2];
  const float l = glm::length(n);
  normal = l > 0.0f ? n / l : glm::vec3(0.0f, 0.0f, 1.0f);
  return true;
}

void Triangles::intersectLine(
    const glm::vec3& origin, const glm::vec3& dir, std::size_t& budget,
    const std::function<void(float, const glm::vec3&, const glm::vec3&)>& visit) const {
  if (nodes_.empty()) return;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!vrml::lineMeetsBox(origin, dir, node.box, -std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::infinity()))
      continue;
    if (node.count == 0) {
      if (top + 2 > 64) continue;  // (depth is limited to 40: never)
      stack[top++] = node.left;
      stack[top++] = node.right;
      continue;
    }
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
      if (budget == 0) return;
      --budget;
      const Triangle& tri = triangles_[i];
      float t = 0.0f, u = 0.0f, v = 0.0f;  // both faces, any t
      if (!vrml::lineTriangle(origin, dir, tri.p[0], tri.p[1], tri.p[2], t, u, v)) continue;
      visit(t, origin + t * dir, (1.0f - u - v) * tri.n[0] + u * tri.n[1] + v * tri.n[2]);
    }
  }
}

}  // namespace gs::particles
