// Every corpus world with ROUTEs runs 10 simulated seconds (600 cascades at 60 Hz) without
// a crash, a hang or a leak (the ASan+UBSan build checks the last two), and the castle
// OrientationInterpolator world turns its box as the interpolator says.
#include "base/file.hpp"
#include "runtime/script_ecmascript.hpp"
#include "runtime_fixture.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace gs;

TEST_CASE("runtime: animated corpus worlds run 10 simulated seconds", "[runtime][corpus]") {
  if (!test::haveCorpus("vrml/freewrl")) return;
  std::vector<std::filesystem::path> worlds;
  for (const char* sub : {"vrml/freewrl", "vrml/castle-animation", "vrml/castle", "vrml/openvrml"})
    for (const auto& p : test::filesWithSuffix(test::corpusDir() / sub, ".wrl"))
      worlds.push_back(p);
  int animated = 0;
  for (const auto& path : worlds) {
    auto scene = std::make_shared<vrml::Scene>(vrml::loadVrmlFile(path.string()));
    if (scene->routes.empty()) continue;
    ++animated;
    INFO(path.string());
    // Scripts run too (ECMAScript through Duktape, with their files read from disk: the
    // model's default fetcher reads local files relative to the world).
    runtime::ExecutionOptions options;
    options.scripts = runtime::ecmascriptFactory();
    runtime::ExecutionModel model(scene, 1000.0, std::move(options));
    model.advanceBy(10.0, 1.0 / 60.0);
    CHECK(model.now() == Approx(1010.0));
    CHECK(model.statistics().cascades >= 600);
  }
  CHECK(animated >= 20);
}

TEST_CASE("runtime: castle's OrientationInterpolator world at mid-cycle", "[runtime][corpus]") {
  if (!test::haveCorpus("vrml/castle-animation")) return;
  auto scene = std::make_shared<vrml::Scene>(vrml::loadVrmlFile(
      (test::corpusDir() / "vrml/castle-animation/orientation_interpolator_alum_box.wrl")
          .string()));
  // cycleInterval 4, loop: at t = 1.32 the fraction is 0.33, the second key (2.094 rad).
  runtime::ExecutionModel model(scene, 1.32);
  const vrml::Node* ttr = nullptr;
  std::function<void(const vrml::NodePtr&)> find = [&](const vrml::NodePtr& n) {
    if (!n || ttr) return;
    if (n->defName == "TTR") ttr = n.get();
    for (const auto& c : n->mfnode("children")) find(c);
  };
  for (const auto& n : scene->rootNodes) find(n);
  REQUIRE(ttr != nullptr);
  const vrml::Rotation r = ttr->field("rotation")->get<vrml::FieldType::SFRotation>();
  CHECK(std::abs(r.y) == Approx(1.0));
  CHECK(r.w * (r.y < 0 ? -1.0f : 1.0f) == Approx(2.094).epsilon(1e-3));
}
