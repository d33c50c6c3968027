// X3D Layering (X3D 4.0 clause 35): nodes inside a LayerSet's Layers take part in the
// execution model as root nodes do (TimeSensors run, ROUTEs deliver).
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::BindableKind;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;

TEST_CASE("Layering: a TimeSensor and an interpolator inside a Layer animate its Transform",
          "[runtime][layering]") {
  RunningWorld w(x3dWorld(R"(PROFILE Immersive
COMPONENT Layering:1
LayerSet {
  order [0 1]
  layers Layer {
    viewport Viewport { clipBoundary [0 0.5 0 1] }
    children [
      DEF LV Viewpoint { position 0 0 50 }
      DEF T TimeSensor { cycleInterval 4 loop TRUE }
      DEF P PositionInterpolator { key [0 1] keyValue [0 0 0, 4 0 0] }
      DEF X Transform { children Shape { geometry Box {} } }
    ]
  }
}
ROUTE T.fraction_changed TO P.set_fraction
ROUTE P.value_changed TO X.set_translation
)"),
                 0.0);
  // Every layer is seen through the world's camera: the Layer's Viewpoint is not bound.
  CHECK(w.model->bound(BindableKind::Viewpoint) == nullptr);
  w.model->advanceTo(1.0);
  CHECK(w.node("X").field("translation")->get<FieldType::SFVec3f>().x == Approx(1.0f));
  w.model->advanceTo(3.0);
  CHECK(w.node("X").field("translation")->get<FieldType::SFVec3f>().x == Approx(3.0f));
}
