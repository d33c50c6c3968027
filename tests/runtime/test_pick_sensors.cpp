// X3D Picking (X3D 4.0 clause 38) in the execution model: the four pick sensors against
// their pickTargets, PickableGroup's pickable, sortOrder, and their events.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

bool sawPick(const std::vector<std::string>& events, const std::string& prefix) {
  return std::any_of(events.begin(), events.end(),
                     [&](const std::string& e) { return e.rfind(prefix, 0) == 0; });
}

const char* kTargets = R"(
DEF A Transform { children Shape { geometry Box { size 2 2 2 } } }
DEF B Transform { translation 10 0 0 children Shape { geometry Box { size 2 2 2 } } }
PickableGroup { pickable FALSE children DEF HIDDEN Transform { translation 0 10 0
  children Shape { geometry Box { size 2 2 2 } } } }
)";

}  // namespace

TEST_CASE("picking: a PointPickSensor picks the targets its points are inside",
          "[runtime][x3d][picking]") {
  RunningWorld w(x3dWorld(std::string(kTargets) + R"(
DEF S PointPickSensor {
  intersectionType "GEOMETRY" sortOrder "ALL_SORTED"
  pickingGeometry PointSet { coord Coordinate { point [ 0.5 0 0, 3 0 0, 10 0.5 0, 0 10 0 ] } }
  pickTarget [ USE A USE B USE HIDDEN ]
}
)"),
                 0.0);
  w.model->advanceTo(0.1);
  const auto events = w.take();
  CHECK(sawPick(events, "S.isActive=TRUE"));
  CHECK(sawPick(events, "S.pickedPoint="));
  // Not 3 0 0 (outside every box), not 0 10 0 (HIDDEN is not pickable).
  CHECK(w.node("S").field("pickedPoint")->get<FieldType::MFVec3f>() ==
        std::vector<glm::vec3>{{0.5f, 0, 0}, {10, 0.5f, 0}});
  const auto& picked = w.node("S").field("pickedGeometry")->get<FieldType::MFNode>();
  REQUIRE(picked.size() == 2);
  CHECK(picked[0].get() == &w.node("A"));  // nearest first
  CHECK(picked[1].get() == &w.node("B"));
  // The targets move away: nothing picked.
  w.send("A", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0, -20, 0)));
  w.send("B", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0, -30, 0)));
  w.take();
  w.model->advanceTo(0.2);
  CHECK(sawPick(w.take(), "S.isActive=FALSE"));
}

TEST_CASE("picking: a LinePickSensor gives its crossings with normals; CLOSEST keeps one",
          "[runtime][x3d][picking]") {
  RunningWorld w(x3dWorld(std::string(kTargets) + R"(
DEF S LinePickSensor {
  intersectionType "GEOMETRY"
  pickingGeometry LineSet { vertexCount 2 coord Coordinate { point [ -5 0 0, 15 0 0 ] } }
  pickTarget [ USE B USE A ]
}
)"),
                 0.0);
  w.model->advanceTo(0.1);
  const auto events = w.take();
  CHECK(sawPick(events, "S.isActive=TRUE"));
  const auto& points = w.node("S").field("pickedPoint")->get<FieldType::MFVec3f>();
  REQUIRE(points.size() == 2);  // A's two faces at x = -1 and 1 (the closest target)
  CHECK(std::min(points[0].x, points[1].x) == Approx(-1.0f));
  CHECK(std::max(points[0].x, points[1].x) == Approx(1.0f));
  const auto& normals = w.node("S").field("pickedNormal")->get<FieldType::MFVec3f>();
  REQUIRE(normals.size() == 2);
  CHECK(std::abs(normals[0].x) == Approx(1.0f));
  const auto& picked = w.node("S").field("pickedGeometry")->get<FieldType::MFNode>();
  REQUIRE(picked.size() == 1);
  CHECK(picked[0].get() == &w.node("A"));
}

TEST_CASE("picking: primitive and volume sensors by bounds and by geometry",
          "[runtime][x3d][picking]") {
  RunningWorld w(x3dWorld(std::string(kTargets) + R"(
Transform { translation 2.5 0 0 children [
  DEF P PrimitivePickSensor { pickingGeometry Sphere { radius 1 } pickTarget [ USE A ]
    intersectionType "BOUNDS" }
  DEF V VolumePickSensor { pickingGeometry Sphere { radius 1 } pickTarget [ USE A ]
    intersectionType "GEOMETRY" }
  DEF FAR VolumePickSensor { pickingGeometry Sphere { radius 0.2 } pickTarget [ USE A ]
    intersectionType "GEOMETRY" }
] }
)"),
                 0.0);
  w.model->advanceTo(0.1);
  const auto events = w.take();
  // The sphere (centre 2.5, radius 1) overlaps A's box (to x = 1) in neither bounds nor
  // geometry: it starts at 1.5.
  CHECK(!sawPick(events, "P.isActive"));
  CHECK(!sawPick(events, "V.isActive"));
  w.send("A", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(1, 0, 0)));
  w.take();
  w.model->advanceTo(0.2);
  const auto moved = w.take();
  CHECK(sawPick(moved, "P.isActive=TRUE"));
  CHECK(sawPick(moved, "V.isActive=TRUE"));
  CHECK(!sawPick(moved, "FAR.isActive"));  // radius 0.2 at 2.5: outside the box (to 2)
}

TEST_CASE("picking: objectType and matchCriterion choose what a sensor may pick",
          "[runtime][x3d][picking]") {
  // Three boxes at the origin, each in PickableGroups of other types; one point inside.
  RunningWorld w(x3dWorld(R"(
DEF BOXES PickableGroup { objectType [ "BOX" "SOLID" ] children DEF A Transform {
  children Shape { geometry Box { size 2 2 2 } } } }
DEF CONES PickableGroup { objectType "CONE" children DEF B Transform {
  children Shape { geometry Box { size 2 2 2 } } } }
DEF NONE PickableGroup { objectType "NONE" children DEF C Transform {
  children Shape { geometry Box { size 2 2 2 } } } }
DEF Any PointPickSensor { sortOrder "ALL" objectType [ "BOX" "CONE" ]
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE A USE B USE C ] }
DEF Every PointPickSensor { sortOrder "ALL" objectType [ "BOX" "SOLID" ] matchCriterion "MATCH_EVERY"
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE A USE B USE C ] }
DEF One PointPickSensor { sortOrder "ALL" objectType [ "SOLID" "CONE" ] matchCriterion "MATCH_ONLY_ONE"
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE BOXES USE B ] }
DEF Two PointPickSensor { sortOrder "ALL" objectType [ "SOLID" "BOX" ] matchCriterion "MATCH_ONLY_ONE"
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE BOXES USE B ] }
DEF All PointPickSensor { sortOrder "ALL"
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE A USE B USE C ] }
DEF Off PointPickSensor { sortOrder "ALL" objectType "NONE"
  pickingGeometry PointSet { coord Coordinate { point 0 0 0 } }
  pickTarget [ USE A USE B ] }
)"),
                 0.0);
  w.model->advanceTo(0.1);
  const auto picked = [&](const char* sensor) {
    std::vector<std::string> names;
    for (const auto& n : w.node(sensor).field("pickedGeometry")->get<FieldType::MFNode>())
      names.push_back(n ? n->defName : "NULL");
    std::sort(names.begin(), names.end());
    return names;
  };
  using Names = std::vector<std::string>;
  CHECK(picked("Any") == Names{"A", "B"});      // MATCH_ANY; never under "NONE"
  CHECK(picked("Every") == Names{"A"});         // both of BOXES' types, and only those
  CHECK(picked("One") == Names{"B", "BOXES"});  // one type shared with each
  CHECK(picked("Two").empty());                 // BOXES shares two types with it, CONES none
  CHECK(picked("All") == Names{"A", "B"});      // "ALL", the default
  CHECK(picked("Off").empty());                 // a sensor of "NONE" picks nothing
  CHECK_FALSE(w.node("Off").get<FieldType::SFBool>("isActive", true));
}

TEST_CASE("picking: a ParticleSystem is picked by its particles as they are drawn",
          "[runtime][x3d][picking][particles]") {
  // Particles that stay where they are born: QUADs of 1 m at the origin, and GEOMETRY
  // boxes of 2 m at x = 10. Nothing lives before the first step.
  RunningWorld w(x3dWorld(R"(
DEF QUADS Transform { children DEF PS ParticleSystem { geometryType "QUAD"
  maxParticles 10 particleLifetime 1 particleSize 1 1
  emitter PointEmitter { speed 0 variation 0 } } }
DEF BOXES Transform { translation 10 0 0 children DEF PB ParticleSystem {
  geometryType "GEOMETRY" geometry Box { size 2 2 2 }
  maxParticles 10 particleLifetime 1
  emitter PointEmitter { speed 0 variation 0 } } }
DEF LINE LinePickSensor { intersectionType "GEOMETRY" sortOrder "ALL"
  pickingGeometry LineSet { vertexCount 2 coord Coordinate { point [ 0.2 0.1 -5, 0.2 0.1 5 ] } }
  pickTarget [ USE QUADS USE BOXES ] }
DEF POINT PointPickSensor { intersectionType "GEOMETRY" sortOrder "ALL"
  pickingGeometry PointSet { coord Coordinate { point [ 10.5 0.5 0.5, 12 0 0 ] } }
  pickTarget [ USE QUADS USE BOXES ] }
)"),
                 0.0);
  w.model->advanceBy(0.5, 1.0 / 60.0);
  const auto events = w.take();
  CHECK(sawPick(events, "LINE.isActive=TRUE"));
  CHECK(sawPick(events, "POINT.isActive=TRUE"));
  // The line crosses each quad at its own point; they are all at the origin.
  const auto& line = w.node("LINE").field("pickedPoint")->get<FieldType::MFVec3f>();
  REQUIRE(!line.empty());
  CHECK(line[0].x == Approx(0.2f));
  CHECK(line[0].y == Approx(0.1f));
  CHECK(line[0].z == Approx(0.0f).margin(1e-6));
  const auto& lineNormals = w.node("LINE").field("pickedNormal")->get<FieldType::MFVec3f>();
  REQUIRE(!lineNormals.empty());
  CHECK(std::abs(lineNormals[0].z) == Approx(1.0f));
  const auto& lineTargets = w.node("LINE").field("pickedGeometry")->get<FieldType::MFNode>();
  REQUIRE(lineTargets.size() == 1);
  CHECK(lineTargets[0].get() == &w.node("QUADS"));
  // The point inside the particles' boxes is picked, however many of them coincide there
  // (each box is closed by itself: an even count of them must not cancel); 12 0 0 is past
  // them. It stays picked at every step.
  CHECK(!sawPick(events, "POINT.isActive=FALSE"));
  REQUIRE(w.model->particleSimulation(w.node("PB")) != nullptr);
  CHECK(w.model->particleSimulation(w.node("PB"))->particles().size() >= 2);
  CHECK(w.node("POINT").field("pickedPoint")->get<FieldType::MFVec3f>() ==
        std::vector<glm::vec3>{{10.5f, 0.5f, 0.5f}});
  const auto& pointTargets = w.node("POINT").field("pickedGeometry")->get<FieldType::MFNode>();
  REQUIRE(pointTargets.size() == 1);
  CHECK(pointTargets[0].get() == &w.node("BOXES"));
  // No particles, nothing picked.
  w.send("PS", "set_enabled", FieldValue::make<FieldType::SFBool>(false));
  w.send("PB", "set_enabled", FieldValue::make<FieldType::SFBool>(false));
  w.take();
  w.model->advanceBy(0.1, 1.0 / 60.0);
  const auto off = w.take();
  CHECK(sawPick(off, "LINE.isActive=FALSE"));
  CHECK(sawPick(off, "POINT.isActive=FALSE"));
}
