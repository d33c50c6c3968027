// 6.42's attenuation model at chosen listener positions, the values worked out by hand
// (docs/media.md): between the ellipsoids the loudness falls linearly in dB, so a point
// halfway (in distance from the focus, along its ray) is at -10 dB, a gain of
// 10^(-10/20) = 0.316228.
#include "audio/sound_model.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace gs::audio;

TEST_CASE("Sound: the ellipsoid radius about the focus", "[audio][sound]") {
  CHECK(ellipsoidRadius(10.0f, 5.0f, 1.0f) == Approx(10.0f));           // ahead: maxFront
  CHECK(ellipsoidRadius(10.0f, 5.0f, -1.0f) == Approx(5.0f));           // behind: maxBack
  CHECK(ellipsoidRadius(10.0f, 5.0f, 0.0f) == Approx(100.0f / 15.0f));  // 2fb / (f + b)
  CHECK(ellipsoidRadius(10.0f, 5.0f, 0.5f) == Approx(8.0f));            // 100 / (15 - 2.5)
  CHECK(ellipsoidRadius(3.0f, 3.0f, 0.3f) == Approx(3.0f));             // equal: a sphere
  CHECK(ellipsoidRadius(0.0f, 3.0f, 0.3f) == 0.0f);
}

TEST_CASE("Sound: the default spheres (1 m and 10 m)", "[audio][sound]") {
  const SoundGeometry g;  // min 1, max 10 both ways: spheres
  CHECK(soundGain(g, 1.0f, {0.0f, 0.0f, 0.0f}) == 1.0f);
  CHECK(soundGain(g, 1.0f, {0.0f, 0.8f, 0.0f}) == 1.0f);              // inside the inner
  CHECK(soundGain(g, 1.0f, {5.5f, 0.0f, 0.0f}) == Approx(0.316228));  // halfway: -10 dB
  CHECK(soundGain(g, 1.0f, {0.0f, 0.0f, -10.0f}) == Approx(0.1));     // outer surface: -20 dB
  CHECK(soundGain(g, 1.0f, {0.0f, 10.01f, 0.0f}) == 0.0f);            // outside: silent
  float db = 1.0f;
  REQUIRE(attenuationDb(g, {3.25f, 0.0f, 0.0f}, db));
  CHECK(db == Approx(-5.0f));  // a quarter of the way
}

TEST_CASE("Sound: an asymmetric pair of ellipsoids at 10 listener positions", "[audio][sound]") {
  SoundGeometry g;
  g.minFront = 2.0f;
  g.minBack = 1.0f;
  g.maxFront = 10.0f;
  g.maxBack = 5.0f;
  g.location = {1.0f, 2.0f, 3.0f};
  g.direction = {0.0f, 0.0f, 4.0f};  // +Z, not unit length
  const glm::vec3 o = g.location;
  struct Case {
    glm::vec3 at;
    double gain;
  };
  const Case cases[] = {
      {o + glm::vec3(0, 0, 2), 1.0},        // on the inner surface ahead: 0 dB
      {o + glm::vec3(0, 0, 6), 0.316228},   // ahead, halfway from 2 to 10: -10 dB
      {o + glm::vec3(0, 0, 10), 0.1},       // the outer surface ahead: -20 dB
      {o + glm::vec3(0, 0, 10.5), 0.0},     // beyond it
      {o + glm::vec3(0, 0, -0.9), 1.0},     // behind, inside the inner (1 m)
      {o + glm::vec3(0, 0, -3), 0.316228},  // behind, halfway from 1 to 5
      {o + glm::vec3(0, 0, -6), 0.0},       // behind, beyond maxBack 5
      {o + glm::vec3(4, 0, 0), 0.316228},   // abeam: inner 4/3, outer 20/3, halfway
      {o + glm::vec3(0, 1.0f, 0), 1.0},     // abeam inside 4/3
      {o + glm::vec3(0, -3, 0), 0.486968},  // abeam at 3: -20 (5/3) / (16/3) = -6.25 dB
  };
  for (const Case& c : cases) {
    INFO("listener " << c.at.x << " " << c.at.y << " " << c.at.z);
    CHECK(soundGain(g, 1.0f, c.at) == Approx(c.gain).margin(1e-6));
  }
  // At 60 degrees off the axis: outer radius 8, inner 2 * 2 * 1 / (3 - 0.5) = 1.6; at 4.8
  // (halfway) -10 dB.
  const glm::vec3 at = o + 4.8f * glm::vec3(std::sqrt(3.0f) / 2.0f, 0.0f, 0.5f);
  CHECK(soundGain(g, 1.0f, at) == Approx(0.316228).margin(1e-5));
  // intensity scales the amplitude; the direction turns the ellipsoids.
  CHECK(soundGain(g, 0.5f, o + glm::vec3(0, 0, 6)) == Approx(0.158114));
  g.direction = {0.0f, 0.0f, -1.0f};
  CHECK(soundGain(g, 1.0f, o + glm::vec3(0, 0, -6)) == Approx(0.316228));
  CHECK(soundGain(g, 1.0f, o + glm::vec3(0, 0, 6)) == 0.0f);
}

TEST_CASE("Sound: priority chooses the voices", "[audio][sound]") {
  const std::vector<SoundCandidate> sounds = {
      {0.0f, 0.9f}, {1.0f, 0.1f}, {0.5f, 0.0f}, {0.5f, 0.3f}, {0.0f, 0.95f}};
  CHECK(chooseSounds(sounds, 10) == std::vector<std::size_t>{1, 3, 4, 0});  // silent 2 never
  CHECK(chooseSounds(sounds, 2) == std::vector<std::size_t>{1, 3});
  CHECK(chooseSounds(sounds, 0).empty());
}
