// Private to particles/: the simulation's random numbers, the same on every machine.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace gs::particles {

/// splitmix64 (Steele, Lea and Flood 2014): 64 bits of state, full period, no platform
/// dependence (std::uniform_real_distribution's results differ between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
  /// Uniform in [a, b).
  float uniform(float a, float b) { return a + (b - a) * uniform(); }
  /// A unit vector uniform on the sphere (X_ITE's getRandomNormal).
  glm::vec3 unitVector() {
    const float theta = uniform(-3.14159265f, 3.14159265f);
    const float c = uniform(-1.0f, 1.0f);
    const float r = std::sqrt(std::max(0.0f, 1.0f - c * c));
    return {std::sin(theta) * r, std::cos(theta) * r, c};
  }
  /// A unit vector uniform over the spherical cap of half-angle `angle` (radians) around
  /// unit `axis` (a zero axis: +Z).
  glm::vec3 unitVectorInCone(const glm::vec3& axis, float angle);

 private:
  std::uint64_t state_;
};

}  // namespace gs::particles
