// Clause 4.6.7: pointing-device sensors (TouchSensor 6.48, PlaneSensor 6.34, SphereSensor
// 6.43, CylinderSensor 6.13) and Anchor (6.2), driven with hand-made picks.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <utility>

using gs::runtime::BindableKind;
using gs::runtime::PickedNode;
using gs::runtime::PickResult;
using gs::runtime::PointerEvent;
using gs::runtime::PointerHint;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using Strings = std::vector<std::string>;

namespace {

/// A pick of the Shape DEFed last in `groups` (the grouping nodes from the root down,
/// each with the matrix of its children's coordinate system) at world `point`.
PickResult pick(const RunningWorld& w, const std::vector<std::pair<std::string, glm::mat4>>& groups,
                glm::vec3 point, glm::vec3 normal = {0, 0, 1}, glm::vec2 texCoord = {0, 0}) {
  PickResult r;
  r.path.push_back({nullptr, glm::mat4(1.0f), &w.scene->rootNodes});
  for (const auto& [name, m] : groups) r.path.push_back({&w.node(name), m, nullptr});
  r.point = point;
  r.normal = normal;
  r.texCoord = texCoord;
  return r;
}

/// A bearing along -Z from (x, y, 10), or along -Y from (x, 10, z) when `down`.
PointerEvent along(float x, float y, bool button, std::optional<PickResult> hit = std::nullopt) {
  PointerEvent e;
  e.rayOrigin = {x, y, 10.0f};
  e.rayDirection = {0.0f, 0.0f, -1.0f};
  e.buttonDown = button;
  e.hit = std::move(hit);
  return e;
}

const gs::vrml::FieldValue& eventOut(const RunningWorld& w, const std::string& node,
                                     const std::string& field) {
  const gs::vrml::Node& n = w.node(node);
  return n.fieldAt(static_cast<std::size_t>(RunningWorld::field(n, field)));
}

void checkRotation(const gs::vrml::FieldValue& v, glm::vec4 expected) {
  REQUIRE(v.type() == FieldType::SFRotation);
  const gs::vrml::Rotation r = v.get<FieldType::SFRotation>();
  CHECK(r.x == Approx(expected.x).margin(1e-5));
  CHECK(r.y == Approx(expected.y).margin(1e-5));
  CHECK(r.z == Approx(expected.z).margin(1e-5));
  CHECK(r.w == Approx(expected.w).margin(1e-5));
}

}  // namespace

TEST_CASE("pointer: a TouchSensor click, in the sensor's coordinates", "[runtime][pointer]") {
  RunningWorld w(R"(
DEF T Transform { translation 1 0 0 scale 2 2 2 children [
  DEF S TouchSensor {}
  DEF SH Shape { geometry Box {} }
] }
)",
                 10.0);
  w.take();
  const glm::mat4 m = glm::scale(glm::translate(glm::mat4(1.0f), {1, 0, 0}), glm::vec3(2.0f));
  const auto hit = [&] {
    return pick(w, {{"T", m}, {"SH", m}}, {1.5f, 0.25f, 1.0f}, {0, 0, 1}, {0.75f, 0.625f});
  };
  CHECK(w.model->pointerHint() == PointerHint{});
  CHECK_FALSE(w.model->pointer(along(1.5f, 0.25f, false, hit())));
  CHECK(w.take() == Strings{"S.isOver=TRUE", "S.hitPoint_changed=0.25 0.125 0.5",
                            "S.hitNormal_changed=0 0 1", "S.hitTexCoord_changed=0.75 0.625"});
  CHECK(w.model->pointerHint() == PointerHint{true, ""});
  CHECK(w.model->pointer(along(1.5f, 0.25f, true, hit())));  // press: held
  CHECK(w.take() == Strings{"S.isActive=TRUE"});
  w.model->advanceTo(12.5);
  w.take();
  CHECK_FALSE(w.model->pointer(along(1.5f, 0.25f, false, hit())));
  CHECK(w.take() == Strings{"S.isActive=FALSE", "S.touchTime=12.500"});
  CHECK_FALSE(w.model->pointer(along(5.0f, 0.25f, false)));  // off the geometry
  CHECK(w.take() == Strings{"S.isOver=FALSE"});
  CHECK(w.model->pointerHint() == PointerHint{});
}

TEST_CASE("pointer: released off the geometry, a TouchSensor sends no touchTime",
          "[runtime][pointer]") {
  RunningWorld w(R"(
DEF G Group { children [ DEF S TouchSensor {} DEF SH Shape { geometry Box {} } ] }
)");
  w.take();
  const glm::mat4 id(1.0f);
  const auto hit = pick(w, {{"G", id}, {"SH", id}}, {0.5f, 0.5f, 1.0f});
  w.model->pointer(along(0.5f, 0.5f, false, hit));
  w.model->pointer(along(0.5f, 0.5f, true, hit));
  w.take();
  w.model->pointer(along(3.0f, 0.5f, true));  // dragged off: still active, not over
  CHECK(w.take() == Strings{"S.isOver=FALSE"});
  w.model->pointer(along(3.0f, 0.5f, false));
  CHECK(w.take() == Strings{"S.isActive=FALSE"});
}

TEST_CASE("pointer: the lowest group with enabled sensors wins", "[runtime][pointer]") {
  RunningWorld w(R"(
DEF OUTER Group { children [
  DEF S1 TouchSensor {}
  DEF INNER Group { children [ DEF S2 TouchSensor {} DEF S3 TouchSensor {}
                               DEF SH Shape { geometry Box {} } ] }
] }
)");
  w.take();
  const glm::mat4 id(1.0f);
  const auto hit = [&] { return pick(w, {{"OUTER", id}, {"INNER", id}, {"SH", id}}, {0, 0, 1}); };
  w.model->pointer(along(0, 0, false, hit()));
  CHECK(w.take() == Strings{"S2.isOver=TRUE", "S2.hitPoint_changed=0 0 1",
                            "S2.hitNormal_changed=0 0 1", "S2.hitTexCoord_changed=0 0",
                            "S3.isOver=TRUE", "S3.hitPoint_changed=0 0 1",
                            "S3.hitNormal_changed=0 0 1", "S3.hitTexCoord_changed=0 0"});
  w.model->pointer(along(3, 0, false));
  w.take();
  w.send("S2", "enabled", gs::vrml::FieldValue::make<FieldType::SFBool>(false));
  w.send("S3", "enabled", gs::vrml::FieldValue::make<FieldType::SFBool>(false));
  w.take();
  w.model->pointer(along(0, 0, false, hit()));
  const Strings events = w.take();
  REQUIRE(!events.empty());
  CHECK(events.front() == "S1.isOver=TRUE");
}

TEST_CASE("pointer: a PlaneSensor drag with offset, autoOffset and clamping",
          "[runtime][pointer]") {
  RunningWorld w(R"(
DEF G Group { children [
  DEF PS PlaneSensor { minPosition -1 0 maxPosition 1 0 }
  DEF TR Transform { children DEF SH Shape { geometry Box {} } }
] }
ROUTE PS.translation_changed TO TR.set_translation
)");
  w.take();
  const glm::mat4 id(1.0f);
  auto hitAt = [&](float x, float y, const glm::mat4& tr) {
    return pick(w, {{"G", id}, {"TR", tr}, {"SH", tr}}, {x, y, 1.0f});
  };
  CHECK(w.model->pointer(along(0.5f, 0.5f, true, hitAt(0.5f, 0.5f, id))));
  CHECK(w.take() == Strings{"PS.isActive=TRUE"});
  // Off the real geometry: the virtual plane z = 1 still tracks.
  CHECK(w.model->pointer(along(1.0f, 0.8f, true)));
  CHECK(w.take() == Strings{"PS.trackPoint_changed=1 0.8 1", "PS.translation_changed=0.5 0 0",
                            "TR.translation_changed=0.5 0 0"});
  w.model->pointer(along(2.5f, 0.5f, true));  // x clamped to maxPosition, y fixed at 0
  CHECK(w.take() == Strings{"PS.trackPoint_changed=2.5 0.5 1", "PS.translation_changed=1 0 0",
                            "TR.translation_changed=1 0 0"});
  CHECK_FALSE(w.model->pointer(along(2.5f, 0.5f, false)));
  CHECK(w.take() == Strings{"PS.isActive=FALSE", "PS.offset_changed=1 0 0"});
  // The second drag starts from the offset.
  const glm::mat4 moved = glm::translate(id, {1, 0, 0});
  w.model->pointer(along(1.25f, 0.0f, true, hitAt(1.25f, 0.0f, moved)));
  CHECK(w.take() == Strings{"PS.isActive=TRUE"});
  w.model->pointer(along(0.75f, 0.0f, true));
  CHECK(w.take() == Strings{"PS.trackPoint_changed=0.75 0 1", "PS.translation_changed=0.5 0 0",
                            "TR.translation_changed=0.5 0 0"});
  // Without autoOffset the offset stays.
  w.send("PS", "autoOffset", gs::vrml::FieldValue::make<FieldType::SFBool>(false));
  w.take();
  w.model->pointer(along(0.75f, 0.0f, false));
  CHECK(w.take() == Strings{"PS.isActive=FALSE"});
}

TEST_CASE("pointer: a SphereSensor rotation accumulates through its offset", "[runtime][pointer]") {
  RunningWorld w(R"(
DEF G Group { children [ DEF SS SphereSensor {} DEF SH Shape { geometry Sphere {} } ] }
)");
  w.take();
  const glm::mat4 id(1.0f);
  const auto hit = [&] { return pick(w, {{"G", id}, {"SH", id}}, {0.0f, 0.0f, 1.0f}); };
  w.model->pointer(along(0.0f, 0.0f, true, hit()));
  CHECK(w.take() == Strings{"SS.isActive=TRUE"});
  w.model->pointer(along(0.6f, 0.0f, true));  // meets the sphere of radius 1 at (0.6 0 0.8)
  const Strings drag = w.take();
  REQUIRE(drag.size() == 2);
  CHECK(drag[0] == "SS.trackPoint_changed=0.6 0 0.8");
  CHECK(drag[1].starts_with("SS.rotation_changed=0 1 0 0.6435"));
  checkRotation(eventOut(w, "SS", "rotation_changed"), {0, 1, 0, std::atan2(0.6f, 0.8f)});
  w.model->pointer(along(0.6f, 0.0f, false));
  const Strings release = w.take();
  REQUIRE(release.size() == 2);
  CHECK(release[0] == "SS.isActive=FALSE");
  CHECK(release[1].starts_with("SS.offset_changed=0 1 0 0.6435"));
  // The same drag again: twice the angle.
  w.model->pointer(along(0.0f, 0.0f, true, hit()));
  w.model->pointer(along(0.6f, 0.0f, true));
  checkRotation(eventOut(w, "SS", "rotation_changed"), {0, 1, 0, 2.0f * std::atan2(0.6f, 0.8f)});
  w.model->pointer(along(0.6f, 0.0f, false));
}

TEST_CASE("pointer: a CylinderSensor turns around local Y on its cylinder or disk",
          "[runtime][pointer]") {
  RunningWorld w(R"(
DEF G Group { children [ DEF CS CylinderSensor { autoOffset FALSE maxAngle 1 }
                         DEF SH Shape { geometry Cylinder {} } ] }
)");
  w.take();
  const glm::mat4 id(1.0f);
  // From the side (90 degrees from the axis, more than diskAngle): the cylinder r = 1.
  w.model->pointer(along(0.0f, 0.5f, true, pick(w, {{"G", id}, {"SH", id}}, {0.0f, 0.5f, 1.0f})));
  CHECK(w.take() == Strings{"CS.isActive=TRUE"});
  w.model->pointer(along(0.6f, 0.5f, true));
  const Strings drag = w.take();
  REQUIRE(drag.size() == 2);
  CHECK(drag[0] == "CS.trackPoint_changed=0.6 0.5 0.8");
  checkRotation(eventOut(w, "CS", "rotation_changed"), {0, 1, 0, std::atan2(0.6f, 0.8f)});
  w.model->pointer(along(0.6f, 0.5f, false));
  CHECK(w.take() == Strings{"CS.isActive=FALSE"});  // autoOffset FALSE: no offset_changed

  // From above (along the axis, within diskAngle): the disk y = 1; a quarter turn is
  // clamped to maxAngle 1.
  PointerEvent down;
  down.rayOrigin = {0.5f, 10.0f, 0.0f};
  down.rayDirection = {0.0f, -1.0f, 0.0f};
  down.buttonDown = true;
  down.hit = pick(w, {{"G", id}, {"SH", id}}, {0.5f, 1.0f, 0.0f}, {0, 1, 0});
  w.model->pointer(down);
  w.take();
  PointerEvent turn = down;
  turn.hit.reset();
  turn.rayOrigin = {0.0f, 10.0f, -0.5f};
  w.model->pointer(turn);
  const Strings disk = w.take();
  REQUIRE(disk.size() == 2);
  CHECK(disk[0] == "CS.trackPoint_changed=0 1 -0.5");
  CHECK(disk[1] == "CS.rotation_changed=0 1 0 1");
  w.send("CS", "maxAngle", gs::vrml::FieldValue::make<FieldType::SFFloat>(-1.0f));  // unclamped
  w.take();
  turn.rayOrigin = {0.0f, 10.0f, -0.25f};
  w.model->pointer(turn);
  checkRotation(eventOut(w, "CS", "rotation_changed"), {0, 1, 0, 1.5707963f});
}

TEST_CASE("pointer: an Anchor to #Name binds that Viewpoint", "[runtime][pointer][anchor]") {
  RunningWorld w(R"(
DEF V1 Viewpoint {}
DEF V2 Viewpoint { position 0 0 20 }
DEF A Anchor { url "#V2" description "Go far" children DEF SH Shape { geometry Box {} } }
)",
                 3.0);
  w.take();
  const glm::mat4 id(1.0f);
  const auto hit = [&] { return pick(w, {{"A", id}, {"SH", id}}, {0, 0, 1}); };
  CHECK_FALSE(w.model->pointer(along(0, 0, false, hit())));
  CHECK(w.model->pointerHint() == PointerHint{true, "Go far"});
  CHECK(w.model->pointer(along(0, 0, true, hit())));
  CHECK(w.take().empty());
  CHECK_FALSE(w.model->pointer(along(0, 0, false, hit())));
  CHECK(w.take() == Strings{"V1.isBound=FALSE", "V2.isBound=TRUE", "V2.bindTime=3.000"});
  CHECK(w.model->bound(BindableKind::Viewpoint) == &w.node("V2"));
}

TEST_CASE("pointer: an Anchor to a world asks loadUrl, only for a click",
          "[runtime][pointer][anchor]") {
  std::vector<Strings> requests;
  gs::runtime::ExecutionOptions options;
  options.loadUrl = [&](const Strings& url, const Strings& parameter) {
    Strings r = url;
    r.insert(r.end(), parameter.begin(), parameter.end());
    requests.push_back(r);
  };
  RunningWorld w(R"(
DEF A Anchor { url [ "other.wrl" "http://example.org/other.wrl" ] parameter "target=new"
               children DEF SH Shape { geometry Box {} } }
)",
                 0.0, options);
  const glm::mat4 id(1.0f);
  const auto hit = [&] { return pick(w, {{"A", id}, {"SH", id}}, {0, 0, 1}); };
  w.model->pointer(along(0, 0, true, hit()));
  w.model->pointer(along(5, 0, false));  // released elsewhere: no click
  CHECK(requests.empty());
  w.model->pointer(along(0, 0, false, hit()));
  w.model->pointer(along(0, 0, true, hit()));
  w.model->pointer(along(0, 0, false, hit()));
  CHECK(requests ==
        std::vector<Strings>{{"other.wrl", "http://example.org/other.wrl", "target=new"}});
}

TEST_CASE("pointer: a held drag sensor keeps the pointer from other sensors",
          "[runtime][pointer]") {
  RunningWorld w(R"(
DEF G1 Group { children [ DEF PS PlaneSensor {} DEF SH1 Shape { geometry Box {} } ] }
DEF G2 Group { children [ DEF TS TouchSensor {} DEF SH2 Shape { geometry Box {} } ] }
)");
  w.take();
  const glm::mat4 id(1.0f);
  w.model->pointer(along(0, 0, true, pick(w, {{"G1", id}, {"SH1", id}}, {0, 0, 1})));
  w.take();
  w.model->pointer(along(1, 0, true, pick(w, {{"G2", id}, {"SH2", id}}, {1, 0, 1})));
  CHECK(w.take() == Strings{"PS.trackPoint_changed=1 0 1", "PS.translation_changed=1 0 0"});
  w.model->pointer(along(1, 0, false, pick(w, {{"G2", id}, {"SH2", id}}, {1, 0, 1})));
  CHECK(w.take() == Strings{"PS.isActive=FALSE", "PS.offset_changed=1 0 0", "TS.isOver=TRUE",
                            "TS.hitPoint_changed=1 0 1", "TS.hitNormal_changed=0 0 1",
                            "TS.hitTexCoord_changed=0 0"});
}

TEST_CASE("pointer: worlds without sensors need no picking", "[runtime][pointer]") {
  RunningWorld plain("Group { children Shape { geometry Box {} } }");
  CHECK_FALSE(plain.model->wantsPointer());
  RunningWorld touch("Group { children [ TouchSensor {} Shape { geometry Box {} } ] }");
  CHECK(touch.model->wantsPointer());
  RunningWorld anchor("Anchor { url \"x.wrl\" }");
  CHECK(anchor.model->wantsPointer());
}

TEST_CASE("pointer: an Anchor in an Inline's world links under that world's URL and rules",
          "[runtime][pointer][anchor][url]") {
  // A remote Inline in a local world: its Anchor's relative URL is the Inline's file's
  // neighbour, and its local file is refused (before, both took the local world's URL and
  // rules).
  std::vector<Strings> requests;
  gs::runtime::ExecutionOptions options;
  options.loadUrl = [&](const Strings& url, const Strings&) { requests.push_back(url); };
  RunningWorld w("Group { }\n", 0.0, options);
  auto inner = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#VRML V2.0 utf8\nDEF A Anchor { url [ \"file:///home/me/secret.wrl\" \"next.wrl\" ] "
      "children DEF SH Shape { geometry Box { } } }\n",
      "http://example.com/w/inner.wrl"));
  w.model->addInlineScene(inner);
  gs::vrml::Node& anchor = *inner->rootNodes.at(0);
  gs::vrml::Node& shape = *anchor.field("children")->get<FieldType::MFNode>().at(0);
  PickResult hit;
  hit.path.push_back({nullptr, glm::mat4(1.0f), &inner->rootNodes});
  hit.path.push_back({&anchor, glm::mat4(1.0f), nullptr});
  hit.path.push_back({&shape, glm::mat4(1.0f), nullptr});
  hit.point = {0, 0, 1};
  hit.normal = {0, 0, 1};
  w.model->pointer(along(0, 0, true, hit));
  w.model->pointer(along(0, 0, false, hit));
  CHECK(requests == std::vector<Strings>{{"http://example.com/w/next.wrl"}});
  bool refused = false;
  for (const auto& d : w.model->diagnostics().items)
    refused = refused || d.message.find("may only reference http(s) URLs") != std::string::npos;
  CHECK(refused);
}
