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
