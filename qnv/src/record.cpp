#include "qnv/record.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace gs::qnv {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

std::uint32_t clampCell(double cell, std::uint32_t steps) {
  if (!(cell > 0.0)) return 0;  // also NaN
  if (cell >= static_cast<double>(steps)) return steps - 1;
  return static_cast<std::uint32_t>(cell);
}

}  // namespace

std::uint16_t quantizeCoordinate(float v, float lo, float hi) {
  if (!(hi > lo)) return 0;
  const double cell =
      (static_cast<double>(v) - lo) / (static_cast<double>(hi) - lo) * kPositionSteps;
  return static_cast<std::uint16_t>(clampCell(cell, kPositionSteps));
}

float reconstructCoordinate(std::uint32_t q, float lo, float hi) {
  if (!(hi > lo)) return lo;
  return lo + (static_cast<float>(q) + 0.5f) * ((hi - lo) / static_cast<float>(kPositionSteps));
}

void quantizeDirection(const glm::vec3& d, std::uint8_t& theta, std::uint8_t& phi) {
  const double len = std::sqrt(double{d.x} * d.x + double{d.y} * d.y + double{d.z} * d.z);
  theta = 0;
  phi = 0;
  if (!(len > 0.0) || !std::isfinite(len)) return;
  const double polar = std::acos(std::clamp(d.z / len, -1.0, 1.0));
  double azimuth = std::atan2(double{d.y}, double{d.x});
  if (azimuth < 0.0) azimuth += 2.0 * std::numbers::pi;
  theta = static_cast<std::uint8_t>(clampCell(polar / std::numbers::pi * kThetaSteps, kThetaSteps));
  // atan2 may return exactly 2 pi after the wrap; that is cell 0 again.
  phi = static_cast<std::uint8_t>(
      static_cast<std::uint32_t>(azimuth / (2.0 * std::numbers::pi) * kPhiSteps) % kPhiSteps);
}

glm::vec3 reconstructDirection(std::uint32_t theta, std::uint32_t phi) {
  const float polar = (static_cast<float>(theta % kThetaSteps) + 0.5f) * kPi / kThetaSteps;
  const float azimuth = (static_cast<float>(phi % kPhiSteps) + 0.5f) * 2.0f * kPi / kPhiSteps;
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
          std::cos(polar)};
}

std::uint16_t quantizeMagnitude(float a, MagnitudeMapping mapping, float lo, float hi) {
  if (!(hi > lo)) return 0;
  double t = 0.0;
  if (mapping == MagnitudeMapping::logarithmic) {
    if (!(a > 0.0f) || !(lo > 0.0f)) return 0;
    t = std::log(double{a} / lo) / std::log(double{hi} / lo);
  } else {
    t = (double{a} - lo) / (double{hi} - lo);
  }
  return static_cast<std::uint16_t>(clampCell(t * kMagnitudeSteps, kMagnitudeSteps));
}

float reconstructMagnitude(std::uint32_t q, MagnitudeMapping mapping, float lo, float hi) {
  if (!(hi > lo)) return lo;
  const double t = (static_cast<double>(q % kMagnitudeSteps) + 0.5) / kMagnitudeSteps;
  if (mapping == MagnitudeMapping::logarithmic && lo > 0.0f)
    return static_cast<float>(lo * std::pow(double{hi} / lo, t));
  return static_cast<float>(lo + t * (double{hi} - lo));
}

}  // namespace gs::qnv
