// Output events that drawing computed, sent by their nodes (ExecutionModel::
// sendDrawnOutputs): a LOD's level_changed (X3D 4.0 clause 10.4.2) and the level the
// sensors' walks then follow; a GeoLOD's children (25.4.5).
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

vrml::DrawnOutput levelOutput(const vrml::Node& n, int level) {
  return {&n, "level_changed", FieldValue::make<FieldType::SFInt32>(level)};
}

}  // namespace

TEST_CASE("A LOD's level_changed comes from drawing; sensors in the shown level run",
          "[runtime][x3d]") {
  // A ProximitySensor in level 1 around the viewer: it is active only once drawing says
  // level 1 shows (before, the walk knew only the first level).
  RunningWorld w(x3dWorld(R"(
DEF L LOD { range [ 10 ] level [
  Group {}
  DEF P ProximitySensor { size 100 100 100 } ] }
DEF Watch Script { inputOnly SFInt32 level }
ROUTE L.level_changed TO Watch.level
)"));
  runtime::ViewerPose viewer;
  viewer.position = glm::vec3(0.0f, 0.0f, 20.0f);
  w.model->setViewer(viewer);
  w.model->advanceTo(1.0);
  CHECK_FALSE(w.node("P").get<FieldType::SFBool>("isActive", true));
  w.take();
  w.model->sendDrawnOutputs({levelOutput(w.node("L"), 1)});
  CHECK(w.take() == std::vector<std::string>{"L.level_changed=1"});
  w.model->advanceTo(2.0);
  CHECK(w.node("P").get<FieldType::SFBool>("isActive", false));
  // An output of a node not in this world, of a field the node lacks, or of another type
  // is ignored.
  auto stranger = vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\nLOD {}\n", "other.x3dv");
  w.take();
  w.model->sendDrawnOutputs(
      {levelOutput(*stranger.rootNodes.at(0), 0),
       {&w.node("L"), "noSuchField", FieldValue::make<FieldType::SFInt32>(0)},
       {&w.node("L"), "level_changed", FieldValue::make<FieldType::SFFloat>(0)}});
  CHECK(w.take().empty());
  w.model->sendDrawnOutputs({levelOutput(w.node("L"), 0)});
  w.model->advanceTo(3.0);
  CHECK_FALSE(w.node("P").get<FieldType::SFBool>("isActive", true));
}

TEST_CASE("A GeoLOD's children output is what the sensors' walk follows",
          "[runtime][x3d][geospatial]") {
  // The children drawing says the GeoLOD shows hold a ProximitySensor around the viewer.
  RunningWorld w(x3dWorld(R"(
DEF G GeoLOD { geoSystem [ "GC" ] range 100 }
)"));
  auto tile = std::make_shared<vrml::Scene>(vrml::parseVrml(
      "#X3D V4.0 utf8\nPROFILE Full\nDEF Q ProximitySensor { size 100 100 100 }\n", "tile.x3dv"));
  w.model->addInlineScene(tile);  // the tile's file, loaded for the GeoLOD's child
  w.model->setViewer({});
  w.model->advanceTo(1.0);
  const vrml::Node& sensor = *tile->rootNodes.at(0);
  CHECK_FALSE(sensor.get<FieldType::SFBool>("isActive", true));
  w.model->sendDrawnOutputs(
      {{&w.node("G"), "children", FieldValue::make<FieldType::MFNode>(tile->rootNodes)}});
  CHECK(w.node("G").mfnode("children").size() == 1);
  w.model->advanceTo(2.0);
  CHECK(sensor.get<FieldType::SFBool>("isActive", false));
}
