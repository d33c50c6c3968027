// X3D Geospatial in the execution model (X3D 4.0 clause 25): GeoPositionInterpolator's two
// outputs and GeoViewpoint's stack.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

TEST_CASE("geospatial: a GeoPositionInterpolator sends geo and local coordinates",
          "[runtime][x3d][geospatial]") {
  RunningWorld w(x3dWorld(R"(
DEF GPI GeoPositionInterpolator {
  geoOrigin GeoOrigin { geoCoords 45 -80 0 rotateYUp TRUE }
  key [ 0 1 ] keyValue [ 45 -80 0, 45 -80 1000 ]
}
DEF T Transform {}
ROUTE GPI.value_changed TO T.set_translation
)"),
                 0.0);
  w.take();
  w.send("GPI", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  const glm::vec3 t = w.node("T").field("translation")->get<FieldType::SFVec3f>();
  CHECK(t.x == Approx(0.0f).margin(1e-3));
  CHECK(t.y == Approx(500.0f).margin(1e-2));
  CHECK(t.z == Approx(0.0f).margin(1e-3));
  const auto events = w.take();
  CHECK(std::any_of(events.begin(), events.end(), [](const std::string& e) {
    return e.rfind("GPI.geovalue_changed=45 -80 500", 0) == 0;
  }));
  // A keyValue that does not match the keys: one error, no output.
  RunningWorld bad(x3dWorld("DEF GPI GeoPositionInterpolator { key [ 0 1 ] keyValue [ 1 2 3 ] }"),
                   0.0);
  bad.take();
  bad.send("GPI", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(bad.take().empty());
  CHECK(bad.model->diagnostics().items.size() == 1);
}

TEST_CASE("geospatial: a GeoViewpoint is on the viewpoint stack", "[runtime][x3d][geospatial]") {
  RunningWorld w(x3dWorld(R"(
DEF GV GeoViewpoint { position 45 -80 1000 }
)"),
                 0.0);
  CHECK(w.model->bound(gs::runtime::BindableKind::Viewpoint) == &w.node("GV"));
}
