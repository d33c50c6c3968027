#include "geometry/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gs::vrml {

bool lineTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& a,
                  const glm::vec3& b, const glm::vec3& c, float& t, float& u, float& v) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  const glm::vec3 p = glm::cross(direction, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-20f) return false;  // parallel or degenerate
  const float inv = 1.0f / det;
  const glm::vec3 s = origin - a;
  u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(s, e1);
  v = glm::dot(direction, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  t = glm::dot(e2, q) * inv;
  return true;
}

bool lineMeetsBox(const glm::vec3& origin, const glm::vec3& direction, const Bounds& box,
                  float tMin, float tMax) {
  if (box.empty()) return false;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(direction[i]) < 1e-30f) {
      if (origin[i] < box.min[i] || origin[i] > box.max[i]) return false;
      continue;
    }
    float t0 = (box.min[i] - origin[i]) / direction[i];
    float t1 = (box.max[i] - origin[i]) / direction[i];
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
    if (tMin > tMax) return false;
  }
  return true;
}

}  // namespace gs::vrml
