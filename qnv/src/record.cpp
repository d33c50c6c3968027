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

namespace {

// Cell boundaries as cosines and sines: theta >= k pi / 32 exactly when z <= cos(k pi / 32),
// and inside a quadrant the azimuth is >= k pi / 32 exactly when
// v cos(k pi / 32) - u sin(k pi / 32) >= 0. Comparisons instead of acos and atan2 make
// encoding three times faster and give the same cells (but on boundaries, where the two
// roundings may differ by one cell, which stays within the error bound).
struct DirectionTables {
  double cosTheta[kThetaSteps];
  double cosPhi[kPhiSteps / 4], sinPhi[kPhiSteps / 4];
  DirectionTables() {
    for (std::uint32_t k = 0; k < kThetaSteps; ++k)
      cosTheta[k] = std::cos(k * std::numbers::pi / kThetaSteps);
    for (std::uint32_t k = 0; k < kPhiSteps / 4; ++k) {
      cosPhi[k] = std::cos(k * 2.0 * std::numbers::pi / kPhiSteps);
      sinPhi[k] = std::sin(k * 2.0 * std::numbers::pi / kPhiSteps);
    }
  }
};

const DirectionTables& directionTables() {
  static const DirectionTables tables;
  return tables;
}

}  // namespace

void quantizeDirection(const glm::vec3& d, std::uint8_t& theta, std::uint8_t& phi) {
  const double x = d.x, y = d.y, z = d.z;
  const double len = std::sqrt(x * x + y * y + z * z);
  theta = 0;
  phi = 0;
  if (!(len > 0.0) || !std::isfinite(len)) return;
  const DirectionTables& t = directionTables();
  // theta: the number of k in 1..31 with z / len <= cos(k pi / 32). Counting instead of a
  // binary search avoids mispredicted branches (the loops vectorize).
  const double c = z / len;
  std::uint32_t polar = 0;
  for (std::uint32_t k = 1; k < kThetaSteps; ++k) polar += c <= t.cosTheta[k] ? 1u : 0u;
  theta = static_cast<std::uint8_t>(polar);
  if (x == 0.0 && y == 0.0) return;
  // phi: the quadrant from the signs, then rotate into [0, pi/2) and count 15 sectors.
  const bool upper = y > 0.0 || (y == 0.0 && x > 0.0);    // azimuth in [0, pi)
  const double x2 = upper ? x : -x, y2 = upper ? y : -y;  // rotated by pi when lower
  const bool left = x2 <= 0.0;                            // azimuth in [pi/2, pi)
  const double u = left ? y2 : x2, v = left ? -x2 : y2;
  const std::uint32_t quadrant = (upper ? 0u : 2u) + (left ? 1u : 0u);
  std::uint32_t sector = 0;
  for (std::uint32_t k = 1; k < kPhiSteps / 4; ++k)
    sector += v * t.cosPhi[k] - u * t.sinPhi[k] >= 0.0 ? 1u : 0u;
  phi = static_cast<std::uint8_t>(quadrant * (kPhiSteps / 4) + sector);
}

glm::vec3 reconstructDirection(std::uint32_t theta, std::uint32_t phi) {
  const float polar = (static_cast<float>(theta % kThetaSteps) + 0.5f) * kPi / kThetaSteps;
  const float azimuth = (static_cast<float>(phi % kPhiSteps) + 0.5f) * 2.0f * kPi / kPhiSteps;
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
          std::cos(polar)};
}

MagnitudeQuantizer::MagnitudeQuantizer(MagnitudeMapping mapping, float lo, float hi)
    : mapping_(mapping), lo_(0.0), scale_(0.0) {
  if (!(hi > lo)) return;
  if (mapping == MagnitudeMapping::logarithmic) {
    if (!(lo > 0.0f)) return;
    lo_ = std::log(double{lo});
    scale_ = kMagnitudeSteps / std::log(double{hi} / lo);
  } else {
    lo_ = lo;
    scale_ = kMagnitudeSteps / (double{hi} - lo);
  }
}

std::uint16_t MagnitudeQuantizer::operator()(float a) const {
  if (scale_ == 0.0) return 0;
  double v = a;
  if (mapping_ == MagnitudeMapping::logarithmic) {
    if (!(a > 0.0f)) return 0;
    v = std::log(v);
  }
  return static_cast<std::uint16_t>(clampCell((v - lo_) * scale_, kMagnitudeSteps));
}

std::uint16_t quantizeMagnitude(float a, MagnitudeMapping mapping, float lo, float hi) {
  return MagnitudeQuantizer(mapping, lo, hi)(a);
}

float reconstructMagnitude(std::uint32_t q, MagnitudeMapping mapping, float lo, float hi) {
  if (!(hi > lo)) return lo;
  const double t = (static_cast<double>(q % kMagnitudeSteps) + 0.5) / kMagnitudeSteps;
  if (mapping == MagnitudeMapping::logarithmic && lo > 0.0f)
    return static_cast<float>(lo * std::pow(double{hi} / lo, t));
  return static_cast<float>(lo + t * (double{hi} - lo));
}

}  // namespace gs::qnv
