// Lines against triangles and boxes: the intersection tests that picking (scene/), the
// pick sensors (runtime/) and particle emitters and bounds (particles/) share. Pure math,
// any units.
#pragma once

#include "geometry/geometry.hpp"

#include <glm/glm.hpp>

namespace gs::vrml {

/// Möller-Trumbore: whether the line origin + t direction meets triangle (a, b, c), either
/// face, for any t; then t and the barycentric (u, v) of b and c (the point is a + u (b - a)
/// + v (c - a)). False when it misses, or when the line is parallel to the triangle or the
/// triangle degenerate (|det| < 1e-20). `direction` need not be unit length.
bool lineTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& a,
                  const glm::vec3& b, const glm::vec3& c, float& t, float& u, float& v);

/// Slab test: whether origin + t direction lies in `box` for some t in [tMin, tMax] (an
/// empty box: never). Infinite bounds give the infinite line.
bool lineMeetsBox(const glm::vec3& origin, const glm::vec3& direction, const Bounds& box,
                  float tMin, float tMax);

}  // namespace gs::vrml
