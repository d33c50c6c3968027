#include <catch2/catch.hpp>

#include <cmath>

#include "app/auto_lod.hpp"

using namespace gs::app;

TEST_CASE("automatic LOD caps the first frame before any rate is known", "[app][lod]") {
  CHECK(autoLodBudget(0, 0.0, 0.05) == kFirstFrameVectors);
  CHECK(autoLodBudget(1000, 0.0, 0.05) == 1000);
}

TEST_CASE("automatic LOD caps a frame at twice the target at the measured rate", "[app][lod]") {
  // 1 M splats/s, a 50 ms target: 100,000 vectors fit twice the target.
  CHECK(autoLodBudget(0, 1e6, 0.05) == 100'000);
  // A user budget below the cap wins; above it, the cap wins.
  CHECK(autoLodBudget(20'000, 1e6, 0.05) == 20'000);
  CHECK(autoLodBudget(5'000'000, 1e6, 0.05) == 100'000);
  // A very slow rate still draws something.
  CHECK(autoLodBudget(0, 10.0, 0.05) == kMinAutoVectors);
}

TEST_CASE("automatic LOD drops at once after a frame far over its target", "[app][lod]") {
  // The soak test's case: 43 s against a 12.5 ms share drops by the most allowed.
  CHECK(autoLodRatio(0.0125, 43.0) == Approx(1.0 / 64.0));
  // Four times over: /4 in one frame, not the damped /2.
  CHECK(autoLodRatio(0.05, 0.2) == Approx(0.25));
  // Near the target: damped square root.
  CHECK(autoLodRatio(0.05, 0.08) == Approx(std::sqrt(0.05 / 0.08)));
  CHECK(autoLodRatio(0.05, 0.01) == Approx(2.0));
  CHECK(autoLodRatio(0.05, 0.0) == 1.0);
}
