// A world's animations as the window's Animations menu starts and stops them
// (session/animations.hpp), on the corpus's Fox (three glTF animations).
#include "encodings/parser.hpp"
#include "session/animations.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

using namespace gs;

TEST_CASE("animations: a glTF asset's are listed by name; one plays at a time",
          "[session][animations][corpus]") {
  if (!test::haveCorpus("gltf")) return;
  auto scene = std::make_shared<vrml::Scene>(vrml::loadVrmlFile(
      (test::corpusDir() / "gltf/castle/animation/gltf_skinned_animation/fox_from_khronos/Fox.gltf")
          .string()));
  REQUIRE(scene->diagnostics.errorCount() == 0);
  const std::vector<vrml::Node*> sensors = session::namedTimeSensors(*scene);
  REQUIRE(sensors.size() == 3);
  CHECK(sensors[0]->defName == "Survey");
  CHECK(sensors[1]->defName == "Walk");
  CHECK(sensors[2]->defName == "Run");
  CHECK(session::namedTimeSensors(*scene, 2).size() == 2);

  runtime::ExecutionModel model(scene, 0.0);
  model.advanceTo(1.0);
  CHECK(session::animationActive(*sensors[0]));  // the first one loops from the start
  CHECK_FALSE(session::animationActive(*sensors[1]));
  session::startAnimation(model, *sensors[1], sensors, true);
  model.advanceTo(1.5);
  CHECK_FALSE(session::animationActive(*sensors[0]));
  CHECK(session::animationActive(*sensors[1]));
  model.advanceTo(20.0);  // longer than Walk's cycle: it loops
  CHECK(session::animationActive(*sensors[1]));
  session::stopAnimation(model, *sensors[1]);
  model.advanceTo(20.5);
  CHECK_FALSE(session::animationActive(*sensors[1]));
  // Not exclusive: both run.
  session::startAnimation(model, *sensors[0], sensors, false);
  session::startAnimation(model, *sensors[2], sensors, false);
  model.advanceTo(21.0);
  CHECK(session::animationActive(*sensors[0]));
  CHECK(session::animationActive(*sensors[2]));
}

TEST_CASE("animations: only DEF-named TimeSensors are listed, in file order",
          "[session][animations]") {
  const vrml::Scene scene = vrml::parseVrml(R"(#VRML V2.0 utf8
DEF B TimeSensor {}
TimeSensor {}
Group { children [ DEF A TimeSensor {} DEF G Group {} ] }
)",
                                            "t.wrl");
  const auto names = session::namedTimeSensors(scene);
  REQUIRE(names.size() == 2);
  CHECK(names[0]->defName == "B");
  CHECK(names[1]->defName == "A");
}
