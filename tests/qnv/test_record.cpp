// The record layout and quantization bounds of docs/qnv-format.md (paper figure 6).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "qnv/record.hpp"

using namespace gs::qnv;

TEST_CASE("record fields pack most significant first in figure 6 order", "[qnv][record]") {
  CHECK(packRecord({1023, 0, 0, 0, 0, 0, 0}) == 0xFFC0000000000000ull);
  CHECK(packRecord({0, 1023, 0, 0, 0, 0, 0}) == 0x003FF00000000000ull);
  CHECK(packRecord({0, 0, 1023, 0, 0, 0, 0}) == 0x00000FFC00000000ull);
  CHECK(packRecord({0, 0, 0, 31, 0, 0, 0}) == 0x00000003E0000000ull);
  CHECK(packRecord({0, 0, 0, 0, 63, 0, 0}) == 0x000000001F800000ull);
  CHECK(packRecord({0, 0, 0, 0, 0, 32767, 0}) == 0x00000000007FFF00ull);
  CHECK(packRecord({0, 0, 0, 0, 0, 0, 255}) == 0x00000000000000FFull);
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const std::uint64_t r = rng();
    CHECK(packRecord(unpackRecord(r)) == r);
  }
}

TEST_CASE("positions reconstruct within half a step per axis", "[qnv][record]") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-3.0f, 5.0f);
  const float lo = -3.0f, hi = 5.0f, halfStep = (hi - lo) / 1024 / 2;
  for (int i = 0; i < 100000; ++i) {
    const float v = u(rng);
    const std::uint16_t q = quantizeCoordinate(v, lo, hi);
    REQUIRE(q < 1024);
    REQUIRE(std::abs(reconstructCoordinate(q, lo, hi) - v) <= halfStep * 1.0001f);
  }
  CHECK(quantizeCoordinate(lo, lo, hi) == 0);
  CHECK(quantizeCoordinate(hi, lo, hi) == 1023);
  CHECK(quantizeCoordinate(std::nanf(""), lo, hi) == 0);
  CHECK(reconstructCoordinate(7, 2.0f, 2.0f) == 2.0f);  // a flat axis reconstructs exactly
}

TEST_CASE("directions reconstruct within the angular step", "[qnv][record]") {
  std::mt19937 rng(2);
  std::normal_distribution<float> n(0.0f, 1.0f);
  const double bound = std::acos(std::pow(std::cos(std::numbers::pi / 64), 2));  // 3.977 deg
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    std::uint8_t t = 0, p = 0;
    quantizeDirection(d, t, p);
    REQUIRE(t < 32);
    REQUIRE(p < 64);
    const glm::vec3 back = reconstructDirection(t, p);
    REQUIRE(std::abs(glm::length(back) - 1.0f) < 1e-5f);
    worst = std::max(worst, std::acos(std::clamp<double>(glm::dot(d, back), -1.0, 1.0)));
  }
  CHECK(worst <= bound + 1e-4);
  CHECK(worst > 0.9 * bound);            // the bound is tight, not loose
  CHECK(worst < std::numbers::pi / 32);  // under the 5.625 degree step
  std::uint8_t t = 0, p = 0;
  quantizeDirection({0, 0, -1}, t, p);
  CHECK(t == 31);
  quantizeDirection({0, -1, 0}, t, p);
  CHECK((t == 16 && p == 48));
}

TEST_CASE("logarithmic magnitudes keep a bounded relative error", "[qnv][record]") {
  const float lo = 1e-6f, hi = 1.0f;
  const double bound = std::pow(double{hi} / lo, 1.0 / 65536) - 1.0;  // 2.1e-4
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> e(std::log(lo), std::log(hi));
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const float a = static_cast<float>(std::exp(e(rng)));
    const float back =
        reconstructMagnitude(quantizeMagnitude(a, MagnitudeMapping::logarithmic, lo, hi),
                             MagnitudeMapping::logarithmic, lo, hi);
    worst = std::max(worst, static_cast<double>(std::abs(back - a) / a));
  }
  CHECK(worst <= bound * 1.01 + 1e-6);
  CHECK(worst > 0.5 * bound);
  // A linear mapping over the same range loses small magnitudes entirely.
  const float small = 2e-6f;
  const float linear = reconstructMagnitude(
      quantizeMagnitude(small, MagnitudeMapping::linear, lo, hi), MagnitudeMapping::linear, lo, hi);
  CHECK(std::abs(linear - small) / small > 1.0);
}

TEST_CASE("direction cells match the acos and atan2 definition", "[qnv][record]") {
  std::mt19937 rng(9);
  std::normal_distribution<float> n(0.0f, 1.0f);
  int differ = 0;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 d(n(rng), n(rng), n(rng));
    const double len = std::sqrt(double{d.x} * d.x + double{d.y} * d.y + double{d.z} * d.z);
    const int t = std::min(31, static_cast<int>(std::acos(d.z / len) / std::numbers::pi * 32));
    double phi = std::atan2(double{d.y}, double{d.x});
    if (phi < 0) phi += 2 * std::numbers::pi;
    const int p = static_cast<int>(phi / (2 * std::numbers::pi) * 64) % 64;
    std::uint8_t qt = 0, qp = 0;
    quantizeDirection(d, qt, qp);
    differ += (qt != t || qp != p);
  }
  CHECK(differ <= 2);  // only a rounding exactly on a cell boundary may differ
}
