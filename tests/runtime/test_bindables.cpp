// Clause 4.6.10: the bindable stacks.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::BindableKind;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

TEST_CASE("bindables: the first of each kind is bound at load", "[runtime][bind]") {
  RunningWorld w(R"(
DEF V1 Viewpoint {}
DEF V2 Viewpoint {}
DEF N NavigationInfo {}
)",
                 5.0);
  CHECK(w.take() ==
        std::vector<std::string>{"V1.isBound=TRUE", "V1.bindTime=5.000", "N.isBound=TRUE"});
  CHECK(w.model->bound(BindableKind::Viewpoint) == &w.node("V1"));
  CHECK(w.model->bound(BindableKind::Fog) == nullptr);
}

TEST_CASE("bindables: set_bind pushes and pops the stack", "[runtime][bind]") {
  RunningWorld w(R"(
DEF V1 Viewpoint {}
DEF V2 Viewpoint {}
DEF V3 Viewpoint {}
)");
  w.take();
  const auto revision = w.model->bindingRevision();
  w.send("V2", "set_bind", FieldValue::make<FieldType::SFBool>(true));
  CHECK(w.take() ==
        std::vector<std::string>{"V1.isBound=FALSE", "V2.isBound=TRUE", "V2.bindTime=0.000"});
  CHECK(w.model->bindingRevision() == revision + 1);
  w.send("V2", "set_bind", FieldValue::make<FieldType::SFBool>(true));  // already bound
  CHECK(w.take().empty());
  w.send("V3", "set_bind", FieldValue::make<FieldType::SFBool>(false));  // not in the stack
  CHECK(w.take().empty());
  w.send("V2", "set_bind", FieldValue::make<FieldType::SFBool>(false));
  CHECK(w.take() ==
        std::vector<std::string>{"V2.isBound=FALSE", "V1.isBound=TRUE", "V1.bindTime=0.000"});
  CHECK(w.model->bindStack(BindableKind::Viewpoint) == std::vector<gs::vrml::Node*>{&w.node("V1")});
}

TEST_CASE("bindables: a viewpoint's own NavigationInfo is bound and unbound with it",
          "[runtime][bind][x3d]") {
  // X3D 4.0 clause 23.3.1 (X_ITE 15 routes isBound to its set_bind). The NavigationInfo
  // in V2's field is no candidate of the graph: N, in the graph, is bound at load.
  RunningWorld w(gs::test::x3dWorld(R"(
DEF V1 Viewpoint {}
DEF V2 Viewpoint { navigationInfo DEF Own NavigationInfo { speed 5 } }
DEF N NavigationInfo {}
)"));
  CHECK(w.model->bound(BindableKind::NavigationInfo) == &w.node("N"));
  w.take();
  w.send("V2", "set_bind", FieldValue::make<FieldType::SFBool>(true));
  CHECK(w.model->bound(BindableKind::NavigationInfo) == &w.node("Own"));
  CHECK(w.take() == std::vector<std::string>{"V1.isBound=FALSE", "V2.isBound=TRUE",
                                             "V2.bindTime=0.000", "N.isBound=FALSE",
                                             "Own.isBound=TRUE", "Own.bindTime=0.000"});
  w.send("V2", "set_bind", FieldValue::make<FieldType::SFBool>(false));
  CHECK(w.model->bound(BindableKind::Viewpoint) == &w.node("V1"));
  CHECK(w.model->bound(BindableKind::NavigationInfo) == &w.node("N"));
}
