// FreeWRL's Javascript_tests (../shared/corpus/vrml/freewrl/Javascript_tests): one Script
// per field type whose outputs can be worked out by hand from its inputs.
#include "script_test_support.hpp"
#include "test_support.hpp"

#include <fstream>
#include <sstream>

using namespace gs;
using namespace gs::test;
using Catch::Detail::Approx;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

const char* const kDir = "vrml/freewrl/Javascript_tests";

struct CorpusScript {
  FakeScriptContext ctx;
  ScriptWorld w;

  explicit CorpusScript(const std::string& name) {
    std::filesystem::path path = corpusDir() / kDir / name;
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    w = loadScript(ctx, text.str(), {}, path.string());
    REQUIRE(w.instance);
  }
  void in(const char* field, FieldValue v, double t = 1.0) {
    int f = w.field(field);
    REQUIRE(f >= 0);
    w.instance->eventIn(f, v, t);
  }
  std::vector<FieldValue> out(const char* field) const { return ctx.emittedFor(*w.script, field); }
  template <FieldType T>
  auto one(const char* field) const {
    auto v = out(field);
    REQUIRE(v.size() == 1);
    return v[0].get<T>();
  }
  vrml::NodePtr def(const std::string& name) const {
    for (const auto& n : w.scene.rootNodes)
      if (n && n->defName == name) return n;
    return nullptr;
  }
};

}  // namespace

TEST_CASE("FreeWRL Javascript_tests: SF types", "[script][corpus]") {
  if (!haveCorpus(kDir)) return;

  SECTION("SFVec3f") {
    CorpusScript s("SFVec3f.wrl");
    s.in("set_position", FieldValue::make<FieldType::SFVec3f>(glm::vec3(1, 2, 3)));
    CHECK(s.one<FieldType::SFVec3f>("inverse") == glm::vec3(-3, -4, 3));
    CHECK(s.one<FieldType::SFVec3f>("normal") == glm::vec3(3, 0, 3));
    CHECK(s.ctx.diagnostics.empty());
  }
  SECTION("SFVec2f") {
    CorpusScript s("SFVec2f.wrl");
    s.in("scaler", FieldValue::make<FieldType::SFVec2f>(glm::vec2(2, 4)));
    CHECK(s.one<FieldType::SFVec2f>("centerer") == glm::vec2(1, 2));
  }
  SECTION("SFRotation") {
    CorpusScript s("SFRotation.wrl");
    s.in("rotator", FieldValue::make<FieldType::SFRotation>(vrml::Rotation(0, 1, 0, 3.14f)));
    CHECK(s.one<FieldType::SFRotation>("centerer") == vrml::Rotation(1, 0, 0, 3.14f));
  }
  SECTION("SFColor, with setHSV on an eventOut never assigned") {
    CorpusScript s("SFColor.wrl");
    s.in("set_color", FieldValue::make<FieldType::SFColor>(glm::vec3(0.5f, 0.25f, 1.0f)));
    CHECK(s.one<FieldType::SFColor>("red_only") == glm::vec3(0.5f, 0, 0));
    CHECK(s.one<FieldType::SFColor>("green_only") == glm::vec3(0, 0.25f, 0));
    CHECK(s.one<FieldType::SFColor>("blue_only") == glm::vec3(0, 0, 1));
    CHECK(s.one<FieldType::SFColor>("inverse") == glm::vec3(0.5f, 0.75f, 0));
    // getHSV of (0.5 0 0) is (0, 1, 0.5); setHSV gives the red back.
    CHECK(s.one<FieldType::SFColor>("hsv") == glm::vec3(0.5f, 0, 0));
  }
  SECTION("SFFloat") {
    CorpusScript s("SFFloat.wrl");
    s.in("set_fraction", FieldValue::make<FieldType::SFFloat>(0.25f));
    CHECK(s.one<FieldType::SFFloat>("value_changed") == 0.25f);
  }
  SECTION("SFInt32: an event only when the choice changes") {
    CorpusScript s("SFInt32.wrl");
    s.in("set_fraction", FieldValue::make<FieldType::SFFloat>(0.6f));
    CHECK(s.one<FieldType::SFInt32>("value_changed") == 2);
    s.in("use_choice", FieldValue::make<FieldType::SFInt32>(2));
    s.in("use_choice", FieldValue::make<FieldType::SFInt32>(2));
    CHECK(s.one<FieldType::SFInt32>("choiceCopy") == 2);
  }
  SECTION("SFTime: value and timestamp") {
    CorpusScript s("SFTime.wrl");
    s.in("touched", FieldValue::make<FieldType::SFTime>(5.0), 7.0);
    CHECK(s.one<FieldType::SFTime>("touch_timed") == 5.0);
    CHECK(s.ctx.printed == std::vector<std::string>{"touched at 5 timed at 7 should be the same"});
  }
  SECTION("SFBool: eventsProcessed counts to 200") {
    CorpusScript s("SFBool.wrl");
    for (int i = 0; i < 199; ++i) s.w.instance->eventsProcessed(i);
    CHECK(s.out("value_changed").empty());
    s.w.instance->eventsProcessed(200);
    CHECK(s.one<FieldType::SFBool>("value_changed") == true);
  }
  SECTION("SFString") {
    CorpusScript s("SFString.wrl");
    s.in("newString", FieldValue::make<FieldType::SFString>(std::string("abc")));
    CHECK(s.one<FieldType::MFString>("textString") ==
          std::vector<std::string>{"TextureCoordinateGeneratorType:", "abc"});
    for (int i = 0; i < 200; ++i) s.w.instance->eventsProcessed(i);
    CHECK(s.one<FieldType::SFString>("newMode") == "SPHERE-REFLECT");
  }
  SECTION("SFNode: new SFNode from text, copied pointers") {
    CorpusScript s("SFNode.wrl");
    s.w.instance->initialize(0.0);
    vrml::NodePtr made = s.one<FieldType::SFNode>("createFromString");
    REQUIRE(made);
    CHECK(made->typeName() == "Cylinder");
    CHECK(made->get<FieldType::SFFloat>("height", 0.0f) == 1.0f);
    s.in("copyGeometryPointer", FieldValue::make<FieldType::SFNode>(made));
    CHECK(s.one<FieldType::SFNode>("copiedPointer") == made);
    CHECK(s.one<FieldType::SFNode>("newedPointer") == made);
    CHECK(s.ctx.diagnostics.empty());
  }
  SECTION("SFImage: a 10 x 10 grey image, copied back") {
    CorpusScript s("SFImage.wrl");
    s.w.instance->initialize(0.0);
    vrml::SFImage img = s.one<FieldType::SFImage>("changeConeImage");
    CHECK(img.width == 10);
    CHECK(img.height == 10);
    CHECK(img.components == 1);
    REQUIRE(img.pixels.size() == 100);
    for (std::uint32_t p : img.pixels) CHECK(p < 255);
    s.in("coneImageChanged", FieldValue::make<FieldType::SFImage>(img));
    CHECK(s.one<FieldType::SFImage>("changeBoxImage") == img);
  }
}

TEST_CASE("FreeWRL Javascript_tests: MF types and routes", "[script][corpus]") {
  if (!haveCorpus(kDir)) return;

  SECTION("MFFloat: one element changed in an eventIn's array") {
    CorpusScript s("MFFloat.wrl");
    s.w.instance->initialize(0.0);
    CHECK(s.one<FieldType::MFFloat>("newOrit") == std::vector<float>{0, 0.1f, 1});
    s.in("leftBoxChanged", FieldValue::make<FieldType::MFFloat>(std::vector<float>{0, 0.3f, 1}));
    CHECK(s.one<FieldType::MFFloat>("rightOrit") == std::vector<float>{0, 0.5f, 1});
  }
  SECTION("MFColor: components of elements") {
    CorpusScript s("MFColor.wrl");
    s.w.instance->initialize(0.0);
    CHECK(s.one<FieldType::MFColor>("newOrit") ==
          std::vector<glm::vec3>{{0, 0, 0}, {0, 0.5f, 0.5f}, {0, 1, 1}});
    s.in("leftBoxChanged",
         FieldValue::make<FieldType::MFColor>(std::vector<glm::vec3>{{0, 0.5f, 0.25f}, {1, 1, 1}}));
    CHECK(s.one<FieldType::MFColor>("rightOrit") ==
          std::vector<glm::vec3>{{0.25f, 0.5f, 0}, {1, 1, 0}});
  }
  SECTION("MFRotation") {
    CorpusScript s("MFRotation.wrl");
    s.in("leftBoxChanged",
         FieldValue::make<FieldType::MFRotation>(std::vector<vrml::Rotation>{{1, 0, 0, 1}}));
    CHECK(s.one<FieldType::MFRotation>("rightOrit") == std::vector<vrml::Rotation>{{1, 0, 1, 1}});
    for (int i = 0; i < 200; ++i) s.w.instance->eventsProcessed(i);
    auto orit = s.one<FieldType::MFRotation>("newOrit");
    REQUIRE(orit.size() == 3);
    CHECK(orit[1] == vrml::Rotation(0, 1, 0, 3.14f));
  }
  SECTION("MFInt32: eventsProcessed counts to 100") {
    CorpusScript s("MFInt32.wrl");
    for (int i = 0; i < 101; ++i) s.w.instance->eventsProcessed(i);
    CHECK(s.one<FieldType::MFInt32>("this_keyValue") == std::vector<std::int32_t>{4, 5, 6, 7});
  }
  SECTION("addDelRoute: deleteRoute then addRoute") {
    CorpusScript s("addDelRoute.wrl");
    for (int i = 0; i < 400; ++i) s.w.instance->eventsProcessed(i);
    CHECK(s.ctx.routes ==
          std::vector<std::string>{"delete Clock.fraction_changed ColumnPath.set_fraction",
                                   "add Clock.fraction_changed ColumnPath.set_fraction"});
    CHECK(s.ctx.diagnostics.empty());
  }
}

TEST_CASE("FreeWRL Javascript_tests: every Script loads and initializes without an error",
          "[script][corpus]") {
  if (!haveCorpus(kDir)) return;
  for (const auto& path : filesWithSuffix(corpusDir() / kDir, ".wrl")) {
    INFO(path.string());
    CorpusScript s(path.filename().string());
    s.w.instance->initialize(0.0);
    for (int i = 0; i < 10; ++i) s.w.instance->eventsProcessed(i);
    s.w.instance->shutdown(10.0);
    INFO(s.ctx.diagnosticText());
    CHECK(s.ctx.diagnostics.empty());
    CHECK_FALSE(s.w.instance->stopped());
  }
}
