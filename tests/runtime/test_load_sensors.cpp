// The X3D LoadSensor (X3D 4.0 clause 9.4.3) in the execution model: the loads reported
// through ExecutionModel::setUrlObjectState (as session::WorldRuntimes reports an Inline's
// or a texture's) drive isActive, isLoaded, loadTime and progress; time moves only by
// advanceTo, so a timeOut passes at an exact time.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::UrlLoadState;
using gs::test::RunningWorld;
using gs::test::WorldText;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;
using LoadEvents = std::vector<std::string>;

namespace {

/// A world of an Inline I and an ImageTexture T (both never loaded by the runtime itself)
/// and `sensor`, the text of a LoadSensor DEFed L, with `more` after it.
RunningWorld loadSensorWorld(const std::string& sensor, const std::string& more = "",
                             double loadTime = 0.0) {
  return RunningWorld(x3dWorld("DEF I Inline { url \"part.x3dv\" }\n"
                               "Shape { appearance Appearance { texture DEF T ImageTexture {\n"
                               "  url \"t.png\" } } geometry Box {} }\n" +
                               sensor + "\n" + more),
                      loadTime);
}

bool loadSensorBool(RunningWorld& w, const std::string& field) {
  return w.node("L").field(field)->get<FieldType::SFBool>();
}

}  // namespace

TEST_CASE("load sensor: an Inline that loads: isActive TRUE, then progress 1, isLoaded, loadTime",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { children USE I }");
  // The world loaded at 0: the sensor watches the Inline, which is on its way.
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  CHECK(loadSensorBool(w, "isActive"));
  w.model->advanceTo(1.0);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loading);  // still on its way
  CHECK(w.take().empty());
  w.model->advanceTo(2.5);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take() ==
        LoadEvents{"L.progress=1", "L.isLoaded=TRUE", "L.loadTime=2.500", "L.isActive=FALSE"});
  CHECK(w.node("L").field("loadTime")->get<FieldType::SFTime>() == 2.5);
  CHECK(w.node("L").field("progress")->get<FieldType::SFFloat>() == 1.0f);
  CHECK(loadSensorBool(w, "isLoaded"));
  CHECK_FALSE(loadSensorBool(w, "isActive"));
  CHECK(w.model->urlObjectState(w.node("I")) == UrlLoadState::loaded);
  // The watch ended: a second report of the same state, or time passing, sends nothing.
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  w.model->advanceTo(10.0);
  CHECK(w.take().empty());
}

TEST_CASE("load sensor: progress is the fraction of the watched nodes loaded",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { children [ USE I USE T ] }");
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  w.model->advanceTo(1.0);
  w.model->setUrlObjectState(w.node("T"), UrlLoadState::loaded);
  CHECK(w.take() == LoadEvents{"L.progress=0.5"});
  w.model->advanceTo(2.0);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take() ==
        LoadEvents{"L.progress=1", "L.isLoaded=TRUE", "L.loadTime=2.000", "L.isActive=FALSE"});
}

TEST_CASE("load sensor: an Inline that fails: isLoaded FALSE, no loadTime",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { children [ USE I USE T ] }");
  w.take();
  w.model->advanceTo(1.0);
  w.model->setUrlObjectState(w.node("T"), UrlLoadState::loaded);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::failed);
  CHECK(w.take() == LoadEvents{"L.progress=0.5", "L.isLoaded=FALSE", "L.isActive=FALSE"});
  CHECK_FALSE(loadSensorBool(w, "isLoaded"));
  CHECK(w.node("L").field("loadTime")->get<FieldType::SFTime>() == 0.0);
}

TEST_CASE("load sensor: timeOut ends the watch with isLoaded FALSE at its time",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { timeOut 2 children USE I }", "", 10.0);
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  CHECK(w.model->animating());  // the timeOut is still to pass
  w.model->advanceBy(1.9, 0.1);
  CHECK(w.take().empty());
  w.model->advanceTo(12.0);  // 10 + 2
  CHECK(w.take() == LoadEvents{"L.isLoaded=FALSE", "L.isActive=FALSE"});
  CHECK_FALSE(w.model->animating());
  // A load after the timeOut is not reported.
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take().empty());
}

TEST_CASE("load sensor: a load before the timeOut wins; timeOut 0 waits for ever",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { timeOut 5 children USE I }");
  w.take();
  w.model->advanceTo(4.0);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take() ==
        LoadEvents{"L.progress=1", "L.isLoaded=TRUE", "L.loadTime=4.000", "L.isActive=FALSE"});
  RunningWorld forever = loadSensorWorld("DEF L LoadSensor { children USE I }");
  forever.take();
  forever.model->advanceTo(1e6);
  CHECK(forever.take().empty());
  CHECK(loadSensorBool(forever, "isActive"));
}

TEST_CASE("load sensor: enabled FALSE watches nothing; TRUE starts a watch that reports at once",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { enabled FALSE timeOut 1 children USE I }");
  CHECK(w.take().empty());
  w.model->advanceTo(5.0);  // no timeOut either
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take().empty());
  CHECK_FALSE(loadSensorBool(w, "isLoaded"));
  // Enabled later, the Inline already loaded: the result at once, never active.
  w.send("L", "enabled", FieldValue::make<FieldType::SFBool>(true));
  CHECK(w.take() == LoadEvents{"L.enabled_changed=TRUE", "L.progress=1", "L.isLoaded=TRUE",
                               "L.loadTime=5.000"});
}

TEST_CASE("load sensor: enabled FALSE while active ends the watch without a result",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w = loadSensorWorld("DEF L LoadSensor { children USE I }");
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  w.model->advanceTo(1.0);
  w.send("L", "enabled", FieldValue::make<FieldType::SFBool>(false));
  CHECK(w.take() == LoadEvents{"L.enabled_changed=FALSE", "L.isActive=FALSE"});
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(w.take().empty());
}

TEST_CASE("load sensor: loaded before the world runs: the result at load, no isActive",
          "[runtime][x3d][load_sensor]") {
  // No watched node a loader reports (an X3DUrlObject GhostSpace does not track counts
  // as loaded; a node that is not an X3DUrlObject is ignored).
  RunningWorld w(x3dWorld("DEF S Script { url \"ecmascript: function initialize() {}\" }\n"
                          "DEF G Group {}\n"
                          "DEF L LoadSensor { children [ USE S USE G ] }\n"),
                 3.0);
  CHECK(w.take() == LoadEvents{"L.progress=1", "L.isLoaded=TRUE", "L.loadTime=3.000"});
}

TEST_CASE("load sensor: empty children (or only nodes without url) send nothing",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w(
      x3dWorld("DEF G Group {}\n"
               "DEF L LoadSensor {}\n"
               "DEF M LoadSensor { children USE G }\n"));
  w.model->advanceTo(1.0);
  CHECK(w.take().empty());
  CHECK_FALSE(loadSensorBool(w, "isActive"));
}

TEST_CASE("load sensor: a new children list starts a new watch", "[runtime][x3d][load_sensor]") {
  RunningWorld w =
      loadSensorWorld("DEF L LoadSensor { children USE I }", "DEF H Group { children USE T }\n");
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  w.model->advanceTo(1.0);
  w.model->setUrlObjectState(w.node("T"), UrlLoadState::loaded);
  CHECK(w.take().empty());  // T is not watched
  // Watching T instead: loaded already, so the watch ends at once.
  const auto& h = w.node("H").field("children")->get<FieldType::MFNode>();
  w.send("L", "children", FieldValue::make<FieldType::MFNode>(h));
  CHECK(w.take() == LoadEvents{"L.children_changed=[T]", "L.progress=1", "L.isLoaded=TRUE",
                               "L.loadTime=1.000", "L.isActive=FALSE"});
}

TEST_CASE("load sensor: X3D 3's watchList is the children field", "[runtime][x3d][load_sensor]") {
  RunningWorld w(
      WorldText{"#X3D V3.3 utf8\nPROFILE Immersive\n"
                "DEF I Inline { url \"part.x3dv\" }\n"
                "DEF L LoadSensor { watchList USE I }\n",
                "test.x3dv"});
  CHECK(w.scene->diagnostics.items.empty());
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::failed);
  CHECK(w.take() == LoadEvents{"L.isLoaded=FALSE", "L.isActive=FALSE"});
}

TEST_CASE("load sensor: a MovieTexture's duration is its load report",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w(
      x3dWorld("DEF M MovieTexture { url \"m.mp4\" }\n"
               "DEF L LoadSensor { children USE M }\n"));
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  w.model->advanceTo(1.0);
  w.model->setMediaDuration(w.node("M"), 4.0);
  // (An X3D MovieTexture is an X3DTimeDependentNode: elapsedTime while it plays.)
  CHECK(w.take() == LoadEvents{"M.duration_changed=4.000", "M.isActive=TRUE", "M.elapsedTime=0.000",
                               "L.progress=1", "L.isLoaded=TRUE", "L.loadTime=1.000",
                               "L.isActive=FALSE"});
  // An unreadable movie (duration -1) fails the watch.
  RunningWorld bad(
      x3dWorld("DEF M MovieTexture { url \"m.mp4\" }\n"
               "DEF L LoadSensor { children USE M }\n"));
  bad.take();
  bad.model->setMediaDuration(bad.node("M"), -1.0);
  const LoadEvents events = bad.take();
  CHECK(events.size() >= 2);
  CHECK(events[events.size() - 2] == "L.isLoaded=FALSE");
  CHECK(events.back() == "L.isActive=FALSE");
}

TEST_CASE("load sensor: ROUTEs from isLoaded drive a Switch through event utilities",
          "[runtime][x3d][load_sensor]") {
  RunningWorld w =
      loadSensorWorld("DEF L LoadSensor { children USE I }",
                      "DEF SW Switch { whichChoice 0 children [ Group {} Group {} ] }\n"
                      "DEF F BooleanFilter {}\n"
                      "DEF IT IntegerTrigger { integerKey 1 }\n"
                      "ROUTE L.isLoaded TO F.set_boolean\n"
                      "ROUTE F.inputTrue TO IT.set_boolean\n"
                      "ROUTE IT.triggerValue TO SW.whichChoice\n");
  auto which = [&] { return w.node("SW").field("whichChoice")->get<FieldType::SFInt32>(); };
  CHECK(w.take() == LoadEvents{"L.isActive=TRUE", "L.progress=0"});
  CHECK(which() == 0);
  w.model->advanceTo(1.0);
  w.model->setUrlObjectState(w.node("I"), UrlLoadState::loaded);
  CHECK(which() == 1);
  const LoadEvents events = w.take();
  CHECK(events == LoadEvents{"L.progress=1", "L.isLoaded=TRUE", "L.loadTime=1.000",
                             "L.isActive=FALSE", "F.inputTrue=TRUE", "F.inputNegate=FALSE",
                             "IT.triggerValue=1", "SW.whichChoice_changed=1"});
}
