// Shared by tests/splats/test_lod_tree.cpp and tests/bench/bench_lod_tree.cpp: a camera
// looking at the synthetic clouds' box [-0.5, 0.5]^3, its cut view, and the opacity a
// cloud's projected footprints carry (the figure the level-of-detail tree keeps).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "splats/lod_tree.hpp"

namespace gs::test {

/// A uniformly random unit quaternion.
inline glm::quat randomRotation(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::quat(g(rng), g(rng), g(rng), g(rng)));
}

struct LodTestView {
  splats::CutView cut;
  glm::mat4 view{1.0f};
  float focal = 1.0f;  // pixels
  int pixels = 0;
};

/// A camera at `distance` x the box's diagonal from the centre of the box [-0.5, 0.5]^3
/// along `direction`, looking at it, `pixels` square, vertical field of view `fovY`
/// radians, the cut's pixel threshold `threshold`.
inline LodTestView lodViewAt(double distance, int pixels = 512, float fovY = glm::radians(60.0f),
                             float threshold = 1.0f, glm::vec3 direction = {0.3f, 0.4f, 0.866f}) {
  LodTestView out;
  const glm::vec3 eye = glm::normalize(direction) * static_cast<float>(distance) * std::sqrt(3.0f);
  out.view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  out.focal = 0.5f * static_cast<float>(pixels) / std::tan(0.5f * fovY);
  out.pixels = pixels;
  out.cut = splats::cutViewFromViewProjection(
      glm::perspective(fovY, 1.0f, 0.01f, 1000.0f) * out.view, eye, out.focal, threshold);
  return out;
}

/// The sum over a cloud of opacity x the integral of its projected footprint, 2 pi
/// sqrt(det Sigma'), pixels^2: the EWA projection J W Sigma W^T J^T without the
/// rasterizer's 0.3-pixel low-pass, for splats in front of the camera.
inline double projectedCoverage(const splats::GaussianCloud& cloud, const LodTestView& view) {
  const glm::dmat3 w(view.view);
  double sum = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const glm::dvec3 t = glm::dvec3(view.view * glm::vec4(cloud.positions[i], 1.0f));
    const double z = -t.z;
    if (!(z > 0.0)) continue;
    const double f = view.focal;
    const glm::dvec3 j0(f / z, 0.0, f * t.x / (z * z));  // d/d(eye x, y, eye z)
    const glm::dvec3 j1(0.0, f / z, f * t.y / (z * z));
    const glm::dmat3 sigma =
        w * glm::dmat3(splats::covariance(cloud.scales[i], cloud.rotations[i])) * glm::transpose(w);
    const double a = glm::dot(j0, sigma * j0), b = glm::dot(j0, sigma * j1),
                 c = glm::dot(j1, sigma * j1);
    sum += cloud.opacities[i] * 2.0 * std::numbers::pi * std::sqrt(std::max(a * c - b * b, 0.0));
  }
  return sum;
}

}  // namespace gs::test
