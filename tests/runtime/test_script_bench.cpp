// Figures for the Script host (hidden: run with `test_runtime "[.bench]"` on an optimized
// build): the cost of making a Script and of one eventIn call.
#include "script_test_support.hpp"

#include <chrono>
#include <cstdio>

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

TEST_CASE("Script host figures", "[.bench]") {
  FakeScriptContext ctx;
  std::string text = scriptWorld("eventIn SFFloat set_f\neventOut SFFloat out",
                                 "function set_f(v, t) { out = v * 2; }");
  vrml::Scene scene = vrml::parseVrml(text, "bench.wrl");
  vrml::NodePtr script = findScript(scene.rootNodes);
  REQUIRE(script);
  auto factory = runtime::ecmascriptFactory();
  constexpr int kScripts = 200;
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<runtime::ScriptInstance>> all;
  for (int i = 0; i < kScripts; ++i) all.push_back(factory(*script, ctx, {}));
  auto t1 = std::chrono::steady_clock::now();
  int field = script->type().findExact("set_f");
  constexpr int kCalls = 100000;
  for (int i = 0; i < kCalls; ++i)
    all[static_cast<std::size_t>(i % kScripts)]->eventIn(
        field, FieldValue::make<FieldType::SFFloat>(static_cast<float>(i)), i);
  auto t2 = std::chrono::steady_clock::now();
  std::printf("make a Script: %.1f us; one eventIn call (one eventOut sent): %.2f us\n",
              std::chrono::duration<double, std::micro>(t1 - t0).count() / kScripts,
              std::chrono::duration<double, std::micro>(t2 - t1).count() / kCalls);
  CHECK(ctx.emitted.size() == static_cast<std::size_t>(kCalls));
  // The same Script in an X3D world: its heap also gets the X3D classes (ISO/IEC 19777-1).
  vrml::Scene x3d = vrml::parseVrml(
      "#X3D V4.0 utf8\nDEF S Script {\n  inputOnly SFFloat set_f\n  outputOnly SFFloat out\n"
      "  url \"ecmascript: function set_f(v, t) { out = v * 2; }\"\n}\n",
      "bench.x3dv");
  vrml::NodePtr x3dScript = findScript(x3d.rootNodes);
  REQUIRE(x3dScript);
  std::vector<std::unique_ptr<runtime::ScriptInstance>> more;
  auto t3 = std::chrono::steady_clock::now();
  for (int i = 0; i < kScripts; ++i) more.push_back(factory(*x3dScript, ctx, {}));
  auto t4 = std::chrono::steady_clock::now();
  std::printf("make an X3D Script: %.1f us\n",
              std::chrono::duration<double, std::micro>(t4 - t3).count() / kScripts);
  CHECK(more.back() != nullptr);
}
